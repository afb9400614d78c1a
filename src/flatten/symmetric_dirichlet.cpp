#include "flatten/symmetric_dirichlet.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "flatten/sparse_cholesky.h"

namespace liftmap {

namespace {

using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;
using Mat46 = Eigen::Matrix<double, 4, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// d(a11, a12, a21, a22) / d(u0, v0, u1, v1, u2, v2) of one face (JacobianOperator's convention).
Mat46 jacobian_map(const Eigen::Matrix<double, 1, 6>& g) {
  Mat46 D = Mat46::Zero();
  for (int k = 0; k < 3; ++k) {
    D(0, 2 * k) = g(2 * k);
    D(1, 2 * k) = g(2 * k + 1);
    D(2, 2 * k + 1) = g(2 * k);
    D(3, 2 * k + 1) = g(2 * k + 1);
  }
  return D;
}

Vec6 corners(const Eigen::MatrixXi& F, const Eigen::MatrixXd& U, Eigen::Index f) {
  Vec6 x;
  for (int k = 0; k < 3; ++k) x.segment<2>(2 * k) = U.row(F(f, k)).transpose();
  return x;
}

double det(const Vec4& j) { return j(0) * j(3) - j(1) * j(2); }

/// |J|^2 + |J^-1|^2 - 4 = |J|^2 (1 + 1 / det^2) - 4 (for 2 by 2 matrices |adj J| = |J|); +inf unless det > 0.
double face_energy(const Vec4& j) {
  const double d = det(j);
  if (!(d > 0)) return std::numeric_limits<double>::infinity();
  return j.squaredNorm() * (1 + 1 / (d * d)) - 4;
}

double energy(const JacobianOperator& op, const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  double e = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    e += op.area(f) * face_energy(jacobian_map(op.G.row(f)) * corners(F, U, f));
  }
  return e;
}

/// Gradient and projected Hessian of face_energy in j.
void face_derivatives(const Vec4& j, Vec4& grad, Mat4& hess) {
  const double d = det(j), n2 = j.squaredNorm();
  const Vec4 gd(j(3), -j(2), -j(1), j(0));  // d det / dj
  Mat4 hd = Mat4::Zero();                   // d^2 det / dj^2
  hd(0, 3) = hd(3, 0) = 1;
  hd(1, 2) = hd(2, 1) = -1;
  const double d2 = 1 / (d * d), d3 = d2 / d, d4 = d2 * d2;
  grad = 2 * (1 + d2) * j - 2 * n2 * d3 * gd;
  hess = 2 * (1 + d2) * Mat4::Identity() - 4 * d3 * (j * gd.transpose() + gd * j.transpose()) +
         n2 * (6 * d4 * gd * gd.transpose() - 2 * d3 * hd);
  const Eigen::SelfAdjointEigenSolver<Mat4> eig(hess);
  hess = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0).asDiagonal() * eig.eigenvectors().transpose();
}

/// The largest a in (0, 1] such that det(J + t dJ) > 0 for all t in [0, a] on every face, times 0.8 if < 1/0.8.
double flip_free_step(const JacobianOperator& op, const Eigen::MatrixXi& F, const Eigen::MatrixXd& U,
                      const Eigen::MatrixXd& step_u) {
  double a = 1 / 0.8;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Mat46 D = jacobian_map(op.G.row(f));
    const Vec4 j = D * corners(F, U, f), dj = D * corners(F, step_u, f);
    // det(j + t dj) = c0 + c1 t + c2 t^2
    const double c0 = det(j), c2 = det(dj);
    const double c1 = j(0) * dj(3) + dj(0) * j(3) - j(1) * dj(2) - dj(1) * j(2);
    double root = std::numeric_limits<double>::infinity();
    if (std::abs(c2) < 1e-300) {
      if (c1 < 0) root = -c0 / c1;
    } else {
      const double disc = c1 * c1 - 4 * c2 * c0;
      if (disc >= 0) {
        const double s = std::sqrt(disc);
        for (const double r : {(-c1 - s) / (2 * c2), (-c1 + s) / (2 * c2)}) {
          if (r > 0) root = std::min(root, r);
        }
      }
    }
    a = std::min(a, root);
  }
  return 0.8 * a;
}

}  // namespace

SymmetricDirichletResult minimize_symmetric_dirichlet(const JacobianOperator& op, const Eigen::MatrixXi& F,
                                                      const std::vector<char>& fixed, const Eigen::MatrixXd& U0,
                                                      const SymmetricDirichletOptions& options) {
  const auto nv = static_cast<Eigen::Index>(fixed.size());
  if (U0.rows() != nv || U0.cols() != 2 || op.G.rows() != F.rows() || op.area.size() != F.rows()) {
    throw InvalidInputError("minimize_symmetric_dirichlet: sizes disagree");
  }
  SymmetricDirichletResult res;
  res.U = U0;
  res.energy_start = res.energy = energy(op, F, U0);
  if (!std::isfinite(res.energy)) {
    throw InvalidInputError("minimize_symmetric_dirichlet: a face of the start is flipped or degenerate");
  }
  std::vector<int> dof(static_cast<size_t>(nv), -1);
  int n = 0;
  for (Eigen::Index v = 0; v < nv; ++v) {
    if (!fixed[static_cast<size_t>(v)]) dof[static_cast<size_t>(v)] = n++;
  }
  if (n == 0) return res;
  SparseCholesky cholesky;
  for (int iter = 0; iter < options.max_iterations; ++iter) {
    // Assemble the projected Newton system H dx = -g over the free coordinates (2 per free vertex).
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * n);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Mat46 D = jacobian_map(op.G.row(f));
      Vec4 gj;
      Mat4 hj;
      face_derivatives(D * corners(F, res.U, f), gj, hj);
      const Vec6 gx = op.area(f) * D.transpose() * gj;
      const Eigen::Matrix<double, 6, 6> hx = op.area(f) * D.transpose() * hj * D;
      for (int a = 0; a < 6; ++a) {
        const int ra = dof[static_cast<size_t>(F(f, a / 2))];
        if (ra < 0) continue;
        g(2 * ra + a % 2) += gx(a);
        for (int b = 0; b < 6; ++b) {
          const int rb = dof[static_cast<size_t>(F(f, b / 2))];
          if (rb >= 0 && 2 * rb + b % 2 <= 2 * ra + a % 2)
            triplets.emplace_back(2 * ra + a % 2, 2 * rb + b % 2, hx(a, b));
        }
      }
    }
    Eigen::SparseMatrix<double> H(2 * n, 2 * n);
    H.setFromTriplets(triplets.begin(), triplets.end());
    // A tiny multiple of the diagonal keeps the projected (semidefinite) Hessian definite.
    for (int i = 0; i < 2 * n; ++i) H.coeffRef(i, i) += 1e-12 * (1 + std::abs(H.coeff(i, i)));
    if (!cholesky.analyzed()) cholesky.analyze(H);
    if (!cholesky.factorize(H)) break;
    const Eigen::VectorXd dx = cholesky.solve(-g);
    Eigen::MatrixXd step_u = Eigen::MatrixXd::Zero(nv, 2);
    for (Eigen::Index v = 0; v < nv; ++v) {
      const int r = dof[static_cast<size_t>(v)];
      if (r >= 0) step_u.row(v) << dx(2 * r), dx(2 * r + 1);
    }
    // Flip-free, then Armijo.
    const double slope = g.dot(dx);
    if (!(slope < 0)) break;
    double step = std::min(1.0, flip_free_step(op, F, res.U, step_u));
    double e = std::numeric_limits<double>::infinity();
    Eigen::MatrixXd trial;
    for (int halvings = 0; halvings < 40; ++halvings, step *= 0.5) {
      trial = res.U + step * step_u;
      e = energy(op, F, trial);
      if (e <= res.energy + 1e-4 * step * slope) break;
    }
    if (!(e < res.energy)) break;
    const double before = res.energy;
    res.U = std::move(trial);
    res.energy = e;
    ++res.iterations;
    if (before - e < options.relative_decrease * before) break;
  }
  return res;
}

}  // namespace liftmap
