#include "flatten/symmetric_dirichlet_face.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
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

}  // namespace
}  // namespace liftmap
