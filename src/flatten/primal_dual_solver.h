#pragma once
/// The convex subproblem (10) of Algorithm 2 (paper §3.3), solved by a primal-dual interior-point method with
/// Nesterov-Todd scaling and Mehrotra's predictor-corrector, on Eigen + CHOLMOD.

#include <Eigen/Core>

#include "flatten/barrier_solver.h"
#include "flatten/sparse_cholesky.h"

namespace liftmap {

/// Solves problem (10) from a strictly feasible start, written as a second-order-cone program in the form of
/// Vandenberghe's "The CVXOPT linear and quadratic cone program solvers" (2010): per face, the cones
///   c >= |(gamma, delta)|,
///   eq. 3:  r - c >= |(alpha, beta)|,  s m >= 1 (m = alpha cos + beta sin - c, a rotated cone),  e >= |(r, s)|,
///   eq. 2:  e - c >= |(alpha, beta)|,  e m >= 1,
///   ghost faces: c >= |(gamma, delta)|, kGhostStretch-bound - c >= |(alpha, beta)|, m >= 0,
/// and the objective T_0 + T_1 with T_m >= |(sqrt(w_j) e_j)_j| (p = 2) or e_j = T_m (p = inf).
/// The primal iterate stays strictly feasible (the slacks are recomputed from the positions every iteration, and
/// every step stays inside all cones): every iterate has sigma_tilde_j > 0 on every face. The dual starts infeasible
/// and its residual shrinks by (1 - step) per iteration. Each iteration factorises ONE sparse SPD matrix in the vertex
/// coordinates (the per-face auxiliaries eliminated by their Schur complements, the global coupling of (10a) by a
/// bordered system and a Woodbury correction) and solves it twice (predictor, corrector).
/// Every Newton solve is iteratively refined against H = A^T W^-2 A formed cone by cone, so that the dual residual
/// stays at the level of rounding instead of growing with the conditioning of the eliminated system.
/// Stops when the gap s^T z is below `relative_gap` times the objective and the dual residual |A^T z - c| is below
/// 1e-7 of the size of its terms (converged = true). Stops uncertified (converged = false, stalled_centrings = 1) at
/// the limit of double precision: two steps in a row shorter than 1e-3, no progress over five iterations, or a
/// Newton system that no longer factorises; for p = 2 this happens near relative gaps of 1e-7 (the objective cones
/// nearly active), for p = inf near 1e-8..1e-9 (docs/performance.md). It then returns the dual-feasible iterate
/// with the smallest gap, and gap_bound is that iterate's gap: an honest bound of objective minus optimum
/// (+infinity if no iterate was dual feasible). The iterate returned is always strictly feasible.
/// Of BarrierOptions it uses `relative_gap`, `max_newton_steps` (iterations) and `on_step`, called after every
/// iteration with centring = the iteration's index, t = 1 / mu (mu = s^T z / degree), lambda2 = the relative dual
/// residual, step = the step length. BarrierResult::newton_steps counts iterations.
/// \throw InvalidInputError if X0 is not strictly feasible; PipelineError if a step is not finite.
/// `cache` as for solve_convex_subproblem.
BarrierResult solve_convex_subproblem_primal_dual(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                                  const BarrierOptions& options, SparseCholesky& cholesky,
                                                  subproblem::AssemblyStructure* cache = nullptr);

}  // namespace liftmap
