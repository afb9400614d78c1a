// SparseCholesky's factorisation (src/flatten/supernodal_factorization.h) on matrices of the flattening's kind: the
// graph of a triangulated grid, two unknowns per vertex, large enough for the elimination tree to split in two.

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>
#include <random>
#include <stdexcept>
#include <vector>

#include "flatten/sparse_cholesky.h"

namespace liftmap {
namespace {

/// An SPD matrix on a w by h grid's triangulation (each square split by a diagonal), two unknowns per vertex: per
/// triangle a random positive semidefinite 6 by 6 block (B B^T) on its corners' unknowns, plus `diagonal` on the
/// diagonal.
Eigen::SparseMatrix<double> grid_matrix(int w, int h, double diagonal, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  const auto vertex = [w](int x, int y) { return y * w + x; };
  const auto add_triangle = [&](int a, int b, int c) {
    Eigen::Matrix<double, 6, 6> B;
    for (int i = 0; i < 36; ++i) B(i) = u(rng);
    const Eigen::Matrix<double, 6, 6> K = B * B.transpose();
    const int v[3] = {a, b, c};
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) t.emplace_back(2 * v[i / 2] + i % 2, 2 * v[j / 2] + j % 2, K(i, j));
    }
  };
  for (int y = 0; y + 1 < h; ++y) {
    for (int x = 0; x + 1 < w; ++x) {
      add_triangle(vertex(x, y), vertex(x + 1, y), vertex(x + 1, y + 1));
      add_triangle(vertex(x, y), vertex(x + 1, y + 1), vertex(x, y + 1));
    }
  }
  const int n = 2 * w * h;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonal);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

Eigen::MatrixXd random_rhs(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd B(n, 3);
  for (Eigen::Index i = 0; i < B.size(); ++i) B(i) = g(rng);
  return B;
}

/// Solves A X = B with the given number of threads and dense kernels.
Eigen::MatrixXd solve_with_threads(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, int threads,
                                   DenseKernels kernels = DenseKernels::kAuto) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  SparseCholesky c(kernels);
  c.analyze(A);
  EXPECT_TRUE(c.factorize(A));
  Eigen::MatrixXd X = c.solve(B);
  omp_set_num_threads(before);
  return X;
}

// A split tree (two groups and a top) solves to the rounding of the problem: the residual is small relative to
// |A| |X|, on several random matrices.
TEST(flatten_sparse_cholesky, SplitFactorizationSolves) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const Eigen::SparseMatrix<double> A = grid_matrix(90, 70, 1e-3, seed);
    SparseCholesky c;
    c.analyze(A);
    ASSERT_TRUE(c.solve_split().split);
    ASSERT_TRUE(c.factorize(A));
    const Eigen::MatrixXd B = random_rhs(A.rows(), seed);
    const Eigen::MatrixXd X = c.solve(B);
    const double residual = (A * X - B).norm() / (B.norm() + A.norm() * X.norm());
    EXPECT_LT(residual, 1e-13) << "seed " << seed;
  }
}

// A small (unsplit) system agrees with Eigen's dense Cholesky.
TEST(flatten_sparse_cholesky, SmallSystemAgreesWithDenseCholesky) {
  const Eigen::SparseMatrix<double> A = grid_matrix(12, 9, 1e-2, 7);
  SparseCholesky c;
  c.analyze(A);
  EXPECT_FALSE(c.solve_split().split);
  ASSERT_TRUE(c.factorize(A));
  const Eigen::MatrixXd B = random_rhs(A.rows(), 7);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(A).llt().solve(B);
  EXPECT_LT((c.solve(B) - dense).norm(), 1e-9 * dense.norm());
}

// The arithmetic follows the schedule, not the threads: one thread and two give bitwise the same solution (the maps
// are the same at any thread count).
TEST(flatten_sparse_cholesky, SameBitsOnOneThreadAndTwo) {
  const Eigen::SparseMatrix<double> A = grid_matrix(90, 70, 1e-3, 11);
  const Eigen::MatrixXd B = random_rhs(A.rows(), 11);
  for (const DenseKernels kernels : {DenseKernels::kBaseline, DenseKernels::kAuto}) {
    const Eigen::MatrixXd one = solve_with_threads(A, B, 1, kernels);
    const Eigen::MatrixXd two = solve_with_threads(A, B, 2, kernels);
    EXPECT_TRUE(one == two) << "kernels " << static_cast<int>(kernels);
  }
}

// The AVX2 kernels (where the CPU has them) solve as well as the baseline ones, and are the ones kAuto runs:
// their rounding differs (FMA), so the solutions agree to the problem's conditioning, not bit for bit. Without
// them, asking for them is refused.
TEST(flatten_sparse_cholesky, BothDenseKernelsSolve) {
  if (!avx2_kernels_available()) {
    EXPECT_THROW(SparseCholesky{DenseKernels::kAvx2}, std::invalid_argument);
    return;
  }
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const Eigen::SparseMatrix<double> A = grid_matrix(90, 70, 1e-3, seed);
    const Eigen::MatrixXd B = random_rhs(A.rows(), seed);
    const Eigen::MatrixXd baseline = solve_with_threads(A, B, 2, DenseKernels::kBaseline);
    const Eigen::MatrixXd avx2 = solve_with_threads(A, B, 2, DenseKernels::kAvx2);
    const Eigen::MatrixXd automatic = solve_with_threads(A, B, 2, DenseKernels::kAuto);
    for (const Eigen::MatrixXd* X : {&baseline, &avx2}) {
      EXPECT_LT((A * *X - B).norm() / (B.norm() + A.norm() * X->norm()), 1e-13) << "seed " << seed;
    }
    EXPECT_FALSE(baseline == avx2) << "the same bits: did the AVX2 kernels run?";
    EXPECT_TRUE(automatic == avx2);
    EXPECT_LT((baseline - avx2).norm(), 1e-6 * baseline.norm()) << "seed " << seed;
  }
}

// A matrix that is not positive definite is reported, wherever the failing pivot lies (either half of the split or
// the top above them), and a later positive definite matrix of the same pattern factorises again.
TEST(flatten_sparse_cholesky, ReportsIndefiniteMatrices) {
  const Eigen::SparseMatrix<double> A = grid_matrix(90, 70, 1e-3, 5);
  SparseCholesky c;
  c.analyze(A);
  ASSERT_TRUE(c.solve_split().split);
  const std::vector<int> halves = c.unknown_halves();
  for (const int half : {0, 1, -1}) {
    Eigen::Index pick = -1;
    for (Eigen::Index i = 0; i < A.rows() && pick < 0; ++i) {
      if (halves[static_cast<size_t>(i)] == half) pick = i;
    }
    ASSERT_GE(pick, 0);
    Eigen::SparseMatrix<double> bad = A;
    bad.coeffRef(pick, pick) = -1.0;
    EXPECT_FALSE(c.factorize(bad)) << "half " << half;
    EXPECT_THROW(static_cast<void>(c.solve(random_rhs(A.rows(), 1))), std::exception) << "half " << half;
  }
  ASSERT_TRUE(c.factorize(A));
  const Eigen::MatrixXd B = random_rhs(A.rows(), 5);
  EXPECT_LT((A * c.solve(B) - B).norm(), 1e-8 * B.norm() * A.norm());
}

}  // namespace
}  // namespace liftmap
