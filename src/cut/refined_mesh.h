#pragma once
/// A refinement of an input mesh in which cut paths run along edges (paper §3.4, "the intersections of the
/// geodesic curves with the edges of the meshes are added as new vertices, and remeshed accordingly").

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"

namespace liftmap {

/// A refinement of an input mesh: every refined vertex is a point of the input surface and every refined face
/// lies inside one input face, so the refined surface is the input surface.
struct RefinedMesh {
  std::vector<Eigen::Vector3d> positions;  ///< per refined vertex, its position in R^3
  std::vector<SurfacePoint> on_input;      ///< per refined vertex, its location on the input mesh (most specific
                                           ///< kind: vertex, else edge, else face)
  std::vector<std::array<int, 3>> faces;   ///< refined faces, counter-clockwise
  std::vector<int> input_face;             ///< per refined face, the input face containing it
  Mesh mesh;                               ///< connectivity of `faces`, rebuilt by `split_refined_mesh`

  [[nodiscard]] int n_vertices() const { return static_cast<int>(positions.size()); }
  /// #V by 3 positions.
  [[nodiscard]] Eigen::MatrixXd vertex_matrix() const;
  /// #F by 3 faces.
  [[nodiscard]] Eigen::MatrixXi face_matrix() const;
};

/// The trivial refinement: the input mesh itself.
/// \param input connectivity of the input mesh
/// \param V #V by 3 input positions
RefinedMesh make_refined_mesh(const Mesh& input, const Eigen::MatrixXd& V);

/// A new vertex at (1 - t) * a + t * b on the refined edge (a, b), 0 < t < 1.
struct EdgeSplit {
  int a = -1;
  int b = -1;
  double t = 0.5;
};

/// Splits refined edges at the given points and re-triangulates the faces around them so that each `chord`
/// becomes an edge. The new vertex of `splits[i]` gets id `n_vertices() + i` (ids before the call), so chords
/// can name new vertices before they exist. Faces are re-triangulated without degenerate triangles.
/// \param input the input mesh (for the provenance of new vertices)
/// \param splits points on existing edges; at most one per position
/// \param chords pairs of vertex ids (old or new) that lie on the boundary of one common refined face
/// \throw PipelineError if an edge of a split does not exist or a chord lies in no single face.
void split_refined_mesh(RefinedMesh& refined, const Mesh& input, const std::vector<EdgeSplit>& splits,
                        const std::vector<std::array<int, 2>>& chords = {});

/// Inserts a polyline into the refined mesh: points on edges become vertices and the segments between
/// consecutive points become edges (paper §3.4, "remeshed accordingly so that the geodesic passes through a
/// connected set of edges").
/// \param points vertex or edge points of `refined.mesh` (t along `Mesh::halfedge(edge)`, 0 < t < 1); each two
///        consecutive points lie on one common face
/// \return the refined vertex ids of the points, or an empty vector (and `refined` unchanged) if two
///         consecutive points share no face
std::vector<int> insert_polyline(RefinedMesh& refined, const Mesh& input, const std::vector<SurfacePoint>& points);

/// The halfedge from `a` to `b` of `mesh`, invalid if there is no such edge.
HalfedgeId find_halfedge(const Mesh& mesh, VertexId a, VertexId b);

}  // namespace liftmap
