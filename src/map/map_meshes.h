#pragma once
/// The whole pipeline (paper §3, Figure 2): cut both meshes to disks, flatten them jointly, lift the flattenings
/// into the bijection, express it on the input meshes, and verify it.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/overlay.h"
#include "core/surface_point.h"
#include "cut/cut_meshes.h"
#include "flatten/joint_flatten.h"
#include "lift/lift_map.h"
#include "map/check_overlay.h"

namespace liftmap {

/// Settings of `map_meshes`; every stage's own settings with their defaults.
struct MapOptions {
  CutOptions cut;
  JointFlattenOptions flatten;
  LiftOptions lift;
  /// Distortion of the maps f and g is measured by dense sampling: each face is split into n^2 sub-triangles
  /// and the map is evaluated at their centroids, each weighted by its area.
  int distortion_samples_per_edge = 2;
  /// Compute the overlay (overlay_of_map: the common refinement of A and B on which the map is affine) and check it
  /// in the verification.
  bool overlay = true;
  /// Threads of the per-face work while map_meshes runs, 1 to MapOptionLimits::max_threads(); 0: the calling
  /// thread's OpenMP setting. Set on the calling thread only and restored before map_meshes returns.
  int threads = 0;
  /// How messages name the two input meshes (the CLI passes their file names).
  std::string name_a = "mesh A", name_b = "mesh B";
  /// Called with (stage, message) as the pipeline advances; empty: silent.
  std::function<void(const std::string&, const std::string&)> progress;
};

/// The ranges the front ends (CLI, Python) accept for MapOptions' numbers.
struct MapOptionLimits {
  static constexpr int kMaxOuterIterations = 10000;  ///< max_iterations: a run stops at the tolerance long before
  static constexpr int kMaxSamplesPerEdge = 10;      ///< distortion_samples_per_edge: from 1
  /// threads: 4 per hardware thread (more only cost memory, and thread creation fails in OpenMP long before an
  /// int overflows).
  static int max_threads();
};

/// The front ends' names of MapOptions' choices (CLI: --p, --h, --solver, --tree; Python: keyword arguments).
struct MapChoiceNames {
  std::string p = "2";          ///< norm of the energy (10a): "2" or "inf"
  std::string h = "eq3";        ///< per-face distortion: "eq3" (sqrt(Sigma^2 + sigma^-2)) or "eq2" (max)
  std::string solver = "auto";  ///< "auto", "barrier" or "primal-dual"
  std::string tree = "mst";     ///< cut tree: "mst" (paper) or "path"
};

/// Sets the choices of `options` from their names.
/// \throw UsageError naming the option and the accepted values if a name is not one of them.
void set_map_choices(MapOptions& options, const MapChoiceNames& names);

/// Area-weighted statistics of a per-face (or per-sample) distortion max(Sigma, 1/sigma) (paper §4.2).
struct DistortionStats {
  double mean = 0;    ///< area-weighted mean
  double median = 0;  ///< area-weighted median
  double p95 = 0;     ///< area-weighted 95th percentile
  double max = 0;
};

/// Area-weighted mean, median, 95th percentile and max of `values` (one weight each); all 0 if empty.
DistortionStats weighted_stats(const Eigen::VectorXd& values, const Eigen::VectorXd& weights);

/// Barycentric coordinates of the centroids of a face's n^2 sub-triangles (upright and inverted, all of equal
/// area): the samples at which the distortion of f and g is measured (MapOptions::distortion_samples_per_edge).
std::vector<std::array<double, 3>> sub_triangle_centroids(int n);

/// Checks of the final map; `passed` is false if any of them fails its tolerance.
struct MapVerification {
  double min_orientation = 0;         ///< min over both flattenings of signed area / mean area (> 0 required)
  double max_boundary_angle_sum = 0;  ///< max over boundary vertices of both flattenings (< 2 pi required)
  double lifting_residual = 0;        ///< max |Psi(f(x)) - Phi(x)| and |Phi(g(y)) - Psi(y)| over vertices, / diameter
  double round_trip_error = 0;        ///< max |g(f(v)) - v| and |f(g(w)) - w| in R^3 over input vertices, / sqrt(area)
  double landmark_error = 0;          ///< max distance in R^3 from f(landmark) to its partner (and for g), / sqrt(area)
                                      ///< of the partner's mesh; surface-point landmarks too
  /// With MapOptions::overlay: its checks (check_overlay) and MapResult::overlay_agreement (an overlay
  /// vertex's point on one side against the bijection's image of its point on the other).
  OverlayCheck overlay;
  double overlay_vertex_error = 0;
  bool passed = false;
  std::vector<std::string> failures;  ///< one line per failed check
};

/// Wall time of each stage, seconds.
struct MapTimings {
  double cut = 0, flatten = 0, lift = 0, overlay = 0, verify = 0, total = 0;
};

struct MapIndex;  // translation between the input meshes and their disks (defined in map_meshes.cpp)

/// The map between two input meshes A and B and everything it was made of.
struct MapResult {
  CutResult cut;                               ///< refined and cut meshes with provenance, boundary correspondence nu
  Mesh disk_a, disk_b;                         ///< connectivity of the cut meshes (cut.a.F_cut, cut.b.F_cut)
  Eigen::MatrixXd disk_va, disk_vb;            ///< #Vc by 3 positions of the cut meshes' vertices
  JointFlattenResult flattening;               ///< Phi (of disk_a), Psi (of disk_b), energies per outer iteration
  std::shared_ptr<LiftedBijection> bijection;  ///< f: disk_a -> disk_b, g: disk_b -> disk_a

  std::vector<SurfacePoint> a_to_b;      ///< per input vertex of A, its image as a face point of input B
  std::vector<SurfacePoint> b_to_a;      ///< per input vertex of B, its image as a face point of input A
  std::vector<SurfacePoint> cut_a_to_b;  ///< per cut vertex of A, its image as a face point of disk_b
  std::vector<SurfacePoint> cut_b_to_a;  ///< per cut vertex of B, its image as a face point of disk_a
  Overlay overlay;                       ///< the common refinement of A and B (empty without MapOptions::overlay)
  double overlay_agreement = 0;          ///< overlay_of_map's `agreement` (relative to sqrt(area))

  DistortionStats distortion_phi, distortion_psi;  ///< per face of the flattenings
  DistortionStats distortion_f, distortion_g;      ///< of the maps, by dense sampling
  Eigen::VectorXd f_samples, f_weights;            ///< the sampled distortion of f and the samples' areas
  double scale_a = 1, scale_b = 1;                 ///< factors that give both meshes the same area
  MapVerification verification;
  MapTimings seconds;
  std::shared_ptr<const MapIndex> index;  ///< used by evaluate_map
};

/// Computes the lifted bijection between two closed genus-0 meshes with corresponding landmarks.
/// \param VA, VB #V by 3 positions; FA, FB #F by 3 faces
/// \param landmarks_a, landmarks_b k >= 2 corresponding vertices
/// Each mesh is validated once, by check_mesh (the validation of `liftmap check`), before any computation.
/// \throw InvalidInputError naming MapOptions::name_a or name_b if a mesh cannot be mapped (see check_mesh), or
///        if the landmarks are invalid (including two too close to cut apart: require_landmarks_apart), or if
///        options.flatten.p is neither 2 nor infinity;
///        PipelineError if a stage fails (a complaint of the flattening, the lift or the overlay about its data,
///        which the pipeline made from checked inputs, included). A map whose verification fails is returned with
///        `verification.passed == false`: the caller decides (the CLI writes it and exits with an error).
MapResult map_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<VertexId>& landmarks_a,
                     const std::vector<VertexId>& landmarks_b, const MapOptions& options = {});

/// map_meshes with landmarks anywhere on the surfaces: k >= 2 corresponding vertex, edge or face points of the
/// input meshes (a face point's coordinates in the order of its row of F). Each becomes a vertex of the refined
/// mesh (cut_meshes), so f takes it exactly onto its partner.
MapResult map_meshes(const Eigen::MatrixXd& VA, const Eigen::MatrixXi& FA, const Eigen::MatrixXd& VB,
                     const Eigen::MatrixXi& FB, const std::vector<SurfacePoint>& landmarks_a,
                     const std::vector<SurfacePoint>& landmarks_b, const MapOptions& options = {});

/// The checks of a map made by map_meshes (MapVerification's fields): both flattenings free of flipped faces with
/// boundary angle sums below 2 pi, Psi(f(x)) = Phi(x) and Phi(g(y)) = Psi(y) at every cut vertex (the lifting),
/// g(f(v)) = v and f(g(w)) = w in R^3 at every input vertex, and f(landmark) = its partner.
/// \pre `map` has its cut, flattening, bijection and input maps (the stages of map_meshes before verification)
MapVerification verify_map(const MapResult& map, const std::vector<SurfacePoint>& landmarks_a,
                           const std::vector<SurfacePoint>& landmarks_b);

/// The distortion max(Sigma, 1/sigma) of the flattenings per face and of the maps f and g by dense sampling (each face
/// split into samples_per_edge^2 sub-triangles, sub_triangle_centroids), both meshes scaled to the same area as the
/// flattening: sets map.distortion_phi, distortion_psi, distortion_f, distortion_g, f_samples and f_weights.
/// \pre as verify_map
void map_distortion(MapResult& map, int samples_per_edge);

/// Evaluates the map at any point of an input mesh (texture transfer, sampling): f for a point of A, g for a
/// point of B.
/// \param side the mesh x lies on: kA evaluates f, kB evaluates g
/// \param x a point of that input mesh (vertex, edge or face point of the input connectivity)
/// \return its image as a face point of the other input mesh
/// \throw PipelineError if the point cannot be located (a face point outside its face)
SurfacePoint evaluate_map(const MapResult& map, Side side, const SurfacePoint& x);

/// A point of a cut disk (disk_a for kA, disk_b for kB; any kind) as a face point of that side's input mesh.
/// \pre `map` has its cut and bijection
SurfacePoint disk_to_input(const MapResult& map, Side side, const SurfacePoint& x);

}  // namespace liftmap
