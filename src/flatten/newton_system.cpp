#include "flatten/newton_system.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/errors.h"

namespace liftmap::subproblem {

namespace {

/// Eigenvalue ratio below which a face's 4x4 Schur block counts as ill-conditioned (its product with the corner
/// map is then cleaned of negative eigenvalues again).
constexpr double kWellConditioned = 1e-8;

/// Clamps the negative eigenvalues of a face's 4x4 Schur block Haa (rounding in the elimination of nearly active
/// constraints) and returns its corner block S^T Haa S (6x6), cleaned again where Haa is ill-conditioned.
/// Most blocks are well conditioned, which a Cholesky factorisation shows at a fraction of an eigensolver's cost:
/// with det = prod(diag L)^2 and every eigenvalue at most the trace, lambda_min >= det / trace^3, so
/// det >= kWellConditioned * trace^4 guarantees lambda_min >= kWellConditioned * lambda_max. Only the other blocks
/// need eigenvalues, and their eigenvectors only if an eigenvalue is negative.
Mat6 positive_corner_block(Eigen::Matrix4d Haa, const Mat46& S) {
  bool well_conditioned = false;
  {
    const Eigen::LLT<Eigen::Matrix4d> haa_llt(Haa);
    if (haa_llt.info() == Eigen::Success) {
      const double d = haa_llt.matrixLLT().diagonal().prod();
      const double tr = Haa.trace();
      well_conditioned = d * d >= kWellConditioned * (tr * tr) * (tr * tr);
    }
  }
  if (well_conditioned) return S.transpose() * Haa * S;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(Haa, Eigen::EigenvaluesOnly);
  const Eigen::Vector4d lambda = eig.eigenvalues();
  if (lambda(0) < 0) {
    eig.compute(Haa);
    Haa = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  }
  Mat6 K = S.transpose() * Haa * S;
  if (lambda(0) < kWellConditioned * lambda(3)) {
    // Ill-conditioned block: the product's rounding (relative to its largest entries) can again leave negative
    // eigenvalues of a few percent of the smaller ones, enough to make the sum indefinite.
    Eigen::SelfAdjointEigenSolver<Mat6> eig6(0.5 * (K + K.transpose()));
    K = eig6.eigenvectors() * eig6.eigenvalues().cwiseMax(0.0).asDiagonal() * eig6.eigenvectors().transpose();
  }
  return K;
}

/// The block's largest eigenvalue times the identity (the smaller curvature raised to the larger one).
Eigen::Matrix2d isotropic_block(const Eigen::Matrix2d& G) {
  const double half = 0.5 * G.trace();
  const double lmax = half + std::sqrt(std::max(0.0, half * half - G.determinant()));
  return lmax > 0 ? Eigen::Matrix2d(lmax * Eigen::Matrix2d::Identity()) : G;
}

}  // namespace

void HessianFaceBlock::eliminate(const Eigen::Matrix<double, 7, 7>& H, const Mat46& S, bool isotropic) {
  constexpr int kY = 4;  // the auxiliaries' first row
  constexpr int kT = 6;
  const Eigen::Matrix2d Pyy = H.block<2, 2>(kY, kY);
  Pinv = Pyy.inverse();
  Pinv = 0.5 * (Pinv + Pinv.transpose());
  const Eigen::Matrix<double, 4, 2> Hay = H.block<4, 2>(0, kY);
  Eigen::Matrix4d Haa = H.block<4, 4>(0, 0);
  const Eigen::LLT<Eigen::Matrix2d> pyy_llt(Pyy);
  if (pyy_llt.info() == Eigen::Success) {
    const Eigen::Matrix<double, 2, 4> W = pyy_llt.matrixL().solve(Hay.transpose());
    Haa -= W.transpose() * W;
  } else {
    Haa -= Hay * Pinv * Hay.transpose();
  }
  Haa = 0.5 * (Haa + Haa.transpose());
  if (isotropic) Haa.block<2, 2>(2, 2) = isotropic_block(Haa.block<2, 2>(2, 2));
  K = positive_corner_block(Haa, S);
  B = S.transpose() * Hay;
  hyT = H.block<2, 1>(kY, kT);
  hxT = S.transpose() * H.block<4, 1>(0, kT);
  h_tt = H(kT, kT);
}

void clear_values(Pattern& pattern) {
  double* values = pattern.A.valuePtr();
  const Eigen::Index n_values = pattern.A.nonZeros();
#pragma omp parallel for schedule(static) if (n_values > 100000)
  for (Eigen::Index k = 0; k < n_values; ++k) values[k] = 0;
}

bool factorize_with_shift(SparseCholesky& cholesky, Eigen::SparseMatrix<double>& A, double& last_shift) {
  if (last_shift == 0 && cholesky.factorize(A)) return true;
  const Eigen::VectorXd diag = A.diagonal();
  for (double shift = std::max(1e-14, 1e-2 * last_shift); shift < 1e3; shift *= 100) {
    for (Eigen::Index v = 0; v < A.rows(); ++v) A.coeffRef(v, v) = diag(v) * (1 + shift);
    if (cholesky.factorize(A)) {
      last_shift = shift;
      return true;
    }
  }
  return false;
}

std::vector<FaceStart> strictly_feasible_start(const Setup& s, const Eigen::VectorXd& pos) {
  std::vector<FaceStart> start(static_cast<size_t>(s.n_faces));
  int first_infeasible = s.n_faces;
#pragma omp parallel for schedule(static) reduction(min : first_infeasible) if (s.n_faces > kParallelFaces)
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    const Eigen::Vector4d a = face_coordinates(fs, pos);
    FaceStart& f = start[static_cast<size_t>(j)];
    f.lo = std::hypot(a(2), a(3));
    f.n = std::hypot(a(0), a(1));
    f.l = a(0) * fs.cs + a(1) * fs.sn;
    if (!(f.l - f.lo > 0)) first_infeasible = std::min(first_infeasible, j);
  }
  if (first_infeasible < s.n_faces) {
    throw InvalidInputError("convex subproblem: the start is not strictly feasible (sigma_tilde <= 0 on face " +
                            std::to_string(first_infeasible) + ")");
  }
  return start;
}

CoupledSolve::CoupledSolve(CouplingColumns C, CouplingColumns pinv_c, const std::array<double, 2>& h)
    : C_(std::move(C)), pinv_c_(std::move(pinv_c)), h_(h) {}

CoupledSolve CoupledSolve::bordered(CouplingColumns C, CouplingColumns pinv_c, const std::array<double, 2>& h) {
  CoupledSolve cs(std::move(C), std::move(pinv_c), h);
  cs.schur_ = -cs.gram();
  cs.schur_(0, 0) += h[0];
  cs.schur_(1, 1) += h[1];
  return cs;
}

CoupledSolve CoupledSolve::rank_two(CouplingColumns C, CouplingColumns pinv_c, const std::array<double, 2>& h,
                                    const std::array<double, 2>& kappa) {
  CoupledSolve cs(std::move(C), std::move(pinv_c), h);
  cs.rank_two_ = true;
  cs.kappa_ = Eigen::Vector2d(kappa[0], kappa[1]);
  const Eigen::Matrix2d G = cs.gram();
  cs.Minv_ = (Eigen::Matrix2d::Identity() + G).inverse();
  cs.GM_ = G * cs.Minv_;
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      cs.schur_(a, b) = (a == b ? h[static_cast<size_t>(a)] : 0.0) - cs.kappa_(a) * cs.kappa_(b) * cs.GM_(a, b);
    }
  }
  return cs;
}

// Symmetrised into a new matrix: in place, G = 0.5 * (G + G^T) aliases (Eigen assigns a fixed 2 x 2 coefficient by
// coefficient, so G(1, 0) read the already averaged G(0, 1)), which both solvers' own copies of this solve did.
Eigen::Matrix2d CoupledSolve::gram() const {
  const Eigen::Matrix2d G = C_.x.transpose() * pinv_c_.x + C_.y.transpose() * pinv_c_.y;
  return 0.5 * (G + G.transpose());
}

NewtonVector CoupledSolve::solve(Eigen::VectorXd pinv_rx, Eigen::VectorXd pinv_ry,
                                 const std::array<double, 2>& r_t) const {
  NewtonVector d;
  d.x = std::move(pinv_rx);
  d.y = std::move(pinv_ry);
  const Eigen::Vector2d ctr = C_.x.transpose() * d.x + C_.y.transpose() * d.y;  // C^T P^-1 r
  const Eigen::Vector2d rt(r_t[0], r_t[1]);
  if (!rank_two_) {
    const Eigen::Vector2d sol = schur_.ldlt().solve(rt - ctr);
    d.t = {sol(0), sol(1)};
    d.x -= pinv_c_.x * sol;
    d.y -= pinv_c_.y * sol;
    return d;
  }
  const Eigen::Vector2d cta = ctr - GM_ * ctr;  // C^T A^-1 r
  const Eigen::Vector2d sol = schur_.ldlt().solve(rt - kappa_.cwiseProduct(cta));
  d.t = {sol(0), sol(1)};
  const Eigen::Vector2d coef = Minv_ * (ctr + kappa_.cwiseProduct(sol));
  d.x -= pinv_c_.x * coef;
  d.y -= pinv_c_.y * coef;
  return d;
}

}  // namespace liftmap::subproblem
