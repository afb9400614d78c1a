#include "map/check_overlay.h"

#include <gtest/gtest.h>

#include "common/test_meshes.h"
#include "io/read_mesh.h"

namespace liftmap {
namespace {

/// The overlay of a mesh with itself under the identity, each face split into four triangles at its centroid m and
/// at the point e = 0.7 c0 + 0.3 c1 of its first edge: (c0, e, m), (e, c1, m), (c1, c2, m), (c2, c0, m). On both sides
/// the triangles tile every face exactly.
Overlay split_overlay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const auto nv = static_cast<int>(V.rows()), nf = static_cast<int>(F.rows());
  Overlay o;
  o.on_a.resize(static_cast<size_t>(nv + 2 * nf));
  o.F.resize(4 * nf, 3);
  o.face_a.resize(4 * nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> corner{0, 0, 0};
      corner[static_cast<size_t>(k)] = 1;
      o.on_a[static_cast<size_t>(F(f, k))] = SurfacePoint::in_face(FaceId(f), corner);
    }
    const int m = nv + 2 * f, e = m + 1;
    o.on_a[static_cast<size_t>(m)] = SurfacePoint::in_face(FaceId(f), {1.0 / 3, 1.0 / 3, 1.0 / 3});
    o.on_a[static_cast<size_t>(e)] = SurfacePoint::in_face(FaceId(f), {0.7, 0.3, 0});
    o.F.row(4 * f) << F(f, 0), e, m;
    o.F.row(4 * f + 1) << e, F(f, 1), m;
    o.F.row(4 * f + 2) << F(f, 1), F(f, 2), m;
    o.F.row(4 * f + 3) << F(f, 2), F(f, 0), m;
    o.face_a.segment(4 * f, 4).setConstant(f);
  }
  o.on_b = o.on_a;
  o.face_b = o.face_a;
  return o;
}

TEST(CheckOverlay, ExactTilingHasNoErrorNoFlipAndNoGap) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  const Overlay o = split_overlay(oct.V, oct.F);
  const OverlayCheck c = check_overlay(o, oct.V, oct.F, oct.V, oct.F);
  EXPECT_LT(c.area_error_a, 1e-15);
  EXPECT_LT(c.face_area_error_b, 1e-15);
  EXPECT_EQ(c.flipped_a + c.flipped_b + c.uncovered_faces_a + c.uncovered_faces_b + c.degenerate_a, 0);
  // A triangle dropped leaves a third of its face uncovered; one reversed is flipped.
  Overlay missing = o;
  missing.F.conservativeResize(missing.F.rows() - 1, 3);
  missing.face_a.conservativeResize(missing.F.rows());
  missing.face_b.conservativeResize(missing.F.rows());
  const OverlayCheck m = check_overlay(missing, oct.V, oct.F, oct.V, oct.F);
  EXPECT_NEAR(m.face_area_error_a, 1.0 / 3, 1e-12);  // (c2, c0, m): a third of the face
  EXPECT_NEAR(m.area_error_b, 1.0 / 24, 1e-12);
  Overlay reversed = o;
  reversed.F.row(0) = o.F.row(0).reverse();
  EXPECT_EQ(check_overlay(reversed, oct.V, oct.F, oct.V, oct.F).flipped_a, 1);
}

/// o with one more triangle in face 0 on both sides, (c1, c0, p) for p = (0.7 - d/2, 0.3 - d/2, d): clockwise, its
/// signed area -d times the face's.
Overlay with_flipped_sliver(Overlay o, const Eigen::MatrixXi& F, double d) {
  const auto p = static_cast<int>(o.on_a.size());
  o.on_a.push_back(SurfacePoint::in_face(FaceId(0), {0.7 - d / 2, 0.3 - d / 2, d}));
  o.on_b = o.on_a;
  const Eigen::Index t = o.F.rows();
  o.F.conservativeResize(t + 1, 3);
  o.F.row(t) << F(0, 1), F(0, 0), p;
  o.face_a.conservativeResize(t + 1);
  o.face_a(t) = 0;
  o.face_b = o.face_a;
  return o;
}

// A cell's sign is judged against the precision of its corners: an overlay computed in flattenings says, per
// triangle, what fraction of its face is rounding there (Overlay::rounding_a); without it, kRoundingArea.
TEST(CheckOverlay, FlippedCellsAreJudgedAgainstTheirOwnRounding) {
  const TriangleMesh oct = read_mesh(testing::test_data("good/octahedron.off"));
  const Overlay base = split_overlay(oct.V, oct.F);
  const Overlay sliver = with_flipped_sliver(base, oct.F, 3e-12);  // beyond kRoundingArea
  OverlayCheck c = check_overlay(sliver, oct.V, oct.F, oct.V, oct.F);
  EXPECT_EQ(c.flipped_a, 1);
  EXPECT_EQ(c.flipped_b, 1);

  Overlay imprecise = sliver;  // corners known to 1e-11 of their faces: the sliver's sign is rounding
  imprecise.rounding_a = Eigen::VectorXd::Constant(imprecise.F.rows(), 1e-11);
  imprecise.rounding_b = imprecise.rounding_a;
  c = check_overlay(imprecise, oct.V, oct.F, oct.V, oct.F);
  EXPECT_EQ(c.flipped_a + c.flipped_b, 0);
  EXPECT_EQ(c.degenerate_a, 1);
  EXPECT_EQ(c.degenerate_b, 1);

  Overlay folded = with_flipped_sliver(base, oct.F, 1e-9);  // a flip larger than the rounding still counts
  folded.rounding_a = Eigen::VectorXd::Constant(folded.F.rows(), 1e-11);
  folded.rounding_b = folded.rounding_a;
  c = check_overlay(folded, oct.V, oct.F, oct.V, oct.F);
  EXPECT_EQ(c.flipped_a, 1);
  EXPECT_EQ(c.flipped_b, 1);

  Overlay stale = imprecise;  // tolerances of another size than F are not the overlay's: kRoundingArea
  stale.rounding_a.conservativeResize(stale.F.rows() - 1);
  EXPECT_EQ(check_overlay(stale, oct.V, oct.F, oct.V, oct.F).flipped_a, 1);
}

// Far from the origin (1e4 times its size, the farthest check_mesh accepts) a mesh keeps the digits of its faces:
// the areas are measured from each face's first corner. Measured at the absolute positions, a face's triangles
// summed to its area within only 6e-11 of the mean face area here (4e-11 on sphere-ellipsoid's overlay), far above
// rounding: a point on an edge, computed from the corners' absolute positions, lies off the edge by the rounding of
// those positions.
TEST(CheckOverlay, AreasAreExactFarFromTheOrigin) {
  const TriangleMesh sphere = testing::read_demo_mesh("larger_sphere.off");  // bounding box diagonal 3.46
  Eigen::MatrixXd far = sphere.V;
  far.rowwise() += Eigen::RowVector3d(3.1e4, -2.9e4, 1.7e4);
  const OverlayCheck c = check_overlay(split_overlay(far, sphere.F), far, sphere.F, far, sphere.F);
  EXPECT_LT(c.face_area_error_a, 1e-14);
  EXPECT_LT(c.face_area_error_b, 1e-14);
  EXPECT_LT(c.area_error_a, 1e-14);
  EXPECT_EQ(c.flipped_a + c.flipped_b + c.degenerate_a + c.degenerate_b, 0);
}

}  // namespace
}  // namespace liftmap
