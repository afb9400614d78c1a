#include "cut/cut_tree.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace liftmap {
namespace {

Eigen::MatrixXd random_weights(int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd P(k, 2);
  for (int i = 0; i < k; ++i) P.row(i) << u(rng), u(rng);
  Eigen::MatrixXd W(k, k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) W(i, j) = (P.row(i) - P.row(j)).norm();
  }
  return W;
}

// Every edge attaches a new landmark to the tree built so far, and all k landmarks are reached.
void expect_traceable_tree(const std::vector<std::array<int, 2>>& edges, int k) {
  ASSERT_EQ(static_cast<int>(edges.size()), k - 1);
  std::set<int> in{edges[0][0]};
  for (const auto& e : edges) {
    EXPECT_EQ(in.count(e[0]), 1u);
    EXPECT_TRUE(in.insert(e[1]).second);
  }
  EXPECT_EQ(static_cast<int>(in.size()), k);
}

TEST(cut_tree, MinimumSpanningTreeIsMinimal) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    const int k = 2 + static_cast<int>(seed);
    const Eigen::MatrixXd W = random_weights(k, seed);
    const auto edges = minimum_spanning_tree(W);
    expect_traceable_tree(edges, k);
    // Cut property: each tree edge is the lightest edge across the cut it defines (checked by brute force
    // against every non-tree edge closing a cycle through it is costly; compare total weight with Kruskal).
    std::vector<std::array<int, 2>> all;
    for (int i = 0; i < k; ++i) {
      for (int j = i + 1; j < k; ++j) all.push_back({i, j});
    }
    std::sort(all.begin(), all.end(), [&](auto x, auto y) { return W(x[0], x[1]) < W(y[0], y[1]); });
    std::vector<int> root(static_cast<size_t>(k));
    for (int i = 0; i < k; ++i) root[static_cast<size_t>(i)] = i;
    const auto find = [&](int x) {
      while (root[static_cast<size_t>(x)] != x) x = root[static_cast<size_t>(x)];
      return x;
    };
    double kruskal = 0, prim = 0;
    for (const auto& e : all) {
      const int ra = find(e[0]), rb = find(e[1]);
      if (ra != rb) root[static_cast<size_t>(ra)] = rb, kruskal += W(e[0], e[1]);
    }
    for (const auto& e : edges) prim += W(e[0], e[1]);
    EXPECT_NEAR(prim, kruskal, 1e-12);
  }
}

TEST(cut_tree, PathTreeHasMaximumDegreeTwo) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    const int k = 2 + static_cast<int>(seed);
    const auto edges = path_tree(random_weights(k, seed));
    expect_traceable_tree(edges, k);
    std::vector<int> degree(static_cast<size_t>(k), 0);
    for (const auto& e : edges) ++degree[static_cast<size_t>(e[0])], ++degree[static_cast<size_t>(e[1])];
    for (const int d : degree) EXPECT_LE(d, 2);
  }
}

}  // namespace
}  // namespace liftmap
