#pragma once
/// The common refinement of two disks under their lifted bijection: every cell is the intersection of a face of
/// one flattening with a face of the other on the same sheet (paper §3.2; the map is affine on every cell).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"
#include "lift/lift_map.h"

namespace liftmap {

/// The overlay of M^ and N^: a triangle mesh whose every triangle lies in one face of M^ and one face of N^.
struct DiskOverlay {
  std::vector<SurfacePoint> on_m;             ///< #Vo: each vertex as the smallest element of M^ holding it
  std::vector<SurfacePoint> on_n;             ///< #Vo: as the smallest element of N^ holding it
  std::vector<Eigen::Vector2d> plane;         ///< #Vo: its position in the common plane (Phi = Psi there), rounded
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise in the plane
  std::vector<int> face_m, face_n;            ///< per triangle: the face of M^ and of N^ containing it
};

/// Intersects every face of M^ with the faces of N^ that the bijection f puts over it.
///
/// For a face F of M^, the faces of N^ over Phi(F) are found from the lift of one corner, f(v): the faces around
/// f(v) that overlap Phi(F) near Phi(v), then their neighbours across edges whose segment meets the interior of
/// Phi(F), so the search stays on f's sheet where Psi overlaps itself. Each cell Phi(F) ∩ Psi(G) is computed with
/// exact constructions; the element of M^ and of N^ holding each corner (vertex, edge or face) is decided exactly,
/// and equal elements make equal overlay vertices, so neighbouring cells share their corners. A cell with more
/// than three corners is split into triangles from a corner, or from its centroid (an extra vertex inside F and
/// G) when every corner fan has a zero-area triangle.
///
/// \param M, Phi, N, Psi the disks and flattenings of `bijection`
/// \return the overlay; its triangles' areas sum to the areas of Phi(M^) and of Psi(N^) up to rounding
/// \throw PipelineError if a face of M^ is not covered by faces of N^ (flattenings that are not liftable)
DiskOverlay overlay_disks(const LiftedBijection& bijection, const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N,
                          const Eigen::MatrixXd& Psi);

}  // namespace liftmap
