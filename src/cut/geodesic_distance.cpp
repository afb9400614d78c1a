#include "cut/geodesic_distance.h"

#include "core/parallel_for_each.h"

namespace liftmap {

std::vector<double> edge_graph_distances(const Mesh& mesh, const Eigen::MatrixXd& V, VertexId source) {
  return edge_graph_distances(mesh, V, std::vector<VertexId>{source});
}

Eigen::MatrixXd landmark_distances(const Mesh& mesh, const Eigen::MatrixXd& V, const std::vector<VertexId>& landmarks) {
  const int k = static_cast<int>(landmarks.size());
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(k, k);
  // One search per landmark, each filling its own row: on every thread available.
  parallel_for_each(k, k, [&](int i) {
    const auto dist = edge_graph_distances(mesh, V, landmarks[static_cast<size_t>(i)]);
    for (int j = 0; j < k; ++j) D(i, j) = dist[static_cast<size_t>(landmarks[static_cast<size_t>(j)].idx)];
  });
  return 0.5 * (D + D.transpose());
}

}  // namespace liftmap
