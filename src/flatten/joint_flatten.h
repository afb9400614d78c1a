#pragma once
/// Joint flattening of two disks with a common boundary: Algorithm 2 of the paper (§3.3).

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "flatten/distortion.h"
#include "flatten/flattening_start.h"
#include "flatten/joint_start_relaxation.h"
#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem.h"
#include "flatten/symmetric_dirichlet.h"

namespace liftmap {

/// One of the two cut disks and its boundary in correspondence order.
struct FlatteningDisk {
  const Mesh* mesh = nullptr;      ///< a disk (one boundary loop, Euler characteristic 1)
  Eigen::MatrixXd V;               ///< #V by 3 vertex positions
  std::vector<VertexId> boundary;  ///< the whole boundary loop, counter-clockwise (interior on the left);
                                   ///< boundary[i] of one disk corresponds to boundary[i] of the other (nu)
};

struct JointFlattenIteration;

/// The solver of the convex subproblems (10).
enum class SubproblemSolver {
  /// The barrier method for p = 2, the primal-dual method for p = inf: each is the faster and the more robust one
  /// there (docs/performance.md, "Barrier method settings").
  kAuto,
  kBarrier,     ///< solve_convex_subproblem (barrier_solver.h)
  kPrimalDual,  ///< solve_convex_subproblem_primal_dual (primal_dual_solver.h)
};

/// Settings of Algorithm 2; defaults are the paper's.
struct JointFlattenOptions {
  double p = 2;                                      ///< 2 or std::numeric_limits<double>::infinity()
  DistortionCombiner h = DistortionCombiner::kNorm;  ///< eq. (3) by default, eq. (2) as alternative
  bool normalize_area = true;                        ///< scale both disks to the same total area (pi) before flattening
  bool ghost_faces = true;                           ///< the paper's ghost faces: boundary angle sums stay below 2 pi
  double relative_tolerance = 1e-3;  ///< stop when the energy (8) improves by less than this, relatively
  int max_iterations = 10;           ///< outer iterations
  bool keep_iterates = false;        ///< keep every iterate's flattenings in the result
  /// The convex subproblem solver. Its relative_gap is the finest gap any subproblem is solved to (see
  /// gap_fraction): 1e-5 is 100 times finer than the outer tolerance, and saves the last one or two centrings,
  /// which on whole-mesh disks run at the limits of double precision.
  SubproblemSettings solver = [] {
    SubproblemSettings s;
    s.relative_gap = 1e-5;
    return s;
  }();
  /// Each subproblem is solved to optimality within a certified relative gap that follows the outer loop's
  /// progress: gap_fraction times the relative decrease of the energy (8) in the previous outer iteration, clamped
  /// to [solver.relative_gap, max_subproblem_gap]; the first subproblem (from the Tutte start, which it improves
  /// by orders of magnitude) to max_subproblem_gap. A gap of a fraction of what the outer loop is about to gain
  /// cannot change its course. 0: every subproblem to solver.relative_gap.
  double gap_fraction = 0.3;
  /// The coarsest gap of gap_fraction's rule, and the first subproblem's.
  double max_subproblem_gap = 1e-2;
  /// Barrier method, p = 2: every subproblem after the first starts at the barrier parameter whose gap bound is
  /// start_gap_fraction times the previous outer iteration's relative energy decrease (or at the usual, lower one;
  /// BarrierSettings::initial_gap), instead of ~100 times the parameter that best centres the start: the start, the
  /// previous minimiser, is within about that decrease of the new optimum. Half of gap_fraction, so that each
  /// subproblem after the first is a single centring from the previous minimiser. 0: off.
  double start_gap_fraction = 0.15;
  /// Barrier method, p = 2: a subproblem after the first starts at most at the barrier parameter whose gap bound is
  /// rotation_gain_start_fraction times the previous outer iteration's rotation gain (Q_{k-1}(X_k) - E(X_k)) / E(X_k):
  /// how far the energy (8) at the previous minimiser X_k, with its own polar rotations, lies below the objective
  /// (10a) of the subproblem that found it (Q_{k-1} >= E, docs/algorithm.md). The next outer iteration gains about
  /// 0.4 to 1 times that, which after a relaxed start can be far below the last gain that start_gap_fraction follows:
  /// a single centring at start_gap_fraction times the last gain then ends above its own start and is solved again
  /// (refined_gap_fraction). Never below half of solver.relative_gap. 0: off.
  double rotation_gain_start_fraction = 2;
  /// Barrier method, p = 2, after the joint relaxation of the start (joint_start): the first subproblem starts at
  /// the barrier parameter whose gap bound is relaxed_start_gap_fraction times its own gap (subproblem_gap:
  /// max_subproblem_gap, or solver.relative_gap if gap_fraction is 0), instead of ~100 times the parameter that best
  /// centres the start. The relaxed start is within a few percent of the first subproblem's optimum, as the previous
  /// minimiser is for the later ones, so a single centring from it suffices. From the circle (no relaxation) the usual
  /// start stays: there the first subproblem has most of the way to go. 0: off.
  double relaxed_start_gap_fraction = 0.2;
  /// A subproblem solved to a gap coarser than refined_gap_fraction times relative_tolerance that ends at or above
  /// its start (the gap rule expected more progress than was left) is solved again from the same start, to that finer
  /// gap, starting at half of it. Below 1, so that a second result above the start certifies convergence: the
  /// subproblem's optimum is then within less than the tolerance of the start's energy
  /// (JointFlattenResult::last_subproblem_steps). 0: off (the loop stops early there, stop_reason says why).
  /// Half leaves the certificate a wide margin under the tolerance; finer costs Newton steps for no gain that the
  /// tolerance can see (docs/performance.md).
  double refined_gap_fraction = 0.5;
  SubproblemSolver method = SubproblemSolver::kAuto;
  /// A disk whose plain Tutte start squeezed a face (FlatteningStart::squeezed) has its drifted start lowered in
  /// the symmetric Dirichlet energy, boundary fixed, never flipping a face (minimize_symmetric_dirichlet);
  /// max_iterations 0: off. Projected Newton throughout: proxy steps (proxy_while_decrease) start faster but, as
  /// measured, do not make the map faster or better (docs/performance.md, "Reweighted proxy steps").
  SymmetricDirichletOptions start_optimization;
  /// Then both disks are relaxed together, their common boundary free (relax_joint_start; needs ghost_faces);
  /// joint_start.newton.max_iterations 0: off.
  JointStartRelaxationOptions joint_start;
  /// Called with (index, statistics) for the start (index 0) and after every accepted outer iteration, as
  /// they happen (progress reporting); empty: not called.
  std::function<void(size_t, const JointFlattenIteration&)> on_iteration = nullptr;
};

/// Whether joint_flatten solves its subproblems with the primal-dual method (else the barrier method).
[[nodiscard]] bool uses_primal_dual(const JointFlattenOptions& options);

/// The initial gap (BarrierSettings::initial_gap) of the next subproblem, given the iterates so far: for the first
/// subproblem relaxed_start_gap_fraction times its gap if the start was relaxed (relaxed_start), else 0; for later
/// ones start_gap_fraction times the last outer iteration's relative energy decrease, at most
/// rotation_gain_start_fraction times its rotation gain (JointFlattenIteration::subproblem_objective above energy),
/// or 0 if it gained nothing.
/// 0 means the barrier method's usual first parameter.
[[nodiscard]] double start_gap(const JointFlattenOptions& options, const std::vector<JointFlattenIteration>& iterations,
                               bool relaxed_start);

/// What the joint relaxation of the start did (relax_joint_start).
struct JointStartRelaxation {
  int steps = 0;             ///< projected Newton steps taken (0: off, or nothing gained)
  double energy_before = 0;  ///< its energy E before and after (0, 0 if off)
  double energy_after = 0;
  double seconds = 0;  ///< wall time of the relaxation (part of iteration 0's seconds)
};

/// Statistics of one iterate (index 0: the Tutte start).
struct JointFlattenIteration {
  double energy = 0;  ///< E_p(Phi) + E_p(Psi), eq. (8) with the chosen h, p (normalised meshes)
  double energy_m = 0, energy_n = 0;
  double max_distortion = 0;        ///< max over both meshes of max(Sigma, 1/sigma) (§4.2)
  double min_area_ratio = 0;        ///< min over both meshes of the smallest face area over the mean
  double subproblem_objective = 0;  ///< optimum of (10) found in this iteration (0 for the start)
  int newton_steps = 0;
  double subproblem_gap = 0;          ///< relative gap the subproblem was solved to (gap_fraction; 0 for the start)
  bool subproblem_converged = false;  ///< the solver certified its gap bound (SubproblemResult::converged)
  int stalled_centrings = 0;          ///< SubproblemResult::stalled_centrings
  /// The subproblem was solved twice: first to subproblem_gap's coarser gap, which ended above its start, then
  /// again from the same start at refined_gap_fraction times the outer tolerance (newton_steps counts both).
  bool subproblem_refined = false;
  std::optional<SubproblemStatus> subproblem_status;  ///< why the subproblem's solve ended; none for the start
  double seconds = 0;  ///< wall time of this outer iteration (rotations + solve + checks); the start: of the start
};

/// Whether a subproblem solved at `solver`'s gap that ended above its start is solved again, finer
/// (JointFlattenIteration::subproblem_refined): refined_gap_fraction times the outer tolerance is below that gap.
[[nodiscard]] bool can_refine(const JointFlattenOptions& options, const SubproblemSettings& solver);

/// The relative gap joint_flatten solves its next subproblem to, given the iterates so far (gap_fraction).
[[nodiscard]] double subproblem_gap(const JointFlattenOptions& options,
                                    const std::vector<JointFlattenIteration>& iterations);

/// Result of the joint flattening.
struct JointFlattenResult {
  Eigen::MatrixXd Phi;  ///< #V(M) by 2 flattening of the first disk
  Eigen::MatrixXd Psi;  ///< #V(N) by 2 flattening of the second; Phi(boundary_m[i]) == Psi(boundary_n[i])
  std::vector<JointFlattenIteration> iterations;            ///< start, then one entry per outer iteration
  std::vector<Eigen::MatrixXd> Phi_iterates, Psi_iterates;  ///< every iterate if keep_iterates, else empty
  std::string stop_reason;  ///< why the outer loop stopped before converging, if it did (empty otherwise)
  bool converged = false;   ///< the relative tolerance was met before max_iterations
  /// Newton steps of a last subproblem that ended at or above its start although certified to a gap below the
  /// outer tolerance, which proves convergence without a new iterate (its optimum is within that gap of the
  /// start); 0 if the loop converged on the energy's relative decrease, or did not converge.
  int last_subproblem_steps = 0;
  double scale_m = 1, scale_n = 1;                ///< factors applied to the disks' coordinates internally
  std::array<FlatteningStartCandidate, 2> start;  ///< each disk's start: drift, energy, smallest face area
  std::array<int, 2> start_steps{};               ///< Newton steps of each disk's start_optimization
  JointStartRelaxation joint_start;               ///< the joint relaxation of the start
};

/// Computes liftable flattenings Phi, Psi of two disks with a common boundary (Algorithm 2): a convex-combination
/// start on the unit circle (corresponding boundary vertices at the same point, spaced by the averaged boundary arc
/// length; flattening_start), relaxed jointly with the common boundary free (relax_joint_start), then convex
/// subproblems (10) with rotations from the polar decompositions.
/// Every iterate has all faces positively oriented, interior angle sums 2 pi, and (with ghost faces) boundary
/// angle sums below 2 pi; Phi and Psi agree exactly on corresponding boundary vertices. Outputs are in the first
/// disk's input units (positions divided by scale_m), so that the common boundary stays common.
/// \throw InvalidInputError if a mesh is not a disk, the boundaries differ in length or are not the boundary
///        loops in counter-clockwise order; PipelineError if the start fails a liftability check (an iterate
///        after it that fails one, or a subproblem the solver fails, ends the loop with stop_reason instead, and
///        the last iterate that passed is the result).
JointFlattenResult joint_flatten(const FlatteningDisk& m, const FlatteningDisk& n,
                                 const JointFlattenOptions& options = {});

/// The building blocks of joint_flatten(), exposed for tests and the subproblem exporter: the (normalised)
/// problem of one outer iteration at the given shared positions X, with rotations taken from X.
struct JointFlattenProblem {
  ConvexSubproblem subproblem;  ///< rotations filled by set_rotations()
  Eigen::MatrixXd X0;           ///< #slots by 2 start (boundary slots first, in boundary order)
  std::array<Eigen::MatrixXi, 2> F;
  std::array<FlatteningStartCandidate, 2> start;  ///< each disk's start (flattening_start)
  std::array<int, 2> start_steps{};               ///< Newton steps of each disk's start_optimization
  JointStartRelaxation joint_start;               ///< the joint relaxation of the start
  double scale_m = 1, scale_n = 1;
  /// The relaxation's factorisation, analysed for its system (null if it did not run): the convex subproblems reuse
  /// the analysis where their system has the same pattern (SparseCholesky::has_pattern_of).
  std::shared_ptr<SparseCholesky> cholesky;
};

/// Normalises, validates, builds the slots and ghost faces, and computes the start (flattening_start).
JointFlattenProblem make_joint_flatten_problem(const FlatteningDisk& m, const FlatteningDisk& n,
                                               const JointFlattenOptions& options);

/// Places every ghost vertex afresh for the subproblem at X, and makes that placement the ghost faces' rest shape:
/// g on the bisector of the exterior wedge at its boundary vertex v, at half the mean length of v's two boundary
/// edges. The ghost faces thus start as well-shaped triangles with identity Jacobians in every outer iteration.
/// Ghost vertices carry no energy and are not part of the output, so each subproblem may choose them anew; kept
/// from one subproblem to the next, they drift outwards by up to the stretch bound's factor (kGhostStretch) per
/// outer iteration, and the needle-like faces limit the Newton steps. No-op without ghost faces.
void place_ghost_vertices(ConvexSubproblem& problem, Eigen::MatrixXd& X);

/// Sets every face's rotation (both meshes and ghosts) to the polar rotation of its Jacobian at X.
void set_rotations(ConvexSubproblem& problem, const Eigen::MatrixXd& X);

/// The flattening of mesh k (0 or 1) of the problem at X, #V by 2.
Eigen::MatrixXd mesh_positions(const ConvexSubproblem& problem, int k, const Eigen::MatrixXd& X);

}  // namespace liftmap
