#include "flatten/symmetric_dirichlet_face.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
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

}  // namespace

double symmetric_dirichlet_energy(const FaceJacobian& j) {
  const double d = jacobian_determinant(j);
  if (!(d > 0)) return std::numeric_limits<double>::infinity();
  // |J^-1| = |adj J| / det J = |J| / det J for 2 by 2 matrices.
  return j.squaredNorm() * (1 + 1 / (d * d)) - 4;
}

SymmetricDirichletDerivatives symmetric_dirichlet_derivatives(const FaceJacobian& j) {
  Eigen::Matrix2d J;
  J << j(0), j(1), j(2), j(3);
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix2d U = svd.matrixU(), V = svd.matrixV();
  const double s1 = svd.singularValues()(0), s2 = svd.singularValues()(1);
  if (U.determinant() < 0) {  // det J > 0: U and V are both reflections; flip both second columns
    U.col(1) *= -1;
    V.col(1) *= -1;
  }
  const double psi1 = 2 * s1 - 2 / (s1 * s1 * s1), psi2 = 2 * s2 - 2 / (s2 * s2 * s2);
  const double p = s1 * s2, p3 = p * p * p;
  const double scale1 = 2 + 6 / (s1 * s1 * s1 * s1), scale2 = 2 + 6 / (s2 * s2 * s2 * s2);
  const double flip = 2 + 2 * (s1 * s1 + s1 * s2 + s2 * s2) / p3;
  const double twist = std::max(0.0, 2 - 2 * (s1 * s1 - s1 * s2 + s2 * s2) / p3);
  const double r = std::sqrt(0.5);
  const Eigen::Vector4d d1 = mode(U, V, 1, 0, 0, 0), d2 = mode(U, V, 0, 0, 0, 1);
  const Eigen::Vector4d l = mode(U, V, 0, r, r, 0), t = mode(U, V, 0, -r, r, 0);
  SymmetricDirichletDerivatives out;
  out.gradient = psi1 * d1 + psi2 * d2;
  out.hessian = scale1 * d1 * d1.transpose() + scale2 * d2 * d2.transpose() + flip * l * l.transpose() +
                twist * t * t.transpose();
  return out;
}

}  // namespace liftmap
