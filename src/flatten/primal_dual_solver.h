#pragma once
/// The convex subproblem (10) of Algorithm 2 (paper §3.3), solved by a primal-dual interior-point method with
/// Nesterov-Todd scaling and Mehrotra's predictor-corrector, on Eigen + CHOLMOD.

#include <Eigen/Core>

#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem.h"

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
/// Every Newton solve is iteratively refined against H = A^T W^-2 A formed cone by cone (at most
/// settings.primal_dual.max_refinements times), so that the dual residual stays at the level of rounding instead of
/// growing with the conditioning of the eliminated system.
/// Uses settings.relative_gap, max_iterations, on_step (centring = the iteration's index, t = 1 / mu, lambda2 = the
/// relative dual residual, step = the step length) and settings.primal_dual.
/// \return status kConverged when the gap s^T z is below relative_gap times the objective and the dual residual
/// |A^T z - c| is below 1e-7 of the size of its terms; kStalled at the limit of double precision (two steps in a row
/// shorter than 1e-3, or no progress over five iterations), kNotFactorizable if a Newton system no longer
/// factorises, kIterationLimit if max_iterations ran out. Uncertified, it returns the dual-feasible iterate with the
/// smallest gap, and gap_bound is that iterate's gap: an honest bound of objective minus optimum (+infinity if no
/// iterate was dual feasible). The iterate returned is always strictly feasible.
/// \throw InvalidInputError if X0 is not strictly feasible; PipelineError if a step is not finite.
/// `cholesky` and `cache` as for solve_convex_subproblem (barrier_solver.h).
SubproblemResult solve_convex_subproblem_primal_dual(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                                     const SubproblemSettings& settings, SparseCholesky& cholesky,
                                                     subproblem::AssemblyStructure* cache = nullptr);

}  // namespace liftmap
