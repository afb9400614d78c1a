#pragma once
/// The combinatorial cut tree over the landmarks (paper §3.4: minimum spanning tree with weights
/// dist_M(i, j) + dist_N(i, j)).

#include <Eigen/Core>
#include <array>
#include <vector>

namespace liftmap {

/// Minimum spanning tree of the complete graph with weights W (Prim's algorithm from landmark 0).
/// \param W k by k symmetric weights, k >= 2
/// \return k - 1 edges {parent, child}; every parent is landmark 0 or the child of an earlier edge, so the
///         edges can be traced in order, each attaching a new landmark to the tree built so far.
std::vector<std::array<int, 2>> minimum_spanning_tree(const Eigen::MatrixXd& W);

/// A tree of maximum degree 2 (a path through all landmarks) by nearest-neighbour growth at both ends,
/// starting from the lightest edge. Same edge order convention as `minimum_spanning_tree`.
/// \param W k by k symmetric weights, k >= 2
std::vector<std::array<int, 2>> path_tree(const Eigen::MatrixXd& W);

}  // namespace liftmap
