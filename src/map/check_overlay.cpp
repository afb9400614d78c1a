#include "map/check_overlay.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace liftmap {

namespace {

Eigen::Vector3d corner(const Eigen::MatrixXd& V, int i) { return V.row(i).transpose(); }

/// A face's two edge vectors from its first corner: points of the face are measured from that corner, so that a
/// mesh far from the origin keeps the digits of its faces' size (a face's area and its triangles' use the same
/// vectors, and their difference is rounding of the face's own size).
struct FaceFrame {
  Eigen::Vector3d e1, e2;

  FaceFrame(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::Index f)
      : e1(corner(V, F(f, 1)) - corner(V, F(f, 0))), e2(corner(V, F(f, 2)) - corner(V, F(f, 0))) {}

  /// The point of barycentric coordinates w, relative to the first corner.
  [[nodiscard]] Eigen::Vector3d at(const std::array<double, 3>& w) const { return w[1] * e1 + w[2] * e2; }
  /// The face's area vector (normal times area).
  [[nodiscard]] Eigen::Vector3d area_vector() const { return 0.5 * e1.cross(e2); }
};

/// Area vector (n * area) of a triangle.
Eigen::Vector3d area_vector(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a);
}

}  // namespace

OverlayCheck check_overlay(const Overlay& overlay, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                           const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB) {
  OverlayCheck c;
  auto one_side = [&](const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Side side, const Eigen::VectorXd& rounding,
                      double& total_error, double& face_error, int& uncovered, int& flipped, int& degenerate) {
    const bool per_triangle = rounding.size() == overlay.F.rows();
    Eigen::VectorXd covered = Eigen::VectorXd::Zero(F.rows());
    Eigen::VectorXi count = Eigen::VectorXi::Zero(F.rows());
    Eigen::VectorXd face_area(F.rows());
    for (Eigen::Index f = 0; f < F.rows(); ++f) face_area(f) = FaceFrame(V, F, f).area_vector().norm();
    for (Eigen::Index t = 0; t < overlay.F.rows(); ++t) {
      const int f = side == Side::kA ? overlay.face_a(t) : overlay.face_b(t);
      const auto w = corner_barycentrics(overlay, F, side, static_cast<int>(t));
      const FaceFrame frame(V, F, f);
      const Eigen::Vector3d n = area_vector(frame.at(w[0]), frame.at(w[1]), frame.at(w[2]));
      const Eigen::Vector3d nf = frame.area_vector();
      const double signed_area = n.dot(nf.normalized());
      // Cells far thinner than rounding (two maps' edges that nearly coincide) have no reliable sign.
      const double tolerance = (per_triangle ? rounding(t) : OverlayCheck::kRoundingArea) * nf.norm();
      if (!(signed_area > -tolerance)) ++flipped;
      if (std::abs(signed_area) <= tolerance) ++degenerate;
      covered(f) += signed_area;
      ++count(f);
    }
    double total = 0, sum = 0;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      total += face_area(f);
      sum += covered(f);
      if (count(f) == 0) ++uncovered;
    }
    const double mean = total / static_cast<double>(F.rows());
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      face_error = std::max(face_error, std::abs(covered(f) - face_area(f)) / mean);
    total_error = std::abs(sum - total) / total;
  };
  one_side(VA, FA, Side::kA, overlay.rounding_a, c.area_error_a, c.face_area_error_a, c.uncovered_faces_a, c.flipped_a,
           c.degenerate_a);
  one_side(VB, FB, Side::kB, overlay.rounding_b, c.area_error_b, c.face_area_error_b, c.uncovered_faces_b, c.flipped_b,
           c.degenerate_b);
  return c;
}

}  // namespace liftmap
