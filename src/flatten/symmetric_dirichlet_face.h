#pragma once
/// One face's symmetric Dirichlet energy as a function of its Jacobian, with its gradient and the positive
/// semidefinite projection of its Hessian in closed form (the analytic eigensystem of an isotropic energy, Smith, de
/// Goes and Kim, "Analytic Eigensystems for Isotropic Distortion Energies", 2019), for minimize_symmetric_dirichlet.

#include <Eigen/Core>

namespace liftmap {

/// j = (J00, J01, J10, J11): a 2 by 2 Jacobian, row-major (JacobianOperator's layout).
using FaceJacobian = Eigen::Vector4d;

/// det J = J00 J11 - J01 J10.
inline double jacobian_determinant(const FaceJacobian& j) { return j(0) * j(3) - j(1) * j(2); }

/// psi(J) = |J|^2 + |J^-1|^2 - 4 = sigma_1^2 + sigma_2^2 + sigma_1^-2 + sigma_2^-2 - 4 (sigma_i the singular values);
/// +infinity unless det J > 0.
double symmetric_dirichlet_energy(const FaceJacobian& j);

/// Gradient and projected Hessian of symmetric_dirichlet_energy at j (det J > 0).
struct SymmetricDirichletDerivatives {
  Eigen::Vector4d gradient;
  Eigen::Matrix4d hessian;  ///< d^2 psi / dj^2 with its negative eigenvalue (if any) set to 0
};

/// With J = U diag(s1, s2) V^T (U, V rotations, s2 > 0) and psi_i = d psi / d s_i = 2 s_i - 2 s_i^-3, the Hessian
/// has four eigenvectors, each U M V^T for a fixed M, with eigenvalues
///   M = diag(1, 0), diag(0, 1):      2 + 6 s_i^-4                                (scalings)
///   M = [0 1; 1 0] / sqrt 2:          (psi_1 - psi_2) / (s1 - s2) = 2 + 2 (s1^2 + s1 s2 + s2^2) / (s1 s2)^3  (flip)
///   M = [0 -1; 1 0] / sqrt 2:         (psi_1 + psi_2) / (s1 + s2) = 2 - 2 (s1^2 - s1 s2 + s2^2) / (s1 s2)^3  (twist)
/// Only the twist's can be negative; it is clamped to 0. The gradient is U diag(psi_1, psi_2) V^T.
/// \pre det J > 0 (the caller keeps every face positively oriented).
SymmetricDirichletDerivatives symmetric_dirichlet_derivatives(const FaceJacobian& j);

/// Gradient of psi at j and the Hessian of its reweighted quadratic proxy (after Rabinovich, Poranne, Panozzo and
/// Sorkine-Hornung, "Scalable Locally Injective Mappings", 2017): with J = U diag(s1, s2) V^T, R = U V^T and
/// W = V diag(w_1, w_2) V^T,
///   q(K) = |(K - R) W|^2,   w_i^2 = psi_i / (2 (s_i - 1)) = (s_i + 1)(s_i^2 + 1) / s_i^3   (4 at s_i = 1),
/// whose gradient at K = J is psi's and whose Hessian, K -> 2 K V diag(w_i^2) V^T on each row of K, is positive
/// definite. Where projected Newton grows a crushed face's small singular value s by a third per step (psi ~ s^-2),
/// the proxy's step takes a face alone to R in one: -H^-1 grad = -U diag(s_i - 1) V^T.
/// \pre det J > 0.
SymmetricDirichletDerivatives symmetric_dirichlet_proxy_derivatives(const FaceJacobian& j);

}  // namespace liftmap
