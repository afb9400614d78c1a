#pragma once
/// Checks of an overlay (the common refinement of two meshes under a map) against the input meshes.

#include <Eigen/Core>

#include "core/overlay.h"

namespace liftmap {

/// Checks of an overlay against its input meshes (issue 32's invariants), all relative.
struct OverlayCheck {
  double area_error_a = 0;       ///< |sum of triangle areas on A - area of A| / area of A
  double area_error_b = 0;       ///< the same on B
  double face_area_error_a = 0;  ///< max over faces of A of |area of the triangles in it - its area| / mean face area
  double face_area_error_b = 0;  ///< the same on B
  int uncovered_faces_a = 0;     ///< faces of A that hold no overlay triangle
  int uncovered_faces_b = 0;
  int flipped_a = 0;  ///< triangles whose normal on A points against their face's normal (or have no area)
  int flipped_b = 0;  ///< the same on B
};

/// Measures an overlay's areas and coverage on both inputs.
OverlayCheck check_overlay(const Overlay& overlay, const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA,
                           const Eigen::MatrixXd& VB, const Eigen::MatrixXi& FB);

}  // namespace liftmap
