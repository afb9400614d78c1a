#pragma once
/// The lifted bijection f : M^ -> N^ and its inverse g (paper §3.2, "Computation of the bijection").

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/mesh.h"
#include "core/surface_point.h"

namespace liftmap {

/// Options of `LiftedBijection`.
struct LiftOptions {
  /// Besides the spanning-tree edges, lift every other edge of both meshes too and require that it lands exactly
  /// (same vertex, edge or face) on the image the tree found for its far end, and that no two vertices share an
  /// image. Catches flattenings that are locally injective with matching boundaries but still not liftable
  /// (different immersed disks over the same boundary curve). Costs about twice the lifting time.
  bool verify = true;
};

/// The lifted bijection of two locally injective flattenings with a common boundary (paper §3.2, Theorem 1,
/// Algorithm 1): f : M^ -> N^ with Phi = Psi o f and f = nu on the boundary, and its inverse g : N^ -> M^ with
/// Psi = Phi o g and g = nu^-1 on the boundary. Both flattenings may overlap themselves globally (paper
/// Figure 3); the ambiguity of Psi^-1 is resolved by lifting paths from the boundary, where f is known.
///
/// Construction lifts every vertex of M^ along a breadth-first spanning tree of its edges, rooted at all boundary
/// vertices (each tree edge u -> w is the segment Phi(u) -> Phi(w), lifted through Psi from f(u)), and likewise
/// every vertex of N^ through Phi. Afterwards `evaluate_f` / `evaluate_g` map any point of a face by lifting a
/// segment from a corner of its face. All walk decisions are exact (see `PathLifter`).
///
/// Solver-style: holds copies of both meshes and flattenings; construct once, evaluate many times.
class LiftedBijection {
 public:
  /// \param M M^, a disk (one boundary loop, Euler characteristic 1, no isolated vertex)
  /// \param Phi #V(M) by 2 flattening of M^, locally injective
  /// \param N N^, a disk
  /// \param Psi #V(N) by 2 flattening of N^, locally injective
  /// \param nu #B by 2 boundary correspondence: row i = (boundary vertex of M^, boundary vertex of N^); every
  ///        boundary vertex of either mesh appears exactly once, consecutive boundary vertices map to consecutive
  ///        boundary vertices (boundary halfedges to boundary halfedges) and Phi(nu(i, 0)) == Psi(nu(i, 1))
  ///        exactly (identical doubles).
  /// \throw InvalidInputError if a mesh is not a disk, a shape is wrong, or nu violates the above.
  /// \throw PipelineError if the flattenings are not liftable: a flattening is not locally injective (flipped
  ///        face, branch point, boundary angle >= 2*pi), a walk leaves a disk, or (with `verify`) two lifts of
  ///        the same vertex disagree or two vertices share an image. The message names the elements and
  ///        coordinates.
  LiftedBijection(const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N, const Eigen::MatrixXd& Psi,
                  const Eigen::MatrixXi& nu, const LiftOptions& options = {});
  ~LiftedBijection();
  LiftedBijection(LiftedBijection&&) noexcept;
  LiftedBijection& operator=(LiftedBijection&&) noexcept;

  /// f at every vertex of M^: a vertex, edge or face point of N^ (a vertex exactly where Phi(v) is a vertex of
  /// Psi on the right sheet, an edge point where it lies on an edge, decided exactly).
  [[nodiscard]] const VertexData<SurfacePoint>& f() const;
  /// g at every vertex of N^, on M^.
  [[nodiscard]] const VertexData<SurfacePoint>& g() const;

  /// f at any point x of M^: a vertex image is looked up; an edge point is found on the lift of its edge; a face
  /// point z = Phi(x) is lifted from the corner of its face with the largest barycentric coordinate. When
  /// rounding puts z outside the triangle Phi(face) (x within ~1e-16 relative of an edge), x is first snapped
  /// onto that edge, so the walk never leaves the lifted triangle.
  /// \pre x is a valid point of M^ (barycentric coordinates >= 0, summing to 1; edge parameter in [0, 1]).
  /// \throw PipelineError if a walk fails (only for non-liftable input, which construction already rejects).
  [[nodiscard]] SurfacePoint evaluate_f(const SurfacePoint& x) const;
  /// g at any point y of N^, as `evaluate_f`.
  [[nodiscard]] SurfacePoint evaluate_g(const SurfacePoint& y) const;

  /// f at many points of M^: element k is evaluate_f(x[k]), bitwise, but the points on one edge share a single lift
  /// of that edge (evaluate_f lifts the whole edge for each), so n points on an edge crossing c faces cost one walk
  /// of c faces instead of n. Runs on the caller's OpenMP threads.
  /// \pre as evaluate_f, for every point. \throw as evaluate_f.
  [[nodiscard]] std::vector<SurfacePoint> evaluate_f(const std::vector<SurfacePoint>& x) const;
  /// g at many points of N^, as the batch `evaluate_f`.
  [[nodiscard]] std::vector<SurfacePoint> evaluate_g(const std::vector<SurfacePoint>& y) const;

 private:
  class OneWay;
  std::unique_ptr<OneWay> f_;
  std::unique_ptr<OneWay> g_;
};

/// f at every vertex of M^ and g at every vertex of N^: the result of `lift_bijection`.
struct LiftedVertexMaps {
  VertexData<SurfacePoint> f;  ///< #V(M^) points of N^
  VertexData<SurfacePoint> g;  ///< #V(N^) points of M^
};

/// One-off form of `LiftedBijection` (paper §3.2): the images of all vertices, both directions.
/// 	hrow as `LiftedBijection`'s constructor.
LiftedVertexMaps lift_bijection(const Mesh& M, const Eigen::MatrixXd& Phi, const Mesh& N, const Eigen::MatrixXd& Psi,
                                const Eigen::MatrixXi& nu, const LiftOptions& options = {});

}  // namespace liftmap
