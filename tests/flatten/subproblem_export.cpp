#include "subproblem_export.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>

#include "core/errors.h"

namespace liftmap {

namespace {

nlohmann::json matrix_json(const Eigen::MatrixXd& M) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    nlohmann::json r = nlohmann::json::array();
    for (Eigen::Index j = 0; j < M.cols(); ++j) r.push_back(M(i, j));
    rows.push_back(std::move(r));
  }
  return rows;
}

nlohmann::json mesh_json(const SubproblemMesh& m) {
  nlohmann::json j;
  j["V"] = matrix_json(m.V);
  j["F"] = matrix_json(m.F.cast<double>());
  j["slot"] = m.slot;
  j["theta"] = std::vector<double>(m.theta.data(), m.theta.data() + m.theta.size());
  return j;
}

}  // namespace

void export_subproblem(const std::string& path, const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                       const SubproblemResult& result, const SubproblemResult* primal_dual) {
  nlohmann::json j;
  j["p"] = std::isinf(problem.p) ? "inf" : "2";
  j["h"] = problem.h == DistortionCombiner::kMax ? "max" : "norm";
  j["n_slots"] = problem.n_slots;
  j["meshes"] = {mesh_json(problem.meshes[0]), mesh_json(problem.meshes[1])};
  j["ghosts"] = mesh_json(problem.ghosts);
  j["X0"] = matrix_json(X0);
  j["X"] = matrix_json(result.X);
  j["objective"] = result.objective;
  j["newton_steps"] = result.iterations;
  if (primal_dual != nullptr) {
    j["primal_dual"] = {{"X", matrix_json(primal_dual->X)},
                        {"objective", primal_dual->objective},
                        {"iterations", primal_dual->iterations},
                        {"converged", primal_dual->converged()}};
  }
  std::ofstream out(path);
  if (!out) throw IoError(path + ": cannot open for writing");
  out << std::setprecision(17) << j.dump();
  if (!out) throw IoError(path + ": write error");
}

}  // namespace liftmap
