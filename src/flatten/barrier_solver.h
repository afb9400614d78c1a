#pragma once
/// The convex subproblem (10) of Algorithm 2 (paper §3.3), solved by our own barrier method on Eigen + CHOLMOD.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "flatten/distortion.h"
#include "flatten/jacobian.h"
#include "flatten/sparse_cholesky.h"

namespace liftmap {

namespace subproblem {
struct AssemblyStructure;
}

/// One flattening of the pair in problem (10): its faces, Jacobian operator, fixed rotations R_j of eq. (7b),
/// and where each vertex's position lives in the shared unknowns.
struct SubproblemMesh {
  Eigen::MatrixXd V;          ///< #V by 3 rest positions (normalised) that `jacobian` was built from
  Eigen::MatrixXi F;          ///< #F by 3 vertex indices
  JacobianOperator jacobian;  ///< jacobian_operator(V, F)
  Eigen::VectorXd theta;      ///< #F rotation angles of eq. (7b)
  std::vector<int> slot;      ///< #V: row of the vertex's position in the unknowns X; corresponding boundary
                              ///< vertices of the two meshes share a row, which realises constraint (10b)
};

/// Problem (10): minimise E(Phi) + E(Psi) over the shared unknown positions X (#slots by 2), with
/// E = sqrt(sum_j |t_j| E_j^2) (p = 2) or max_j E_j (p = inf), E_j = h(Sigma_j, 1/sigma_tilde_j) (docs/algorithm.md).
struct ConvexSubproblem {
  std::array<SubproblemMesh, 2> meshes;
  /// Constraint-only faces (no energy): sigma_tilde_j > 0 and Sigma_j <= kGhostStretch * Sigma_j(X0) on each
  /// (the bound keeps the ghost vertices, which no energy holds, in a bounded region). The paper's ghost
  /// faces, two per boundary vertex, closing its one-ring through an extra ghost vertex so that its angle sum
  /// stays below 2 pi.
  SubproblemMesh ghosts;
  int n_slots = 0;                                   ///< rows of X
  double p = 2;                                      ///< 2 or infinity
  DistortionCombiner h = DistortionCombiner::kNorm;  ///< eq. (3) by default
};

/// Bound of the ghost faces' largest singular value, relative to its value at the start of the subproblem.
inline constexpr double kGhostStretch = 10;

/// One Newton step of the barrier method, for profiling (BarrierOptions::on_step).
struct BarrierStep {
  int centring = 0;                  ///< index of the centring (barrier parameter value) the step belongs to
  double t = 0;                      ///< barrier parameter
  double lambda2 = 0;                ///< squared Newton decrement before the step
  double step = 0;                   ///< step length taken (0: none, the centring ends)
  bool repaired = false;             ///< the step came from the line search with repaired auxiliaries
  bool isotropic = false;            ///< the step's system had isotropic (gamma, delta) curvature (BarrierOptions)
  double objective = 0;              ///< objective f0 of the auxiliaries after the step
  double seconds = 0;                ///< wall time of the step (derivatives, factorisation, solve, line search)
  double seconds_derivatives = 0;    ///< of which per-face derivatives and assembly
  double seconds_factorization = 0;  ///< of which the sparse factorisation (with diagonal shifts if needed)
  double seconds_line_search = 0;    ///< of which the line search (0 if the step ended the centring)
};

/// Settings of the barrier method.
struct BarrierOptions {
  /// Stop when the duality-gap bound nu/t is below this times the objective. 1e-8 is reached reliably on a
  /// few thousand faces; beyond, the Newton systems at t ~ 1e11 approach double-precision limits.
  double relative_gap = 1e-8;
  /// The first centring's barrier parameter, relative to the t that best centres the start (the t where the
  /// gradients of t f0 and of the barrier balance along f0's own directions). Every centring costs ~10 Newton
  /// steps, but those at low t only lead towards a region that a centring at a higher t reaches from the start in
  /// about as many: a factor of 100 skips two of the 6-7 centrings (camel-cow, man-homer, sphere-ellipsoid: 20-25%
  /// fewer Newton steps); at 1e4 the first centring took 300-400 steps. p = 2 only: p = inf, with its
  /// fraction-to-the-boundary repairs, needed 1.3-2.5 times more steps from the higher start on the CVXOPT test
  /// instances, and one ran out of steps.
  double initial_barrier_factor = 100;
  double barrier_growth = 20;  ///< t <- barrier_growth * t after each centring
  /// p = 2: if positive, the first barrier parameter is at least the one whose gap bound nu / t is this times the
  /// objective at the start (0: initial_barrier_factor alone decides). For a start that is already nearly optimal,
  /// such as the previous outer iteration's minimiser, whose central point at a low t lies far back towards the
  /// analytic centre (joint_flatten sets it; JointFlattenOptions::start_gap_fraction).
  double initial_gap = 0;
  /// The last centring (the one that can certify the gap) stops when the Newton decrement lambda^2/2 is below this,
  /// or earlier, once lambda^2/2 is below centring_tolerance and the gap bound at the point,
  /// (nu + lambda sqrt(nu) / (1 - lambda)) / t, meets relative_gap: the certificate is then already in hand, and
  /// polishing the decrement further cost late outer iterations of camel-cow 10-12 Newton steps (steps 58/67/61 ->
  /// 48/50/52 in outer iterations 7-9, flattening 60.0 -> 51.7 s, energies equal to 6 digits).
  double newton_tolerance = 1e-7;
  /// p = 2 (p = inf keeps 1/8): earlier centrings stop after the step from a point where lambda^2/2 is below this
  /// (lambda <= 2): polishing them
  /// to newton_tolerance cost 2-4 Newton steps each, and the next barrier parameter starts with decrements of ~1e7
  /// whatever the polish. The last centring's early stop (newton_tolerance) also reads it, but its gap bound needs
  /// lambda < 1 anyway. It was 1/8 (lambda <= 1/2, the textbook long-step proximity); near there full Newton steps
  /// still only halved lambda^2 each. Side by side (profile_flatten, 10 outer iterations; final energies equal to
  /// 6 digits), Newton steps for camel-cow / man-homer / fandisk-bunny: 1/8: 287 / 334 / 170, 1/2: 275 / 321 / 163,
  /// 2: 264 / 310 / 157, 4: 262 / 310 / 159, 20: 261 / 314 / 165.
  double centring_tolerance = 2;
  /// A centring ends, centred, when lambda^2/2 is below this and the line search cannot take the full Newton
  /// step (which it would in exact arithmetic: the merit t f0 + barrier has reached the limit of double
  /// precision, seen at t ~ 1e8 on whole-mesh disks). With lambda < 1 the gap is still bounded, by
  /// (nu + lambda sqrt(nu) / (1 - lambda)) / t. At 1e-2, camel-cow's last centring crawled 8 steps at lengths
  /// of 1e-10 with lambda^2/2 = 0.013.
  double precision_tolerance = 0.125;
  /// p = 2: after a Newton step that Armijo's condition shortened (not feasibility), the next step's system gives
  /// every face's (gamma, delta) block of its Schur complement isotropic curvature, its smaller eigenvalue raised to
  /// the larger. The barrier smooths the kink of |(gamma, delta)| at a scale of ~1/t; on nearly conformal faces the
  /// Newton model of that smoothed kink has almost no curvature along (gamma, delta) and overshoots (as Newton's
  /// method does on a pseudo-Huber function), and late centrings crawled at steps of 1/16 and 1/32 while f0 changed
  /// in the sixth digit. The raised curvature is that of the majoriser of |.|. Only after merit-limited steps:
  /// applied to every damped step (an earlier experiment), it doubled camel-cow's first subproblem, whose damped
  /// steps are limited by faces that would flip. The stopping tests use true Newton steps only. Side by side
  /// (profile_flatten, 10 outer iterations, same final energies to 7 digits): man-homer 379 -> 334 Newton steps
  /// (24.4 -> 19.7 s), fandisk-bunny 214 -> 170 (26.7 -> 18.8 s), camel-cow 285 -> 287.
  bool isotropic_anticonformal_curvature = true;
  int max_newton_steps = 400;  ///< in total, over all centrings
  /// Primal-dual method only: iterative refinement steps per Newton solve at most (0: none). See
  /// solve_convex_subproblem_primal_dual.
  int max_refinements = 3;
  std::function<void(const BarrierStep&)> on_step = nullptr;  ///< called after every Newton step if set
};

/// What the barrier method found.
struct BarrierResult {
  Eigen::MatrixXd X;     ///< #slots by 2 minimiser; row `fixed_slot` kept at its start position (the
                         ///< objective is invariant under translation)
  double objective = 0;  ///< objective (10a) at X, auxiliary variables eliminated
  double gap_bound = 0;  ///< (nu + lambda sqrt(nu) / (1 - lambda)) / t at the end (lambda: the last Newton
                         ///< decrement): a bound of objective minus optimum
  int newton_steps = 0;
  int centrings = 0;
  /// Centrings that ended because no step along the Newton direction decreased the merit, before the Newton
  /// decrement reached its tolerance (precision limit); their iterates are feasible but not centred.
  int stalled_centrings = 0;
  bool converged = false;  ///< the gap bound was reached at a centred point; false if max_newton_steps ran out
                           ///< first or the last centring stalled
};

/// Objective (10a) at X with the auxiliary variables eliminated; +infinity if some sigma_tilde_j <= 0.
double subproblem_objective(const ConvexSubproblem& problem, const Eigen::MatrixXd& X);

/// Solves problem (10) from a strictly feasible start with a log-barrier method: second-order-cone barriers on
/// |(gamma,delta)| <= c_j and on the epigraph constraints of E_j (auxiliary c_j, e_j per face, and the two
/// epigraph variables of the max for p = inf), Newton steps in which the per-face auxiliaries are eliminated by
/// a Schur complement so that each step is ONE sparse SPD solve in the vertex coordinates (plus a rank-2 or
/// bordered correction for the global coupling of (10a)), and a line search that never leaves the strictly
/// feasible set: every iterate has sigma_tilde_j > 0, hence det A_j > 0, for all faces.
/// \param X0 #slots by 2 strictly feasible start
/// \param cholesky reused factorisation: analysed on first use, then only refactorised (same problem pattern)
/// \param cache if given, the Newton system's assembly structure, kept for the next subproblem of the same faces
/// \throw InvalidInputError if X0 is not strictly feasible; PipelineError if a Newton step is not finite.
/// If the Newton systems stop factorising (double-precision limit, seen for p = inf near a 1e-8 gap), the
/// method stops at its strictly feasible iterate with converged = false and the reached gap_bound.
BarrierResult solve_convex_subproblem(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                      const BarrierOptions& options, SparseCholesky& cholesky,
                                      subproblem::AssemblyStructure* cache = nullptr);

}  // namespace liftmap
