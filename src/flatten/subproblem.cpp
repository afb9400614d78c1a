#include "flatten/subproblem.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "flatten/jacobian.h"

namespace liftmap {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// E_j = h(Sigma_j, 1 / sigma_tilde_j) of a face whose Jacobian has similarity coordinates a = (alpha, beta, gamma,
/// delta), rotated by (cs, sn); +infinity if sigma_tilde_j <= 0.
double face_energy(const Eigen::Vector4d& a, double cs, double sn, bool h_max) {
  const double n = std::hypot(a(0), a(1));
  const double c = std::hypot(a(2), a(3));
  const double st = a(0) * cs + a(1) * sn - c;
  if (!(st > 0)) return kInf;
  return h_max ? std::max(n + c, 1.0 / st) : std::hypot(n + c, 1.0 / st);
}

}  // namespace

double subproblem_objective(const ConvexSubproblem& problem, const Eigen::MatrixXd& X) {
  const bool h_max = problem.h == DistortionCombiner::kMax;
  double total = 0;
  for (const SubproblemMesh& mesh : problem.meshes) {
    double acc = 0;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      Vec6 u;
      for (int k = 0; k < 3; ++k) u.segment<2>(2 * k) = X.row(mesh.slot[static_cast<size_t>(mesh.F(f, k))]).transpose();
      const Eigen::Vector4d a = similarity_map(mesh.jacobian.G.row(f)) * u;
      const double E = face_energy(a, std::cos(mesh.theta(f)), std::sin(mesh.theta(f)), h_max);
      if (std::isinf(problem.p)) {
        acc = std::max(acc, E);
      } else {
        acc += mesh.jacobian.area(f) * E * E;
      }
    }
    total += std::isinf(problem.p) ? acc : std::sqrt(acc);
  }
  return total;
}

std::string to_string(SubproblemStatus status) {
  switch (status) {
    case SubproblemStatus::kConverged:
      return "converged";
    case SubproblemStatus::kIterationLimit:
      return "iteration limit";
    case SubproblemStatus::kStalled:
      return "stalled";
    case SubproblemStatus::kNotFactorizable:
      return "not factorizable";
  }
  return "unknown";
}

}  // namespace liftmap
