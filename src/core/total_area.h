#pragma once
/// Surface area of a triangle mesh.

#include <Eigen/Core>

namespace liftmap {

/// Sum of the areas of the faces of (V, F), in the order of the rows of F.
/// \param V #V by 3 positions
/// \param F #F by 3 faces (indices into V)
double total_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace liftmap
