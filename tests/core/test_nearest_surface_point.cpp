#include "core/nearest_surface_point.h"

#include <gtest/gtest.h>

#include "common/test_meshes.h"

namespace liftmap {
namespace {

// Every region of the plane around a triangle: inside, beyond each side, beyond each corner. The coordinates of a
// point on a side or at a corner have exact zeros.
TEST(NearestSurfacePoint, TriangleRegionsGiveExactZeros) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  const auto near = [&](double x, double y, double z) { return nearest_in_triangle({x, y, z}, a, b, c); };
  EXPECT_EQ(near(-1, -1, 3), (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(near(3, -1, 0), (std::array<double, 3>{0, 1, 0}));
  EXPECT_EQ(near(-1, 5, -1), (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(near(0.5, -3, 1), (std::array<double, 3>{0.75, 0.25, 0}));  // below side a-b
  EXPECT_EQ(near(-3, 0.5, 1), (std::array<double, 3>{0.75, 0, 0.25}));  // left of side a-c
  const auto bc = near(2, 2, 0);                                        // beyond side b-c, at its midpoint
  EXPECT_EQ(bc[0], 0.0);
  EXPECT_DOUBLE_EQ(bc[1], 0.5);
  const auto inside = near(0.5, 0.5, 7);
  EXPECT_DOUBLE_EQ(inside[1], 0.25);
  EXPECT_DOUBLE_EQ(inside[2], 0.25);
  EXPECT_DOUBLE_EQ(inside[0], 0.5);
}

TEST(NearestSurfacePoint, LocatesPointsOnAndOffAnOctahedron) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  const SurfaceLocator locator(oct.V, oct.F);
  // On face 0 (x + y + z = 1): itself.
  const NearestSurfacePoint on = locator.nearest({0.2, 0.3, 0.5});
  EXPECT_EQ(on.face, 0);
  EXPECT_LT(on.distance, 1e-15);
  EXPECT_LT(
      (testing::position(oct, SurfacePoint::in_face(FaceId(on.face), on.bary)) - Eigen::Vector3d(0.2, 0.3, 0.5)).norm(),
      1e-15);
  // Off it along the normal: the centroid of face 0.
  const NearestSurfacePoint off = locator.nearest({2, 2, 2});
  EXPECT_EQ(off.face, 0);
  EXPECT_NEAR(off.distance, std::sqrt(3.0) * (2 - 1.0 / 3), 1e-14);
  // Beyond vertex 0 (1, 0, 0): that vertex, exactly.
  const NearestSurfacePoint tip = locator.nearest({3, 0, 0});
  int ones = 0;
  for (int k = 0; k < 3; ++k) {
    if (tip.bary[static_cast<size_t>(k)] == 1.0) {
      ++ones;
      EXPECT_EQ(oct.F(tip.face, k), 0);
    }
  }
  EXPECT_EQ(ones, 1);
  EXPECT_DOUBLE_EQ(tip.distance, 2.0);
}

}  // namespace
}  // namespace liftmap
