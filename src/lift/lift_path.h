#pragma once
/// Path lifting through a locally injective flattening (paper §3.2, Algorithm 1).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"

namespace liftmap {

/// The lifted path q of one segment [a, b]: every point where the walk passes from one element of the mesh to
/// the next, with the face that holds each piece in between.
struct LiftTrace {
  std::vector<SurfacePoint> nodes;  ///< the start, each edge crossing and vertex passed, the end
  std::vector<double> s;            ///< #nodes: parameter of each node along [a, b] (0 at a, 1 at b), nondecreasing
  std::vector<FaceId> faces;        ///< #nodes - 1: a face holding the piece between node k and node k + 1
                                    ///< (for a piece along an edge, one of the edge's faces)
};

/// The lift q of a polyline w (Algorithm 1's output).
struct LiftedPath {
  std::vector<SurfacePoint> points;  ///< q in order: lifts of the rows of W with every crossing node in between
  std::vector<int> row_index;        ///< #W: index into `points` of the lift of each row of W
};

/// Lifts segments and polylines of the plane through a locally injective flattening Psi of a mesh N^
/// (paper §3.2, Algorithm 1): starting at a point y0 of N^ with Psi(y0) = z0, it walks the faces of N^ along the
/// polyline, one-ring by one-ring, so that the result q satisfies Psi(q) = w even where Psi overlaps itself
/// globally (paper Figure 3).
///
/// Every in/out/on decision (which edge the walk leaves a face through, whether it passes exactly through a
/// vertex or runs along an edge, whether the end lies on an edge or at a vertex) is made with exact orientation
/// predicates on the segment's endpoints and the vertices of Psi, never on constructed points; barycentric
/// coordinates and edge parameters of the results are computed in floating point afterwards. The location of a
/// point is therefore a consistent combinatorial fact: lifting the same planar point along two paths of the same
/// sheet gives the same vertex, edge or face.
///
/// Solver-style: the flattening is checked once at construction, then any number of segments is lifted.
class PathLifter {
 public:
  /// \param mesh N^, a manifold mesh with or without boundary (copied)
  /// \param Psi #V by 2 flattening of `mesh`
  /// \throw InvalidInputError if `Psi` has the wrong shape or non-finite entries
  /// \throw PipelineError if `Psi` is not locally injective (see `check_local_injectivity`): paths through it
  ///        cannot be lifted (paper §3.2); the message names the first faces/vertices at fault.
  PathLifter(const Mesh& mesh, const Eigen::MatrixXd& Psi);

  /// Lifts the segment [a, b] starting at `start`, and returns the lift of b.
  /// \param start a point of N^ whose closure contains a; only its element (vertex, edge or face) is used, and
  ///        it is refined exactly (a face start with `a` on an edge of the face starts on that edge, etc.).
  ///        A vertex start needs Psi(vertex) == a exactly.
  /// \param trace if not null, receives the lifted path of the segment
  /// \return the lift of b: a vertex, an edge point or a face point, decided exactly
  /// \throw InvalidInputError if the element of `start` does not contain `a`
  /// \throw PipelineError if the walk leaves N^ through a boundary edge or vertex (the path is not liftable,
  ///        e.g. the flattenings violate the lifting conditions), naming the element and the coordinates; or
  ///        if the walk exceeds its step bound (#V + #E + #F + 4: a straight segment meets each element of a
  ///        locally injective flattening at most once).
  SurfacePoint lift_segment(const SurfacePoint& start, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            LiftTrace* trace = nullptr) const;

  /// Lifts the polyline `W` (#W by 2, W.row(0) being the image of `start`) segment by segment (Algorithm 1).
  /// \throw as `lift_segment`; InvalidInputError if `W` is empty or not #W by 2.
  [[nodiscard]] LiftedPath lift_polyline(const SurfacePoint& start, const Eigen::MatrixXd& W) const;

  /// Exact location of `z` in the closure of the element of `hint`, as the smallest element holding it.
  /// \throw InvalidInputError if the element of `hint` does not contain `z`.
  [[nodiscard]] SurfacePoint refine(const SurfacePoint& hint, const Eigen::Vector2d& z) const;

  /// The face point of `f` whose image under Psi is closest to `z`, by barycentric coordinates computed in
  /// floating point; a z that rounding put just outside is moved onto the nearest point of the edge it fell across.
  [[nodiscard]] SurfacePoint face_point(FaceId f, const Eigen::Vector2d& z) const;

  /// The coordinates of a point of the element of `p` (a point found by lifting z) recomputed from z given in
  /// extended precision: barycentric coordinates of a face point, the parameter of an edge point (a vertex is
  /// returned as it is). Flattened faces can be far smaller than the flattening, so z's rounding to double, at
  /// the scale of the whole flattening, would dominate their coordinates.
  [[nodiscard]] SurfacePoint refine_coordinates(const SurfacePoint& p, long double zx, long double zy) const;

  /// Psi at the corners of face f.
  [[nodiscard]] std::array<Eigen::Vector2d, 3> corners(FaceId f) const;

  /// Psi at vertex v.
  [[nodiscard]] const Eigen::Vector2d& position(VertexId v) const { return psi_[static_cast<size_t>(v.idx)]; }
  [[nodiscard]] const Mesh& mesh() const { return mesh_; }

 private:
  [[nodiscard]] SurfacePoint edge_point(HalfedgeId h, const Eigen::Vector2d& z) const;
  [[nodiscard]] FaceId face_of_edge(HalfedgeId h) const;

  Mesh mesh_;
  std::vector<Eigen::Vector2d> psi_;
  int max_steps_ = 0;
};

/// One-off form of `PathLifter::lift_polyline` (paper §3.2, Algorithm 1).
/// \param mesh N^
/// \param Psi #V by 2 locally injective flattening of `mesh`
/// \param start a point of N^ with Psi(start) = W.row(0) (see `PathLifter::lift_segment`)
/// \param W #W by 2 polyline in the plane
/// \throw as `PathLifter`'s constructor and `lift_polyline`
LiftedPath lift_path(const Mesh& mesh, const Eigen::MatrixXd& Psi, const SurfacePoint& start, const Eigen::MatrixXd& W);

}  // namespace liftmap
