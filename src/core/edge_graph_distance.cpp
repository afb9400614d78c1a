#include "core/edge_graph_distance.h"

namespace liftmap {

std::vector<double> edge_graph_distances(const Mesh& mesh, const Eigen::MatrixXd& V,
                                         const std::vector<VertexId>& sources) {
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P = V;
  std::vector<int> ids;
  ids.reserve(sources.size());
  for (const VertexId s : sources) ids.push_back(s.idx);
  std::vector<double> dist;
  edge_graph_search(
      mesh, ids, [&](int u, int w) { return (P.row(w) - P.row(u)).norm(); }, [](int, int, double) { return true; },
      dist);
  return dist;
}

}  // namespace liftmap
