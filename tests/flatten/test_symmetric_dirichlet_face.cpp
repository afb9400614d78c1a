#include "flatten/symmetric_dirichlet_face.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <random>
#include <vector>

namespace liftmap {
namespace {

/// psi from its definition, with an explicit inverse.
double psi_reference(const FaceJacobian& j) {
  Eigen::Matrix2d J;
  J << j(0), j(1), j(2), j(3);
  return J.squaredNorm() + J.inverse().squaredNorm() - 4;
}

/// (fn(j + h e_k) - fn(j - h e_k)) / 2h: the central difference of fn along coordinate k.
template <class Fn>
auto central_difference(const Fn& fn, const FaceJacobian& j, int k, double h) {
  FaceJacobian p = j, m = j;
  p(k) += h;
  m(k) -= h;
  using Value = decltype(fn(j));  // a value, not an expression of the temporaries fn(p) and fn(m)
  return Value((fn(p) - fn(m)) / (2 * h));
}

Eigen::Vector4d gradient_by_differences(const FaceJacobian& j, double h) {
  Eigen::Vector4d g;
  for (int k = 0; k < 4; ++k) g(k) = central_difference(psi_reference, j, k, h);
  return g;
}

/// The Hessian by central differences of the analytic gradient, projected by a numerical eigendecomposition.
Eigen::Matrix4d projected_hessian_by_differences(const FaceJacobian& j, double h) {
  const auto gradient = [](const FaceJacobian& x) -> Eigen::Vector4d {
    return symmetric_dirichlet_derivatives(x).gradient;
  };
  Eigen::Matrix4d H;
  for (int k = 0; k < 4; ++k) H.col(k) = central_difference(gradient, j, k, h);
  H = 0.5 * (H + H.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(H);
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).asDiagonal() * eig.eigenvectors().transpose();
}

/// Jacobians with positive determinant: random ones, near-conformal ones (s1 close to s2, where the flip's
/// eigenvalue is a limit), a rotation, a squeezed one (the twist's eigenvalue negative) and a reflection-free shear.
std::vector<FaceJacobian> jacobians() {
  std::vector<FaceJacobian> out;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  while (out.size() < 40) {
    const FaceJacobian j(u(rng), u(rng), u(rng), u(rng));
    if (j(0) * j(3) - j(1) * j(2) > 0.05) out.push_back(j);
  }
  const double c = std::cos(0.7), s = std::sin(0.7);
  out.emplace_back(c, -s, s, c);                                 // a rotation: s1 = s2 = 1
  out.emplace_back(1.5 * c, -1.5 * s, 1.5 * s, 1.5 * c);         // a similarity
  out.emplace_back(1.5 * c, -1.5 * s, 1.5 * s + 1e-7, 1.5 * c);  // nearly one
  out.emplace_back(0.3, 0, 0, 0.2);                              // squeezed: the twist's eigenvalue is negative
  out.emplace_back(1, 3, 0, 0.5);                                // a shear
  return out;
}

TEST(flatten_symmetric_dirichlet_face, EnergyIsTheDefinitionAndInfiniteWhenFlipped) {
  for (const FaceJacobian& j : jacobians()) {
    EXPECT_NEAR(symmetric_dirichlet_energy(j), psi_reference(j), 1e-12 * (1 + psi_reference(j)));
  }
  EXPECT_TRUE(std::isinf(symmetric_dirichlet_energy(FaceJacobian(1, 0, 0, -1))));
  EXPECT_TRUE(std::isinf(symmetric_dirichlet_energy(FaceJacobian(1, 2, 1, 2))));
  EXPECT_NEAR(symmetric_dirichlet_energy(FaceJacobian(std::cos(1.0), -std::sin(1.0), std::sin(1.0), std::cos(1.0))), 0,
              1e-15);
}

TEST(flatten_symmetric_dirichlet_face, GradientMatchesDifferences) {
  for (const FaceJacobian& j : jacobians()) {
    const Eigen::Vector4d g = symmetric_dirichlet_derivatives(j).gradient;
    const Eigen::Vector4d fd = gradient_by_differences(j, 1e-6);
    EXPECT_LT((g - fd).norm(), 1e-5 * (1 + fd.norm())) << j.transpose();
  }
}

// The closed-form eigensystem against differences of the gradient projected numerically: the same matrix, so the
// twist is the only mode that can be clamped, and clamped where the numerical eigenvalue is negative.
TEST(flatten_symmetric_dirichlet_face, ProjectedHessianMatchesANumericalProjection) {
  int clamped = 0;
  for (const FaceJacobian& j : jacobians()) {
    const Eigen::Matrix4d H = symmetric_dirichlet_derivatives(j).hessian;
    const Eigen::Matrix4d ref = projected_hessian_by_differences(j, 1e-6);
    EXPECT_LT((H - ref).norm(), 1e-5 * (1 + ref.norm())) << j.transpose();
    EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(H);
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * H.norm());
    if (eig.eigenvalues().minCoeff() < 1e-9 * H.norm()) ++clamped;
  }
  EXPECT_GT(clamped, 0) << "no Jacobian had a negative twist eigenvalue: the clamp went untested";
}

/// J = U diag(s) V^T with det U = det V = 1, by a numerical SVD (det J > 0).
struct Polar {
  Eigen::Matrix2d U, V;
  Eigen::Vector2d s;
};

Polar polar(const FaceJacobian& j) {
  Eigen::Matrix2d J;
  J << j(0), j(1), j(2), j(3);
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Polar p{.U = svd.matrixU(), .V = svd.matrixV(), .s = svd.singularValues()};
  if (p.U.determinant() < 0) {
    p.U.col(1) *= -1;
    p.V.col(1) *= -1;
  }
  return p;
}

Eigen::Vector4d row_major(const Eigen::Matrix2d& M) { return {M(0, 0), M(0, 1), M(1, 0), M(1, 1)}; }

// The proxy q(K) = |(K - R) W|^2 built here from its definition (R = U V^T, W = V diag(w) V^T, w_i^2 =
// psi_i / (2 (s_i - 1))): its gradient at J is psi's (by differences of psi), its Hessian is q's (the quadratic form
// 2 |dK W|^2 along random directions), positive definite, and bitwise the gradient of symmetric_dirichlet_derivatives.
TEST(flatten_symmetric_dirichlet_face, ProxyHasPsisGradientAndAPositiveDefiniteHessian) {
  std::mt19937 rng(9);
  std::normal_distribution<double> n01;
  for (const FaceJacobian& j : jacobians()) {
    const SymmetricDirichletDerivatives q = symmetric_dirichlet_proxy_derivatives(j);
    EXPECT_EQ(q.gradient, symmetric_dirichlet_derivatives(j).gradient);
    const Eigen::Vector4d fd = gradient_by_differences(j, 1e-6);
    EXPECT_LT((q.gradient - fd).norm(), 1e-5 * (1 + fd.norm())) << j.transpose();
    const Polar p = polar(j);
    Eigen::Vector2d w;
    for (int i = 0; i < 2; ++i) {
      const double s = p.s(i), psi = 2 * s - 2 / (s * s * s);
      w(i) = std::abs(s - 1) < 1e-6 ? 2 : std::sqrt(psi / (2 * (s - 1)));
    }
    const Eigen::Matrix2d W = p.V * w.asDiagonal() * p.V.transpose();
    Eigen::Matrix2d J;
    J << j(0), j(1), j(2), j(3);
    const Eigen::Vector4d g_q = row_major(2 * (J - p.U * p.V.transpose()) * W * W.transpose());
    EXPECT_LT((q.gradient - g_q).norm(), 1e-9 * (1 + g_q.norm())) << j.transpose();
    for (int k = 0; k < 4; ++k) {
      Eigen::Matrix2d dK;
      dK << n01(rng), n01(rng), n01(rng), n01(rng);
      const double form = row_major(dK).dot(q.hessian * row_major(dK)), ref = 2 * (dK * W).squaredNorm();
      EXPECT_NEAR(form, ref, 1e-9 * ref) << j.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(q.hessian);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0) << j.transpose();
  }
}

// A face alone: the proxy's step J - H^-1 grad lands on the rotation of J's polar decomposition, however crushed J is
// (projected Newton's step would grow a crushed singular value by a third).
TEST(flatten_symmetric_dirichlet_face, ProxyStepTakesALoneFaceToItsRotation) {
  std::vector<FaceJacobian> js = jacobians();
  js.emplace_back(1, 0, 0, 1e-4);
  js.emplace_back(0.8 * std::cos(0.3), -1e-3 * std::sin(0.3), 0.8 * std::sin(0.3), 1e-3 * std::cos(0.3));
  for (const FaceJacobian& j : js) {
    const SymmetricDirichletDerivatives q = symmetric_dirichlet_proxy_derivatives(j);
    const Eigen::Vector4d stepped = j - q.hessian.ldlt().solve(q.gradient);
    const Polar p = polar(j);
    const Eigen::Vector4d R = row_major(p.U * p.V.transpose());
    EXPECT_LT((stepped - R).norm(), 1e-9) << j.transpose();
  }
}

}  // namespace
}  // namespace liftmap
