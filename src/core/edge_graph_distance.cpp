#include "core/edge_graph_distance.h"

#include <functional>
#include <limits>
#include <queue>

namespace liftmap {

std::vector<double> edge_graph_distances(const Mesh& mesh, const Eigen::MatrixXd& V,
                                         const std::vector<VertexId>& sources) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(static_cast<size_t>(mesh.n_vertices()), inf);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P = V;
  for (const VertexId s : sources) {
    dist[static_cast<size_t>(s.idx)] = 0;
    queue.emplace(0.0, s.idx);
  }
  while (!queue.empty()) {
    const double d = queue.top().first;
    const int u = queue.top().second;
    queue.pop();
    if (d > dist[static_cast<size_t>(u)]) continue;
    mesh.for_each_outgoing(VertexId(u), [&](HalfedgeId h) {
      const int w = mesh.head(h).idx;
      const double nd = d + (P.row(w) - P.row(u)).norm();
      if (nd < dist[static_cast<size_t>(w)]) {
        dist[static_cast<size_t>(w)] = nd;
        queue.emplace(nd, w);
      }
    });
  }
  return dist;
}

}  // namespace liftmap
