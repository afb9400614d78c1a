#pragma once
/// The one sparse symmetric positive definite solver of liftmap: a supernodal LL^T, with CHOLMOD's symbolic
/// analysis (fill-reducing ordering: AMD, or METIS's nested dissection for large systems) done once per sparsity
/// pattern and a numeric refactorisation per matrix (every Newton step, every outer iteration). The numeric
/// factorisation (supernodal_factorization.h) and the triangular solves with the factor are ours: both run on two
/// threads where the elimination tree splits, and call no BLAS, so the factor does not depend on the machine's
/// BLAS; its dense kernels are AVX2 ones where the CPU has AVX2 and FMA (DenseKernels).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "flatten/supernodal_factorization.h"

namespace liftmap {

/// Cholesky factorisation of a sparse SPD matrix that keeps its symbolic analysis across refactorisations.
/// Only the lower triangle of the matrix is read. Usage: `analyze(A)` once, then `factorize(A)` whenever the
/// values change (same pattern), then `solve(b)` any number of times. factorize() and solve() run on two threads
/// where the elimination tree splits into two halves (the factorisation's of about equal flops, the solve's of
/// about equal stored values: solve_split), with the same arithmetic on one thread.
class SparseCholesky {
 public:
  /// `kernels`: the dense kernels of the numeric factorisation (kAuto: AVX2 with FMA where the CPU has them).
  /// \throw std::invalid_argument if kAvx2 is asked for and avx2_kernels_available() is false.
  explicit SparseCholesky(DenseKernels kernels = DenseKernels::kAuto);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  /// Fill-reducing ordering and symbolic factorisation of the pattern of `A` (n by n, lower triangle used).
  /// \throw PipelineError if CHOLMOD fails.
  void analyze(const Eigen::SparseMatrix<double>& A);
  /// Numeric factorisation of `A`, which must have the pattern given to `analyze` (has_pattern_of).
  /// \return false if `A` is not (numerically) positive definite; the caller decides what to do.
  /// \throw PipelineError if `A` does not have the analysed pattern.
  [[nodiscard]] bool factorize(const Eigen::SparseMatrix<double>& A);
  /// Solves `A X = B` for the last factorised `A`; `B` is n by k.
  [[nodiscard]] Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  [[nodiscard]] bool analyzed() const;
  /// Whether `A` has exactly the sparsity pattern analyze() was given (size and row indices of every column), so
  /// that factorize(A) may reuse the analysis. False if not analysed.
  [[nodiscard]] bool has_pattern_of(const Eigen::SparseMatrix<double>& A) const;

  /// How solve() shares its work between two threads: two groups of independent subtrees of the elimination
  /// tree, one per thread, and the top of the tree above them on one (fractions of the factor's stored values).
  struct SolveSplit {
    bool split = false;  ///< false: the solve runs on one thread (small or unbalanced tree)
    double group0 = 0, group1 = 0, top = 0;
  };
  /// The split found by analyze().
  [[nodiscard]] SolveSplit solve_split() const;
  /// Per unknown (row of A): 0 or 1, the half of the split its column is eliminated in, or -1 if in the top. Two
  /// unknowns of different halves are never coupled in A, so sums into A's entries or into vectors over the
  /// unknowns can run on two threads, one per half, with the entries that touch the top added afterwards. Empty
  /// if the solve is not split.
  [[nodiscard]] std::vector<int> unknown_halves() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace liftmap
