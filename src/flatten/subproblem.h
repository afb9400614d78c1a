#pragma once
/// The convex subproblem (10) of Algorithm 2 (paper §3.3) as plain data: the problem, the settings of its two
/// solvers (barrier_solver.h, primal_dual_solver.h), one result type with a status, and its objective.

#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "flatten/distortion.h"
#include "flatten/jacobian.h"

namespace liftmap {

namespace subproblem {
struct AssemblyStructure;  // subproblem_faces.h: the Newton system's structure, shared by a flattening's subproblems
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
/// E = sqrt(sum_j |t_j| E_j^2) (p = 2) or max_j E_j (p = inf), E_j = h(Sigma_j, 1/sigma_tilde_j) (docs/algorithm.md),
/// subject to sigma_tilde_j > 0 on every face.
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

/// Objective (10a) at X (#slots by 2) with the auxiliary variables eliminated; +infinity if some sigma_tilde_j <= 0.
double subproblem_objective(const ConvexSubproblem& problem, const Eigen::MatrixXd& X);

/// One iteration of a solver, for progress and profiling (SubproblemSettings::on_step).
struct SubproblemStep {
  int centring = 0;        ///< barrier: index of the centring the Newton step belongs to; primal-dual: iteration index
  double t = 0;            ///< barrier: the barrier parameter; primal-dual: 1 / mu (mu = s^T z / degree)
  double lambda2 = 0;      ///< barrier: squared Newton decrement before the step; primal-dual: relative dual residual
  double step = 0;         ///< step length taken (0: none; barrier: the centring ends)
  bool repaired = false;   ///< barrier: the step came from the line search with repaired auxiliaries
  bool isotropic = false;  ///< barrier: the step's system had isotropic (gamma, delta) curvature
  double objective = 0;    ///< objective f0 of the auxiliaries after the step
  double seconds = 0;      ///< wall time of the iteration
  double seconds_derivatives = 0;    ///< of which derivatives, scalings and assembly
  double seconds_factorization = 0;  ///< of which the sparse factorisation (with diagonal shifts if needed)
  double seconds_line_search = 0;    ///< of which the line search or the step (0 if the step ended a centring)
};

/// Settings of the barrier method (barrier_solver.h). What each value was measured against is in
/// docs/performance.md ("Barrier method settings").
struct BarrierSettings {
  /// The first centring's barrier parameter, relative to the t that best centres the start (the t where the
  /// gradients of t f0 and of the barrier balance along f0's own directions). p = 2 only.
  double initial_barrier_factor = 100;
  double barrier_growth = 20;  ///< t <- barrier_growth * t after each centring (p = 2: clamped, see solve())
  /// p = 2: if positive, the first barrier parameter is at least the one whose gap bound nu / t is this times the
  /// objective at the start (0: initial_barrier_factor alone decides): for a start that is already nearly optimal,
  /// such as the previous outer iteration's minimiser (JointFlattenOptions::start_gap_fraction).
  double initial_gap = 0;
  /// The last centring (the one that can certify the gap) stops when the Newton decrement lambda^2/2 is below this,
  /// or earlier, once lambda^2/2 is below centring_tolerance and the gap bound at the point,
  /// (nu + lambda sqrt(nu) / (1 - lambda)) / t, meets relative_gap.
  double newton_tolerance = 1e-7;
  /// p = 2 (p = inf uses 1/8): earlier centrings stop after the step from a point where lambda^2/2 is below this.
  double centring_tolerance = 2;
  /// A centring ends, centred, when lambda^2/2 is below this and the line search cannot take the full Newton step
  /// (which it would in exact arithmetic): the merit has reached the limit of double precision.
  double precision_tolerance = 0.125;
  /// p = 2: after a Newton step that Armijo's condition shortened (not feasibility), the next step's system gives
  /// every face's (gamma, delta) block of its Schur complement isotropic curvature, its smaller eigenvalue raised to
  /// the larger (the curvature of the majoriser of |.|, which the barrier smooths at a scale of ~1/t). The stopping
  /// tests use true Newton steps only.
  bool isotropic_anticonformal_curvature = true;
  /// p = 2, h of eq. 3: in the last centring, every true Newton step whose lambda^2/2 is at most this first builds a
  /// dual point from its direction (newton_dual_gap.h) and ends the centring if that point's gap meets relative_gap;
  /// the decrement need not fall below 1. 0: off (the gap bound of newton_tolerance alone).
  double dual_gap_decrement = 1e4;
};

/// Settings of the primal-dual method (primal_dual_solver.h).
struct PrimalDualSettings {
  int max_refinements = 3;  ///< iterative refinement steps per Newton solve at most (0: none)
};

/// Settings of a subproblem solve: the common part, then each method's own.
struct SubproblemSettings {
  /// Stop when the certified gap is below this times the objective (the barrier method: times T_0 + T_1 at the
  /// point, which exceeds the objective by at most the gap). 1e-8 is reached reliably on a few thousand faces;
  /// beyond, the Newton systems approach double-precision limits.
  double relative_gap = 1e-8;
  int max_iterations = 400;  ///< Newton steps (barrier, over all centrings) or iterations (primal-dual)
  std::function<void(const SubproblemStep&)> on_step = nullptr;  ///< called after every iteration if set
  BarrierSettings barrier;
  PrimalDualSettings primal_dual;
};

/// Why a subproblem solve ended.
enum class SubproblemStatus {
  kConverged,        ///< the gap bound met relative_gap at a certified point
  kIterationLimit,   ///< max_iterations ran out first
  kStalled,          ///< no progress at the limit of double precision (short steps, failed line searches)
  kNotFactorizable,  ///< the Newton system no longer factorised, even with diagonal shifts
};

/// "converged", "iteration limit", "stalled" or "not factorizable".
std::string to_string(SubproblemStatus status);

/// What a solver found. The iterate returned is always strictly feasible.
struct SubproblemResult {
  Eigen::MatrixXd X;     ///< #slots by 2 minimiser; the fixed gauge slot kept at its start position (the
                         ///< objective is invariant under translation)
  double objective = 0;  ///< objective (10a) at X, auxiliary variables eliminated
  /// A bound of objective minus optimum: barrier (nu + lambda sqrt(nu) / (1 - lambda)) / t at the end (lambda: the
  /// last Newton decrement), or the gap of the dual point built from the last Newton direction if that was lower
  /// (BarrierSettings::dual_gap_decrement); primal-dual the gap s^T z of the best dual-feasible iterate (+infinity if
  /// none).
  double gap_bound = 0;
  int iterations = 0;  ///< Newton steps (barrier) or iterations (primal-dual)
  int centrings = 0;   ///< barrier: centrings run (primal-dual: 0)
  /// Barrier: centrings that ended because no step along the Newton direction decreased the merit before the
  /// decrement reached its tolerance (their iterates are feasible but not centred). Primal-dual: 0.
  int stalled_centrings = 0;
  SubproblemStatus status = SubproblemStatus::kIterationLimit;
  [[nodiscard]] bool converged() const { return status == SubproblemStatus::kConverged; }
};

}  // namespace liftmap
