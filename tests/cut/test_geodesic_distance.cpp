#include "cut/geodesic_distance.h"

#include <gtest/gtest.h>

#include "cut_test_util.h"
#include "exact_geodesic.h"

namespace liftmap {
namespace {

// Edge-graph distances bound the exact geodesic distances from above, and not by much (they only rank pairs).
TEST(cut_geodesic_distance, UpperBoundOfExactDistances) {
  const auto m = test::load("cow");
  const Mesh mesh(m.F, static_cast<int>(m.V.rows()));
  const std::vector<VertexId> l{VertexId(3), VertexId(700), VertexId(1500), VertexId(2800)};
  const Eigen::MatrixXd D = landmark_distances(mesh, m.V, l);
  ASSERT_EQ(D.rows(), 4);
  std::vector<int> targets;
  for (const VertexId v : l) targets.push_back(v.idx);
  const auto exact = exact_geodesic_distances(m.V, m.F, l[0].idx, targets);
  for (int j = 0; j < 4; ++j) {
    EXPECT_DOUBLE_EQ(D(j, j), 0.0);
    EXPECT_DOUBLE_EQ(D(0, j), D(j, 0));
    EXPECT_GE(D(0, j), exact[static_cast<size_t>(j)] * (1 - 1e-9));
    EXPECT_LE(D(0, j), exact[static_cast<size_t>(j)] * 1.2);
  }
}

}  // namespace
}  // namespace liftmap
