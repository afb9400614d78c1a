#include "cut/geodesic_path.h"

#include <gtest/gtest.h>

#include "cut_test_util.h"
#include "exact_geodesic.h"

namespace liftmap {
namespace {

TEST(cut_exact_geodesic, FlatSquare) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  const auto d = exact_geodesic_distances(V, F, 0, {1, 2, 3});
  EXPECT_NEAR(d[0], 1.0, 1e-12);
  EXPECT_NEAR(d[1], std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(d[2], 1.0, 1e-12);
}

// The first tree path (two landmarks, nothing in the way; later paths are constrained by the cut) is within 0.5% of the
// exact geodesic distance.
void expect_near_geodesic(const char* name, unsigned seed, int pairs, double* worst) {
  const auto m = test::load(name);
  std::mt19937 rng(seed);
  for (int i = 0; i < pairs; ++i) {
    const auto l = test::landmark_set(m, 2, test::Pattern::kRandom, rng);
    const CutResult r = cut_meshes(m.V, m.F, m.V, m.F, l, l);
    const double exact = exact_geodesic_distances(m.V, m.F, l[0].idx, {l[1].idx})[0];
    const double ratio = r.a.path_lengths[0] / exact;
    *worst = std::max(*worst, ratio);
    EXPECT_LT(ratio, 1.005) << name << " " << l[0].idx << "-" << l[1].idx;
    EXPECT_GT(ratio, 1.0 - 1e-9) << name << " " << l[0].idx << "-" << l[1].idx;
  }
}

// Straightening steps on an edge path: each step keeps an edge path between the same ends, never gets longer,
// and keeps every new vertex on the surface.
TEST(cut_geodesic_path, StepsShortenEdgePaths) {
  const auto m = test::load("hand");
  const Mesh input(m.F, static_cast<int>(m.V.rows()));
  RefinedMesh r = make_refined_mesh(input, m.V);
  const int a = 17, b = 900;
  // Edge path from a to b, descending the edge-graph distance to b.
  const auto d = edge_graph_distances(input, m.V, VertexId(b));
  std::vector<int> path{a};
  while (path.back() != b) {
    int next = path.back();
    input.for_each_outgoing(VertexId(path.back()), [&](HalfedgeId h) {
      const int w = input.head(h).idx;
      if (d[static_cast<size_t>(w)] < d[static_cast<size_t>(next)]) next = w;
    });
    path.push_back(next);
  }
  const auto length = [&](const std::vector<int>& p) {
    double l = 0;
    for (size_t i = 0; i + 1 < p.size(); ++i)
      l += (r.positions[static_cast<size_t>(p[i + 1])] - r.positions[static_cast<size_t>(p[i])]).norm();
    return l;
  };
  const double edge_length = length(path);
  double previous = edge_length;
  for (int step = 0; step < 6; ++step) {
    path = shorten_path(r, input, path, [](int) { return false; });
    ASSERT_EQ(path.front(), a);
    ASSERT_EQ(path.back(), b);
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      ASSERT_TRUE(find_halfedge(r.mesh, VertexId(path[i]), VertexId(path[i + 1])).valid());
    }
    EXPECT_LE(length(path), previous * (1 + 1e-12));
    previous = length(path);
  }
  EXPECT_LT(previous, edge_length);
  const double exact = exact_geodesic_distances(m.V, m.F, a, {b})[0];
  EXPECT_LT(previous / exact, 1.01);
  EXPECT_EQ(r.mesh.euler_characteristic(), 2);
}

TEST(cut_geodesic_path, WithinHalfPercentOfExact) {
  double worst = 0;
  expect_near_geodesic("cow", 1, 6, &worst);
  expect_near_geodesic("hand", 2, 6, &worst);
  expect_near_geodesic("triceratops", 3, 6, &worst);
  expect_near_geodesic("camel", 4, 2, &worst);
  RecordProperty("worst_ratio", std::to_string(worst));
  std::printf("worst length / exact: %.5f\n", worst);
}

}  // namespace
}  // namespace liftmap
