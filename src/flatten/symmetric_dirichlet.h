#pragma once
/// Flip-free minimisation of the symmetric Dirichlet energy of a flattening with fixed boundary: the
/// pre-optimisation of the joint flattening's start (flattening_start.h, docs/algorithm.md).

#include <Eigen/Core>
#include <vector>

#include "flatten/jacobian.h"

namespace liftmap {

/// Settings of minimize_symmetric_dirichlet.
struct SymmetricDirichletOptions {
  int max_iterations = 30;          ///< projected Newton steps at most
  double relative_decrease = 1e-2;  ///< stop once a step lowers the energy by less than this, relatively
};

/// Result of minimize_symmetric_dirichlet.
struct SymmetricDirichletResult {
  Eigen::MatrixXd U;        ///< #V by 2 positions, every face positively oriented, fixed vertices unchanged
  double energy_start = 0;  ///< E at the given positions
  double energy = 0;        ///< E at U
  int iterations = 0;       ///< Newton steps taken
};

/// Lowers E(U) = sum_f area_f (|J_f|^2 + |J_f^-1|^2 - 4), J_f the Jacobian of face f (JacobianOperator), by
/// projected Newton (every face's 4 by 4 Hessian in J clamped to its positive semidefinite part, Teran et al.
/// 2005): each step is cut to 0.8 of the largest step that keeps every face's determinant positive (the roots of
/// det(J + a dJ), a quadratic in a) and then backtracked until Armijo's condition holds. E is infinite at a
/// flipped or degenerate face, so no step ever flips one. The vertices with fixed[v] != 0 do not move.
/// \param op, F the mesh's Jacobian operator and #F by 3 faces
/// \param fixed #V flags (boundary and isolated vertices)
/// \param U0 #V by 2 positions with every face positively oriented
/// \throw InvalidInputError if sizes disagree or a face of U0 is not positively oriented.
SymmetricDirichletResult minimize_symmetric_dirichlet(const JacobianOperator& op, const Eigen::MatrixXi& F,
                                                      const std::vector<char>& fixed, const Eigen::MatrixXd& U0,
                                                      const SymmetricDirichletOptions& options = {});

}  // namespace liftmap
