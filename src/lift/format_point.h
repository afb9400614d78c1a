#pragma once
/// Planar points as text, for the messages of the lifting stage.

#include <Eigen/Core>
#include <string>

namespace liftmap {

/// `p` as "(x, y)" with 17 significant digits, so that the coordinates a message names round-trip exactly.
std::string format_point(const Eigen::Vector2d& p);

}  // namespace liftmap
