#pragma once
/// Shortest-path distances along mesh edges (Dijkstra).

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "core/mesh.h"

namespace liftmap {

/// Dijkstra's shortest paths along mesh edges from `sources`, with the caller's edge lengths and a filter.
/// \param length length(u, w) >= 0 of the edge from u to w
/// \param relax relax(u, w, d): whether w may be reached from u at distance d (false: w is not entered through
///        u; the caller may record the arrival)
/// \param dist out: #V distances (infinity where not reached); \param pred out (if not null): #V predecessors
///        (-1 at sources and unreached vertices)
template <class Length, class Relax>
void edge_graph_search(const Mesh& mesh, const std::vector<int>& sources, Length&& length, Relax&& relax,
                       std::vector<double>& dist, std::vector<int>* pred = nullptr) {
  const auto n = static_cast<size_t>(mesh.n_vertices());
  dist.assign(n, std::numeric_limits<double>::infinity());
  if (pred != nullptr) pred->assign(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (const int s : sources) {
    dist[static_cast<size_t>(s)] = 0;
    queue.emplace(0.0, s);
  }
  while (!queue.empty()) {
    const double d = queue.top().first;  // no structured binding: lambdas capture it only from clang 16
    const int u = queue.top().second;
    queue.pop();
    if (d > dist[static_cast<size_t>(u)]) continue;
    mesh.for_each_outgoing(VertexId(u), [&](HalfedgeId h) {
      const int w = mesh.head(h).idx;
      const double nd = d + length(u, w);
      if (nd < dist[static_cast<size_t>(w)] && relax(u, w, nd)) {
        dist[static_cast<size_t>(w)] = nd;
        if (pred != nullptr) (*pred)[static_cast<size_t>(w)] = u;
        queue.emplace(nd, w);
      }
    });
  }
}

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
