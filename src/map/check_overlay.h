#pragma once
/// Checks of an overlay (the common refinement of two meshes under a map) against the input meshes.

#include <Eigen/Core>

#include "core/overlay.h"

namespace liftmap {

/// Checks of an overlay against its input meshes (issue 32's invariants), all relative; each face's areas are measured
/// from its first corner, so that they keep their digits far from the origin.
struct OverlayCheck {
  double area_error_a = 0;       ///< |sum of triangle areas on A - area of A| / area of A
  double area_error_b = 0;       ///< the same on B
  double face_area_error_a = 0;  ///< max over faces of A of |area of the triangles in it - its area| / mean face area
  double face_area_error_b = 0;  ///< the same on B
  int uncovered_faces_a = 0;     ///< faces of A that hold no overlay triangle
  int uncovered_faces_b = 0;
  int flipped_a = 0;     ///< triangles whose signed area on A, against their face's normal, is below -r times the
                         ///< face's area, r the triangle's Overlay::rounding_a (kRoundingArea if the overlay has none)
  int flipped_b = 0;     ///< the same on B
  int degenerate_a = 0;  ///< triangles whose area on A is within r of the face's area of zero: cells where edges of
                         ///< the two meshes nearly coincide, thinner than the precision of their corners shows
  int degenerate_b = 0;  ///< the same on B
  /// Areas below this fraction of their face's are rounding of the face's own coordinates: their sign is not
  /// meaningful. A cell computed in a flattening can be less precise (Overlay::rounding_a), never more.
  static constexpr double kRoundingArea = 1e-12;
};

/// Measures an overlay's areas and coverage on both inputs.
OverlayCheck check_overlay(const Overlay& overlay, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                           const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB);

}  // namespace liftmap
