#include "flatten/joint_start_relaxation.h"

#include <vector>

namespace liftmap {

SymmetricDirichletResult relax_joint_start(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                           const JointStartRelaxationOptions& options, SparseCholesky* cholesky) {
  std::vector<SymmetricDirichletTerm> terms;
  for (const SubproblemMesh& mesh : problem.meshes) {
    terms.push_back({.jacobian = &mesh.jacobian, .F = &mesh.F, .slot = &mesh.slot, .weight = 1, .own_solve = true});
  }
  if (problem.ghosts.F.rows() > 0) {
    const SubproblemMesh& g = problem.ghosts;
    terms.push_back({.jacobian = &g.jacobian, .F = &g.F, .slot = &g.slot, .weight = options.ghost_weight});
  }
  std::vector<char> fixed(static_cast<size_t>(X0.rows()), 0);
  if (!fixed.empty()) fixed[0] = 1;
  return minimize_symmetric_dirichlet(terms, fixed, X0, options.newton, cholesky);
}

}  // namespace liftmap
