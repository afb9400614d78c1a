#pragma once
/// Shortest-path distances along mesh edges (Dijkstra).

#include <Eigen/Core>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// Shortest-path distances along mesh edges (Dijkstra) from the nearest of `sources` to every vertex: an upper
/// bound of the geodesic distance, typically a few percent above it. For adjacent vertices i, j the distances
/// satisfy |d_i - d_j| <= |x_i - x_j|.
/// \param mesh connectivity
/// \param V #V by 3 positions
/// \param sources valid vertices of mesh (at distance 0)
/// \return #V distances (infinity for vertices no source reaches)
std::vector<double> edge_graph_distances(const Mesh& mesh, const Eigen::MatrixXd& V,
                                         const std::vector<VertexId>& sources);

}  // namespace liftmap
