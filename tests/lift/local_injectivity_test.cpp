#include "lift/local_injectivity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "lift_fixtures.h"

namespace liftmap {
namespace {

using testing::FlatDisk;

/// A disk around a centre vertex whose rings wind `turns` times: centre, then rings of `turns * k` vertices at
/// radii 1 and 2 (the outer ring is the boundary). turns = 2 gives a branch point at the centre.
FlatDisk wound_disk(int k, int turns) {
  const int n = turns * k;
  FlatDisk d;
  d.X.resize(1 + 2 * n, 2);
  d.X.row(0) << 0, 0;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / k;
    d.X.row(1 + i) << std::cos(a), std::sin(a);
    d.X.row(1 + n + i) << 2 * std::cos(a), 2 * std::sin(a);
  }
  d.F.resize(3 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    d.F.row(3 * i) << 0, 1 + i, 1 + j;
    d.F.row(3 * i + 1) << 1 + i, 1 + n + i, 1 + n + j;
    d.F.row(3 * i + 2) << 1 + i, 1 + n + j, 1 + j;
  }
  return d;
}

TEST(LiftLocalInjectivity, GridAndOverlappingSpiralPass) {
  const FlatDisk grid = testing::grid_disk(5, 4, true);
  EXPECT_TRUE(check_local_injectivity(Mesh(grid.F, 30), grid.X).locally_injective());
  // Winds 2.3 times around the annulus: globally overlapping, locally injective.
  const FlatDisk spiral = testing::spiral_strip(5, 150, 2.3, 0.3);
  const auto report = check_local_injectivity(Mesh(spiral.F, static_cast<int>(spiral.X.rows())), spiral.X);
  EXPECT_TRUE(report.locally_injective()) << report.summary(spiral.X);
  const FlatDisk once = wound_disk(12, 1);
  EXPECT_TRUE(check_local_injectivity(Mesh(once.F, static_cast<int>(once.X.rows())), once.X).locally_injective());
}

TEST(LiftLocalInjectivity, FlippedFaceIsReported) {
  FlatDisk grid = testing::grid_disk(4, 4, true);
  grid.X.row(2 * 5 + 2) << 3.5, 2.2;  // interior vertex (2, 2) pushed over its neighbour (3, 2)
  const auto report = check_local_injectivity(Mesh(grid.F, 25), grid.X);
  EXPECT_FALSE(report.locally_injective());
  EXPECT_FALSE(report.flipped_faces.empty());
  EXPECT_NE(report.summary(grid.X).find("flipped"), std::string::npos);
}

TEST(LiftLocalInjectivity, BranchPointIsReported) {
  const FlatDisk d = wound_disk(10, 2);  // every face is counter-clockwise, the centre's ring winds twice
  const Mesh mesh(d.F, static_cast<int>(d.X.rows()));
  const auto report = check_local_injectivity(mesh, d.X);
  EXPECT_TRUE(report.flipped_faces.empty());
  ASSERT_EQ(report.bad_interior_vertices.size(), 1u);
  EXPECT_EQ(report.bad_interior_vertices[0], VertexId(0));
}

TEST(LiftLocalInjectivity, BoundaryAngleOfTwoPiOrMoreIsReported) {
  for (const double sweep : {1.5 * std::numbers::pi, 2.0 * std::numbers::pi, 2.5 * std::numbers::pi}) {
    // Fan of a boundary vertex at the origin over `sweep`; the last spoke of the 2 pi fan repeats the first.
    const int n = 12;
    FlatDisk d;
    d.X.resize(n + 2, 2);
    d.X.row(0) << 0, 0;
    for (int i = 0; i <= n; ++i) {
      const double a = sweep * i / n;
      d.X.row(1 + i) << std::cos(a), std::sin(a);
    }
    if (sweep == 2.0 * std::numbers::pi) d.X.row(1 + n) = d.X.row(1);
    d.F.resize(n, 3);
    for (int i = 0; i < n; ++i) d.F.row(i) << 0, 1 + i, 2 + i;
    const auto report = check_local_injectivity(Mesh(d.F, n + 2), d.X);
    EXPECT_TRUE(report.flipped_faces.empty());
    EXPECT_EQ(report.bad_boundary_vertices.size(), sweep < 2.0 * std::numbers::pi ? 0u : 1u) << sweep;
  }
}

TEST(LiftLocalInjectivity, WrongShapeThrows) {
  const FlatDisk grid = testing::grid_disk(2, 2, true);
  EXPECT_THROW(check_local_injectivity(Mesh(grid.F, 9), Eigen::MatrixXd::Zero(8, 2)), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
