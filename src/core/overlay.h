#pragma once
/// The overlay: the common refinement of the two input meshes A and B under a map (README, "Output folder").
///
/// The map is exactly piecewise linear on it. Every overlay triangle lies inside one face of A and inside one face
/// of B, and is mapped affinely from one to the other; its vertices are the vertices of A, the vertices of B (both
/// carried across by the map), and the crossings of A's edges with B's edges. Cells that are convex polygons with
/// more than three corners are split into triangles (from a corner, or from the cell's centroid when a corner fan
/// would make a zero-area triangle).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/surface_point.h"

namespace liftmap {

/// Which input mesh a point, a map or an overlay embedding belongs to.
enum class Side { kA, kB };

/// The common refinement of A and B under a map, as one triangle mesh with two embeddings.
struct Overlay {
  Eigen::MatrixXd VA;              ///< #Vo by 3: each overlay vertex's position on A
  Eigen::MatrixXd VB;              ///< #Vo by 3: its position on B (its image under the map)
  std::vector<SurfacePoint> on_a;  ///< #Vo: each overlay vertex as a face point of input A
  std::vector<SurfacePoint> on_b;  ///< #Vo: as a face point of input B
  Eigen::MatrixXi F;               ///< #Fo by 3 triangles, counter-clockwise on A and on B
  Eigen::VectorXi face_a, face_b;  ///< #Fo: the input face of A and of B containing each triangle
  /// #Fo, or empty: per triangle, the fraction of its face of A (of B) below which its signed area there is
  /// rounding, not a sign. Its corners were computed in the flattenings, so their coordinates in the face carry the
  /// flattening's rounding magnified by how small the face is there (overlay_of_map). Empty: the rounding of
  /// the coordinates alone (OverlayCheck::kRoundingArea).
  Eigen::VectorXd rounding_a, rounding_b;
};

/// Barycentric coordinates of overlay triangle `t`'s three corners in its own input face (face_a(t) on A,
/// face_b(t) on B), in the order of that face's vertices: the affine map of the triangle into the face.
/// A vertex recorded in another face lies on an edge or vertex the two faces share; its weights move to the same
/// vertices of this face. Weights of rounding size on a vertex the faces do not share (1e-16) are dropped and the
/// rest renormalised.
/// \param F the input faces of that side (#F by 3)
/// \pre t is a triangle of `overlay`
std::array<std::array<double, 3>, 3> corner_barycentrics(const Overlay& overlay, const Eigen::MatrixXi& F, Side side,
                                                         int t);

}  // namespace liftmap
