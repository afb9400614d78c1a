#pragma once
/// The one "point on a mesh" type of liftmap: landmarks, geodesic path nodes and map images are all
/// SurfacePoints.

#include <Eigen/Core>
#include <array>

#include "core/mesh.h"

namespace liftmap {

/// A point on a triangle mesh: at a vertex, on an edge, or inside a face.
struct SurfacePoint {
  enum class Kind { kVertex, kEdge, kFace };
  Kind kind = Kind::kVertex;
  VertexId vertex;  ///< kVertex
  EdgeId edge;      ///< kEdge: the point (1 - t) * tail + t * head of `Mesh::halfedge(edge)`
  double t = 0.0;
  FaceId face;                          ///< kFace
  std::array<double, 3> bary{0, 0, 0};  ///< kFace: weights of `face_vertices(face)`, summing to 1

  static SurfacePoint at_vertex(VertexId v);
  static SurfacePoint on_edge(EdgeId e, double t);
  static SurfacePoint in_face(FaceId f, const std::array<double, 3>& bary);
};

/// Position of `p` given per-vertex data `X` (#V by k: 3D positions, a flattening, any attribute).
Eigen::RowVectorXd interpolate(const Mesh& mesh, const Eigen::MatrixXd& X, const SurfacePoint& p);

/// The same point expressed as a face point: a face containing it and barycentric coordinates in the order
/// of `face_vertices`. A vertex or edge point picks one incident face (the first found).
/// \pre the element of `p` has at least one incident face.
SurfacePoint as_face_point(const Mesh& mesh, const SurfacePoint& p);

/// Barycentric coordinates of `p` in face `f` of `mesh`, in the order of `face_vertices(f)`: exact zeros for the
/// corners a vertex or edge point does not touch.
/// \pre `f` contains `p` (a face around the vertex, a face of the edge, or the face itself).
std::array<double, 3> barycentric_in_face(const Mesh& mesh, const SurfacePoint& p, FaceId f);

/// The most specific SurfacePoint for barycentric coordinates `b` of face `f` (in the order of `face_vertices(f)`):
/// a vertex point if one coordinate is positive, an edge point if two are, else a face point. Coordinates are
/// clamped and normalised first (clamp_barycentric); only exact zeros count, so interpolation that keeps zeros
/// exact is recognised exactly. \pre some entry of b is positive
SurfacePoint canonical_point(const Mesh& mesh, FaceId f, std::array<double, 3> b);

/// w with its negative entries (rounding noise, of order -1e-16) set to 0, then divided by its sum: barycentric
/// coordinates of a valid face point. \pre some entry of w is positive
std::array<double, 3> clamp_barycentric(std::array<double, 3> w);

/// The face point `p` (of any face of the mesh with faces F) re-expressed in face f, which holds it: its weights
/// move to the same vertices of f. Where p lies on an edge or vertex that both faces share this is exact; weights
/// of rounding size (up to 1e-9) on a vertex f does not have are dropped and the rest renormalised.
/// \param exact if not null, set to false instead of throwing when f does not hold p (the weights are then
///        meaningless)
/// \throw PipelineError if f does not hold p and `exact` is null
std::array<double, 3> reexpress_in_face(const SurfacePoint& p, const Eigen::MatrixXi& F, int f, bool* exact = nullptr);

}  // namespace liftmap
