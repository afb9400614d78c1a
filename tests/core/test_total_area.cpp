#include "core/total_area.h"

#include <gtest/gtest.h>

#include "common/test_meshes.h"

namespace liftmap {
namespace {

TEST(TotalArea, UnitCubeSurface) {
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Eigen::MatrixXi F(12, 3);
  F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7;
  EXPECT_DOUBLE_EQ(total_area(V, F), 6.0);
  EXPECT_EQ(total_area(V, Eigen::MatrixXi(0, 3)), 0.0);
}

TEST(TotalArea, ScalesWithTheSquareOfTheMeshSize) {
  for (const char* name : {"cow.off", "camel.off"}) {
    const TriangleMesh m = testing::read_demo_mesh(name);
    const double a = total_area(m.V, m.F);
    EXPECT_GT(a, 0) << name;
    EXPECT_NEAR(total_area(3.0 * m.V, m.F), 9.0 * a, 1e-12 * a) << name;
  }
}

}  // namespace
}  // namespace liftmap
