#include "lift/disk_overlay.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/test_meshes.h"
#include "lift_fixtures.h"

namespace liftmap {
namespace {

using testing::FlatPair;

double doubled_area(const Eigen::MatrixXd& X, int i, int j, int k) {
  const Eigen::Vector2d u = (X.row(j) - X.row(i)).transpose(), v = (X.row(k) - X.row(i)).transpose();
  return u.x() * v.y() - u.y() * v.x();
}

/// The overlay of a pair and the invariants every overlay has: its vertices lie at one planar point on both
/// disks and f takes one to the other, its triangles are counter-clockwise and tile every face of both disks
/// exactly, and it is itself a disk (manifold, consistently oriented, Euler characteristic 1).
DiskOverlay checked_overlay(const FlatPair& p) {
  const Mesh m(p.m.F, static_cast<int>(p.m.X.rows()));
  const Mesh n(p.n.F, static_cast<int>(p.n.X.rows()));
  const LiftedBijection lift(m, p.m.X, n, p.n.X, p.nu);
  const DiskOverlay o = overlay_disks(lift, m, p.m.X, n, p.n.X);
  const double scale = (p.m.X.colwise().maxCoeff() - p.m.X.colwise().minCoeff()).norm();
  const auto nv = static_cast<int>(o.on_m.size());
  Eigen::MatrixXd X(nv, 2);
  for (int v = 0; v < nv; ++v) {
    const Eigen::RowVectorXd xm = interpolate(m, p.m.X, o.on_m[static_cast<size_t>(v)]);
    const Eigen::RowVectorXd xn = interpolate(n, p.n.X, o.on_n[static_cast<size_t>(v)]);
    const Eigen::RowVectorXd xf = interpolate(n, p.n.X, lift.evaluate_f(o.on_m[static_cast<size_t>(v)]));
    EXPECT_LT((xm - xn).norm(), 1e-13 * scale) << "vertex " << v;
    EXPECT_LT((xf - xn).norm(), 1e-13 * scale) << "vertex " << v;
    X.row(v) = xm;
  }
  Eigen::VectorXd area_m = Eigen::VectorXd::Zero(m.n_faces()), area_n = Eigen::VectorXd::Zero(n.n_faces());
  Eigen::MatrixXi F(static_cast<Eigen::Index>(o.triangles.size()), 3);
  for (size_t t = 0; t < o.triangles.size(); ++t) {
    const auto& c = o.triangles[t];
    F.row(static_cast<Eigen::Index>(t)) << c[0], c[1], c[2];
    const double a = doubled_area(X, c[0], c[1], c[2]);
    EXPECT_GT(a, 0) << "triangle " << t;
    area_m(o.face_m[t]) += a;
    area_n(o.face_n[t]) += a;
  }
  // Corners are rounded at the scale of the whole flattening: areas are exact to a fraction of the mean face's.
  const double mean_m = area_m.sum() / m.n_faces(), mean_n = area_n.sum() / n.n_faces();
  for (int f = 0; f < m.n_faces(); ++f) {
    const double a = doubled_area(p.m.X, p.m.F(f, 0), p.m.F(f, 1), p.m.F(f, 2));
    EXPECT_NEAR(area_m(f), a, 1e-12 * (a + mean_m)) << "face " << f << " of M^";
  }
  for (int f = 0; f < n.n_faces(); ++f) {
    const double a = doubled_area(p.n.X, p.n.F(f, 0), p.n.F(f, 1), p.n.F(f, 2));
    EXPECT_NEAR(area_n(f), a, 1e-12 * (a + mean_n)) << "face " << f << " of N^";
  }
  const Mesh overlay(F, nv);  // throws if not manifold or not consistently oriented
  EXPECT_EQ(overlay.euler_characteristic(), 1);
  EXPECT_EQ(overlay.boundary_loops().size(), 1U);
  return o;
}

TEST(DiskOverlay, SquareWithCrossingDiagonalsHasFiveVerticesAndFourTriangles) {
  FlatPair p{testing::grid_disk(1, 1, true), testing::grid_disk(1, 1, false), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const DiskOverlay o = checked_overlay(p);
  EXPECT_EQ(o.on_m.size(), 5U);
  EXPECT_EQ(o.triangles.size(), 4U);
  int crossings = 0;
  for (size_t v = 0; v < o.on_m.size(); ++v) {
    if (o.on_m[v].kind == SurfacePoint::Kind::kEdge) {
      ++crossings;
      EXPECT_EQ(o.on_n[v].kind, SurfacePoint::Kind::kEdge);
      EXPECT_DOUBLE_EQ(o.plane[v].x(), 0.5);
      EXPECT_DOUBLE_EQ(o.plane[v].y(), 0.5);
    }
  }
  EXPECT_EQ(crossings, 1);
}

// Every grid vertex of one disk is a grid vertex of the other and diagonals cross at cell centres: exact
// coincidences everywhere, which must weld into one vertex each.
TEST(DiskOverlay, GridsWithOtherDiagonalsShareEveryVertex) {
  FlatPair p{testing::grid_disk(4, 3, true), testing::grid_disk(4, 3, false), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const DiskOverlay o = checked_overlay(p);
  EXPECT_EQ(o.on_m.size(), 20U + 12U);  // grid vertices and one crossing per cell
  EXPECT_EQ(o.triangles.size(), 48U);
}

TEST(DiskOverlay, IdenticalDisksGiveTheDiskItself) {
  FlatPair p{testing::grid_disk(3, 3, true), testing::grid_disk(3, 3, true), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  const DiskOverlay o = checked_overlay(p);
  EXPECT_EQ(o.on_m.size(), 16U);
  EXPECT_EQ(o.triangles.size(), 18U);
}

// Flattenings that overlap themselves (the strip winds 2.3 times): the faces over a face must be found on f's
// sheet, not on the others that cover the same points of the plane.
TEST(DiskOverlay, OverlappingSpiralsStayOnTheirSheet) {
  FlatPair p{testing::spiral_strip(5, 120, 2.3, 0.0), testing::spiral_strip(5, 120, 2.3, 0.25), {}};
  p.nu = testing::match_boundaries(p.m, p.n);
  checked_overlay(p);
}

TEST(DiskOverlay, TuttePairOfCamelAndCowPatches) {
  const FlatPair p =
      testing::tutte_pair_of_patches(testing::read_demo_mesh("camel.off"), testing::read_demo_mesh("cow.off"), 2500);
  const DiskOverlay o = checked_overlay(p);
  EXPECT_GT(o.triangles.size(), p.m.F.rows() + p.n.F.rows());
}

}  // namespace
}  // namespace liftmap
