#pragma once
/// Flip-free minimisation of the symmetric Dirichlet energy of a flattening with fixed boundary: the
/// pre-optimisation of the joint flattening's start (flattening_start.h, docs/algorithm.md).

#include <Eigen/Core>
#include <vector>

#include "flatten/jacobian.h"
#include "flatten/sparse_cholesky.h"

namespace liftmap {

/// Settings of minimize_symmetric_dirichlet.
struct SymmetricDirichletOptions {
  int max_iterations = 30;          ///< projected Newton steps at most
  double relative_decrease = 1e-2;  ///< stop once a step lowers the energy by less than this, relatively
  /// Apply relative_decrease only to steps that the flip barrier did not shorten. A Newton step cut short before a
  /// face flips lowers E little because that face is nearly crushed, not because E is near its minimum: such a
  /// step does not end the minimisation (max_iterations still bounds it).
  bool only_full_steps_stop = false;
  /// Steps along the reweighted proxy's direction (symmetric_dirichlet_proxy_derivatives) instead of projected
  /// Newton's while each lowers E by at least this fraction of it; from the first that lowers it less (or fails to
  /// lower it), projected Newton. A proxy step never ends the minimisation. 0: projected Newton throughout.
  /// From a crushed start a proxy step moves a face most of the way to its rest shape where projected Newton
  /// grows its small singular value by a third (docs/algorithm.md, "Reweighted proxy steps").
  double proxy_while_decrease = 0;
};

/// Result of minimize_symmetric_dirichlet.
struct SymmetricDirichletResult {
  Eigen::MatrixXd U;        ///< #V (or #slots) by 2 positions, every face positively oriented, fixed ones unchanged
  double energy_start = 0;  ///< E at the given positions
  double energy = 0;        ///< E at U
  int iterations = 0;       ///< steps taken (proxy steps included)
  int proxy_steps = 0;      ///< of which along the reweighted proxy's direction
};

/// One mesh's part of a symmetric Dirichlet energy over shared unknowns X (#slots by 2): several meshes whose
/// vertices share slots (the joint flattening's common boundary) are lowered together.
struct SymmetricDirichletTerm {
  const JacobianOperator* jacobian = nullptr;  ///< the mesh's Jacobian operator (its rest shape)
  const Eigen::MatrixXi* F = nullptr;          ///< #F by 3 vertex indices
  const std::vector<int>* slot = nullptr;      ///< #V: the row of X holding the vertex's position
  double weight = 1;                           ///< the term's factor in E (positive)
  /// Solve again for the term's own unknowns (those no other term touches) from its own faces, once the Newton step
  /// of the shared ones is known: H_oo d_o = -(g_o + H_os d_s), the same equation as the joint solve's rows, so the
  /// step is mathematically unchanged. Two terms with the same data then get bitwise the same step, whatever order
  /// the joint factorisation eliminates their unknowns in (a mesh mapped onto a copy of itself stays the identity).
  /// Done only for a term whose data (faces' rest shapes and factors, own and shared unknowns) equal another
  /// own_solve term's: for any other the joint step serves, and the second factorisation would double the cost.
  bool own_solve = false;
};

/// Lowers E(X) = sum over the terms of weight * sum_f area_f (|J_f|^2 + |J_f^-1|^2 - 4) as the single-mesh
/// overload below does, over the rows of X whose fixed flag is 0 (the others do not move).
/// \param fixed #slots flags; \param X0 #slots by 2 positions with every face of every term positively oriented
/// \param cholesky if given, the factorisation to use: its analysis is reused if it has this system's pattern, and
///        left analysed for it on return (a later solver with the same pattern can then skip its own analysis)
/// \throw InvalidInputError if sizes disagree, a corner has no slot, a weight is not positive or a face of X0 is not
///        positively oriented.
SymmetricDirichletResult minimize_symmetric_dirichlet(const std::vector<SymmetricDirichletTerm>& terms,
                                                      const std::vector<char>& fixed, const Eigen::MatrixXd& X0,
                                                      const SymmetricDirichletOptions& options = {},
                                                      SparseCholesky* cholesky = nullptr);

/// Lowers E(U) = sum_f area_f (|J_f|^2 + |J_f^-1|^2 - 4), J_f the Jacobian of face f (JacobianOperator), by
/// projected Newton (every face's 4 by 4 Hessian in J clamped to its positive semidefinite part, Teran et al.
/// 2005), after the reweighted proxy's steps that options.proxy_while_decrease asks for (each face's Hessian
/// replaced by its proxy's: the same gradient, a positive definite matrix). Each step is cut to 0.9 of the largest
/// step that keeps every face's determinant positive (the roots of det(J + a dJ), a quadratic in a) and then
/// backtracked until Armijo's condition holds. E is infinite at a flipped or degenerate face, so no step ever flips
/// one. The vertices with fixed[v] != 0 do not move.
/// \param op, F the mesh's Jacobian operator and #F by 3 faces
/// \param fixed #V flags (boundary and isolated vertices)
/// \param U0 #V by 2 positions with every face positively oriented
/// \throw InvalidInputError if sizes disagree or a face of U0 is not positively oriented.
SymmetricDirichletResult minimize_symmetric_dirichlet(const JacobianOperator& op, const Eigen::MatrixXi& F,
                                                      const std::vector<char>& fixed, const Eigen::MatrixXd& U0,
                                                      const SymmetricDirichletOptions& options = {});

}  // namespace liftmap
