#pragma once
/// The convex subproblem (10) of Algorithm 2 (paper §3.3), solved by a log-barrier method on Eigen + CHOLMOD.

#include <Eigen/Core>

#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem.h"

namespace liftmap {

/// Solves problem (10) from a strictly feasible start with a log-barrier method (Boyd and Vandenberghe, §11.3):
/// second-order-cone barriers on |(gamma,delta)| <= c_j and on the epigraph constraints of E_j (auxiliary c_j, e_j
/// per face, and the two epigraph variables of the max for p = inf, or of the objective cones
/// T_m >= |(sqrt(w_j) e_j)_j| for p = 2), minimising t (T_0 + T_1) + barrier for a growing t. Newton steps in which the
/// per-face auxiliaries are eliminated by a Schur complement, so that each step is ONE sparse SPD solve in the vertex
/// coordinates (plus a rank-2 or bordered correction for the global coupling of (10a)), and a line search that never
/// leaves the strictly feasible set: every iterate has sigma_tilde_j > 0, hence det A_j > 0, for all faces.
/// Uses settings.relative_gap, max_iterations (Newton steps), on_step and settings.barrier.
/// \param X0 #slots by 2 strictly feasible start
/// \param cholesky reused factorisation: analysed on first use, then only refactorised (same problem pattern)
/// \param cache if given, the Newton system's assembly structure, kept for the next subproblem of the same faces
/// \return status kConverged once the gap bound (nu + lambda sqrt(nu) / (1 - lambda)) / t meets relative_gap at a
/// centred point; kNotFactorizable if the Newton systems stop factorising (double-precision limit, seen for p = inf
/// near a 1e-8 gap), kStalled if centrings keep stalling, each at its strictly feasible iterate with the gap bound
/// reached; kIterationLimit if max_iterations ran out.
/// \throw InvalidInputError if X0 is not strictly feasible; PipelineError if a Newton step is not finite.
SubproblemResult solve_convex_subproblem(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                         const SubproblemSettings& settings, SparseCholesky& cholesky,
                                         subproblem::AssemblyStructure* cache = nullptr);

}  // namespace liftmap
