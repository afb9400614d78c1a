#include "flatten/symmetric_dirichlet_face.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace liftmap {

namespace {

/// vec(U M V^T), row-major, for M = [m00 m01; m10 m11].
Eigen::Vector4d mode(const Eigen::Matrix2d& U, const Eigen::Matrix2d& V, double m00, double m01, double m10,
                     double m11) {
  Eigen::Matrix2d M;
  M << m00, m01, m10, m11;
  const Eigen::Matrix2d D = U * M * V.transpose();
  return {D(0, 0), D(0, 1), D(1, 0), D(1, 1)};
}

/// J = U diag(s1, s2) V^T with U and V rotations (det J > 0).
struct SingularValues {
  Eigen::Matrix2d U, V;
  double s1 = 0, s2 = 0;
};

SingularValues singular_values(const FaceJacobian& j) {
  Eigen::Matrix2d J;
  J << j(0), j(1), j(2), j(3);
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  SingularValues out{
      .U = svd.matrixU(), .V = svd.matrixV(), .s1 = svd.singularValues()(0), .s2 = svd.singularValues()(1)};
  if (out.U.determinant() < 0) {  // det J > 0: U and V are both reflections; flip both second columns
    out.U.col(1) *= -1;
    out.V.col(1) *= -1;
  }
  return out;
}

/// The scaling modes vec(U diag(1, 0) V^T) and vec(U diag(0, 1) V^T).
std::array<Eigen::Vector4d, 2> scaling_modes(const SingularValues& sv) {
  return {mode(sv.U, sv.V, 1, 0, 0, 0), mode(sv.U, sv.V, 0, 0, 0, 1)};
}

/// d psi / dj = U diag(psi_1, psi_2) V^T = psi_1 d1 + psi_2 d2, psi_i = 2 s_i - 2 s_i^-3 (d: scaling_modes).
Eigen::Vector4d gradient(const SingularValues& sv, const std::array<Eigen::Vector4d, 2>& d) {
  const double psi1 = 2 * sv.s1 - 2 / (sv.s1 * sv.s1 * sv.s1), psi2 = 2 * sv.s2 - 2 / (sv.s2 * sv.s2 * sv.s2);
  return psi1 * d[0] + psi2 * d[1];
}

}  // namespace

double symmetric_dirichlet_energy(const FaceJacobian& j) {
  const double d = jacobian_determinant(j);
  if (!(d > 0)) return std::numeric_limits<double>::infinity();
  // |J^-1| = |adj J| / det J = |J| / det J for 2 by 2 matrices.
  return j.squaredNorm() * (1 + 1 / (d * d)) - 4;
}

SymmetricDirichletDerivatives symmetric_dirichlet_derivatives(const FaceJacobian& j) {
  const SingularValues sv = singular_values(j);
  const Eigen::Matrix2d &U = sv.U, &V = sv.V;
  const double s1 = sv.s1, s2 = sv.s2;
  const double p = s1 * s2, p3 = p * p * p;
  const double scale1 = 2 + 6 / (s1 * s1 * s1 * s1), scale2 = 2 + 6 / (s2 * s2 * s2 * s2);
  const double flip = 2 + 2 * (s1 * s1 + s1 * s2 + s2 * s2) / p3;
  const double twist = std::max(0.0, 2 - 2 * (s1 * s1 - s1 * s2 + s2 * s2) / p3);
  const double r = std::sqrt(0.5);
  const std::array<Eigen::Vector4d, 2> d = scaling_modes(sv);
  const Eigen::Vector4d &d1 = d[0], &d2 = d[1];
  const Eigen::Vector4d l = mode(U, V, 0, r, r, 0), t = mode(U, V, 0, -r, r, 0);
  SymmetricDirichletDerivatives out;
  out.gradient = gradient(sv, d);
  out.hessian = scale1 * d1 * d1.transpose() + scale2 * d2 * d2.transpose() + flip * l * l.transpose() +
                twist * t * t.transpose();
  return out;
}

SymmetricDirichletDerivatives symmetric_dirichlet_proxy_derivatives(const FaceJacobian& j) {
  const SingularValues sv = singular_values(j);
  const auto weight = [](double s) { return (s + 1) * (s * s + 1) / (s * s * s); };  // w^2
  const Eigen::Matrix2d M = 2 * sv.V * Eigen::Vector2d(weight(sv.s1), weight(sv.s2)).asDiagonal() * sv.V.transpose();
  SymmetricDirichletDerivatives out;
  out.gradient = gradient(sv, scaling_modes(sv));
  out.hessian.setZero();  // K -> K M on each row of K: the rows (J00, J01) and (J10, J11) do not couple
  out.hessian.topLeftCorner<2, 2>() = M;
  out.hessian.bottomRightCorner<2, 2>() = M;
  return out;
}

}  // namespace liftmap
