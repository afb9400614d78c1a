#pragma once
/// The face energy of eq. 3 at the auxiliary c, R = |(n + c, 1 / m)| (n = |(alpha, beta)|, m = alpha cos + beta sin
/// - c), with its derivatives: the barrier method's epigraph term e >= R (barrier_solver.cpp) and the dual point built
/// from its Newton direction (newton_dual_gap.cpp) both differentiate it.

#include <Eigen/Core>
#include <cmath>

namespace liftmap::subproblem {

/// R and its gradient and Hessian in (alpha, beta, c, e) (R does not depend on e: its row and column are 0).
struct EpigraphNorm {
  double R = 0;
  Eigen::Vector4d d = Eigen::Vector4d::Zero();
  Eigen::Matrix4d d2 = Eigen::Matrix4d::Zero();
};

/// R = |(r, s)|, r = n + c, s = 1 / m, at (alpha, beta, c) with the face's rotation (cs, sn) = (cos, sin). With
/// dr = grad n + grad c and ds = -grad m / m^2: grad R = (r dr + s ds) / R and
/// hess R = (dr dr^T + r hess n + ds ds^T + s hess s - grad R grad R^T) / R, where ds ds^T + s hess s = 3 dm dm^T /
/// m^4. \pre n > 0 and m > 0
inline EpigraphNorm epigraph_norm(double al, double be, double c, double cs, double sn) {
  EpigraphNorm out;
  const double n = std::sqrt(al * al + be * be);
  const double m = al * cs + be * sn - c;
  const double r = n + c, sv = 1.0 / m;
  out.R = std::sqrt(r * r + sv * sv);
  const Eigen::Vector4d dr(al / n, be / n, 1, 0);
  const Eigen::Vector4d dm(cs, sn, -1, 0);
  const Eigen::Vector4d ds = -dm * (sv * sv);
  out.d = (r * dr + sv * ds) / out.R;
  out.d2 = dr * dr.transpose() + (3 * sv * sv * sv * sv) * dm * dm.transpose() - out.d * out.d.transpose();
  const double n3 = n * n * n;
  out.d2(0, 0) += r * be * be / n3;
  out.d2(1, 1) += r * al * al / n3;
  out.d2(0, 1) -= r * al * be / n3;
  out.d2(1, 0) -= r * al * be / n3;
  out.d2 /= out.R;
  return out;
}

}  // namespace liftmap::subproblem
