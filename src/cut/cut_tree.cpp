#include "cut/cut_tree.h"

#include <limits>

namespace liftmap {

std::vector<std::array<int, 2>> minimum_spanning_tree(const Eigen::MatrixXd& W) {
  const int k = static_cast<int>(W.rows());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<char> in_tree(static_cast<size_t>(k), 0);
  std::vector<double> best(static_cast<size_t>(k), inf);
  std::vector<int> parent(static_cast<size_t>(k), 0);
  std::vector<std::array<int, 2>> edges;
  in_tree[0] = 1;
  for (int j = 1; j < k; ++j) best[static_cast<size_t>(j)] = W(0, j);
  for (int step = 1; step < k; ++step) {
    int next = -1;
    for (int j = 0; j < k; ++j) {
      if (!in_tree[static_cast<size_t>(j)] &&
          (next < 0 || best[static_cast<size_t>(j)] < best[static_cast<size_t>(next)])) {
        next = j;
      }
    }
    in_tree[static_cast<size_t>(next)] = 1;
    edges.push_back({parent[static_cast<size_t>(next)], next});
    for (int j = 0; j < k; ++j) {
      if (!in_tree[static_cast<size_t>(j)] && W(next, j) < best[static_cast<size_t>(j)]) {
        best[static_cast<size_t>(j)] = W(next, j);
        parent[static_cast<size_t>(j)] = next;
      }
    }
  }
  return edges;
}

std::vector<std::array<int, 2>> path_tree(const Eigen::MatrixXd& W) {
  const int k = static_cast<int>(W.rows());
  int a = 0, b = 1;
  for (int i = 0; i < k; ++i) {
    for (int j = i + 1; j < k; ++j) {
      if (W(i, j) < W(a, b)) a = i, b = j;
    }
  }
  std::vector<char> used(static_cast<size_t>(k), 0);
  used[static_cast<size_t>(a)] = used[static_cast<size_t>(b)] = 1;
  std::vector<std::array<int, 2>> edges{{a, b}};
  std::array<int, 2> ends{a, b};
  for (int step = 2; step < k; ++step) {
    int best_end = 0, best_j = -1;
    for (int e = 0; e < 2; ++e) {
      for (int j = 0; j < k; ++j) {
        if (used[static_cast<size_t>(j)]) continue;
        if (best_j < 0 || W(ends[static_cast<size_t>(e)], j) < W(ends[static_cast<size_t>(best_end)], best_j)) {
          best_end = e, best_j = j;
        }
      }
    }
    used[static_cast<size_t>(best_j)] = 1;
    edges.push_back({ends[static_cast<size_t>(best_end)], best_j});
    ends[static_cast<size_t>(best_end)] = best_j;
  }
  return edges;
}

}  // namespace liftmap
