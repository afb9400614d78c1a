#pragma once
/// Export of one convex subproblem (10) and our solution, for the differential test against CVXOPT.

#include <Eigen/Core>
#include <string>

#include "flatten/barrier_solver.h"

namespace liftmap {

/// Writes a JSON instance: for each of the two meshes and the ghost faces, the rest positions V (#V by 3), faces
/// F, slot of each vertex and rotation angle of each face; p ("2" or "inf"), h ("norm" or "max"), the start X0,
/// our minimiser X (#slots by 2; slot 0 is held fixed) and objective; with `primal_dual`, also the primal-dual
/// solver's minimiser and objective (key "primal_dual": X, objective, iterations, converged).
/// \throw IoError if the file cannot be written.
void export_subproblem(const std::string& path, const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                       const SubproblemResult& result, const SubproblemResult* primal_dual = nullptr);

}  // namespace liftmap
