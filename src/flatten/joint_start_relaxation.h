#pragma once
/// The joint relaxation of the flattening start: both disks lowered together in the symmetric Dirichlet energy,
/// their common boundary free (docs/algorithm.md, "Joint relaxation with a free common boundary").
///
/// The Tutte start puts the common boundary on the unit circle, spaced by arc length. The optimum of the outer
/// loop has a very different boundary (long thin parts of a disk's boundary stretched, cut paths' tips folded
/// inwards), so the first convex subproblem from the circle has most of the way to go and costs several times the
/// others. The relaxation moves every position of both disks, boundary included, by projected Newton on
///   E(X) = E_sd(Phi) + E_sd(Psi) + w_g E_sd(ghost faces),
/// E_sd = sum_f area_f (|J_f|^2 + |J_f^-1|^2 - 4), each step cut before any face of either disk or any ghost face
/// flips (minimize_symmetric_dirichlet). Corresponding boundary vertices share their position (the slots of
/// ConvexSubproblem), so the boundary stays common; the ghost faces, which close every boundary vertex's one-ring,
/// stay positively oriented, so every boundary angle sum stays below 2 pi: the result is a feasible start of
/// problem (10).

#include <Eigen/Core>

#include "flatten/subproblem.h"
#include "flatten/symmetric_dirichlet.h"

namespace liftmap {

/// Settings of relax_joint_start.
struct JointStartRelaxationOptions {
  /// Projected Newton steps at most (0: off, the paper's start on the circle), and the relative decrease of E below
  /// which a full step ends the relaxation; a step shortened so that no face flips does not end it (a start with
  /// crushed faces crawls through such steps before E falls by orders of magnitude). Each disk's own unknowns are
  /// solved for from its own faces (SymmetricDirichletTerm::own_solve), so two identical disks stay bitwise
  /// identical: a mesh mapped onto a copy of itself scaled by a power of two is the identity to rounding.
  /// Projected Newton throughout, as for the per-disk pre-optimisation (JointFlattenOptions::start_optimization).
  SymmetricDirichletOptions newton{.max_iterations = 300, .relative_decrease = 1e-3, .only_full_steps_stop = true};
  /// w_g: the ghost faces' weight, relative to the disks' faces. Their rest shape is their placement at the start
  /// (place_ghost_vertices); they hold no energy of the map and are re-placed before every subproblem.
  double ghost_weight = 0.1;
};

/// Lowers E(X) above from X0, keeping slot 0 in place (E is invariant under translation). The ghost faces' rest
/// shape is problem.ghosts' (the caller re-places the ghosts for the result, place_ghost_vertices).
/// \param problem the joint problem (both meshes' slots and Jacobian operators; ghost faces, if any, placed for X0)
/// \param X0 #slots by 2 positions, every face of both disks and every ghost face positively oriented
/// \param cholesky as minimize_symmetric_dirichlet()'s: left analysed for the relaxation's system, whose pattern is
///        the convex subproblems' (joint_flatten reuses it)
/// \return U: the relaxed positions (#slots by 2), with the energies before and after and the Newton steps taken
/// \throw InvalidInputError as minimize_symmetric_dirichlet().
SymmetricDirichletResult relax_joint_start(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                           const JointStartRelaxationOptions& options = {},
                                           SparseCholesky* cholesky = nullptr);

}  // namespace liftmap
