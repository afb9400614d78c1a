#pragma once
/// Fast approximate geodesic distances between landmarks, used to choose the cut tree (paper §3.4).

#include <Eigen/Core>
#include <vector>

#include "core/edge_graph_distance.h"
#include "core/mesh.h"

namespace liftmap {

/// Shortest-path distances along mesh edges from `source` to every vertex (edge_graph_distances with one source);
/// good enough to rank landmark pairs.
/// \param mesh connectivity
/// \param V #V by 3 positions
/// \return #V distances (infinity for unreachable vertices)
std::vector<double> edge_graph_distances(const Mesh& mesh, const Eigen::MatrixXd& V, VertexId source);

/// k by k symmetric matrix of approximate geodesic distances between the landmarks (edge-graph distances).
/// One search per landmark, on the calling thread's OpenMP threads; the result does not depend on their number.
/// \pre landmarks are distinct valid vertices of a connected mesh.
Eigen::MatrixXd landmark_distances(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& landmarks);

}  // namespace liftmap
