#pragma once
/// The numeric supernodal Cholesky factorisation L L^T = B of SparseCholesky, on two threads where the elimination
/// tree splits into two independent halves.
///
/// Left-looking, supernode by supernode (the algorithm of CHOLMOD's supernodal numeric factorisation, on the
/// structure CHOLMOD's symbolic analysis gives): supernode s, columns k1 .. k2-1 and rows R_s (its own columns
/// first), is
///   1. its columns of B scattered into the dense block L_s (|R_s| by k2 - k1, column-major),
///   2. minus, for every earlier supernode d with rows in k1 .. k2-1, the product L_d[R_d >= k1] L_d[k1 <= R_d < k2]^T
///      scattered into L_s by row (d's rows are a subset of R_s),
///   3. factorised: L_11 = chol(L_s's top square), L_21 = L_s's rows below times L_11^-T,
/// after which s waits in the list of the supernode holding its next row. The dense products are Eigen's, not a
/// BLAS's: two threads can run them at once (Debian's serial OpenBLAS cannot be called from two), and the factor
/// does not depend on which BLAS the machine has. They are compiled twice (supernodal_numeric.h), for baseline
/// x86-64 and for AVX2 with FMA, the latter taken where the CPU has both: the factor's last bits depend on that.

#include <array>
#include <vector>

namespace liftmap {

/// A lower supernodal factor's structure (CHOLMOD's layout): supernode s holds columns super[s] .. super[s+1]-1,
/// its row indices are rows[pi[s]] .. rows[pi[s+1]-1] in ascending order (its own columns first), its values the
/// dense column-major block at x + px[s] (leading dimension pi[s+1] - pi[s]).
struct SupernodalStructure {
  const int* super = nullptr;
  const int* pi = nullptr;
  const int* px = nullptr;
  const int* rows = nullptr;
  int count = 0;  ///< supernodes
  int n = 0;      ///< columns

  [[nodiscard]] int columns(int s) const { return super[s + 1] - super[s]; }
  [[nodiscard]] int rows_of(int s) const { return pi[s + 1] - pi[s]; }
};

/// The lower triangle of an n by n matrix in compressed columns (rows of column c at i[p[c]] .. i[p[c+1]-1], each
/// row >= c and inside the factor's structure of column c).
struct LowerColumns {
  const int* p = nullptr;
  const int* i = nullptr;
  const double* x = nullptr;
};

/// Who factorises which supernodes: groups[0] and groups[1] (ascending) are unions of whole subtrees of the
/// supernodal elimination tree whose rows lie in their own group or in `top`, run on two threads at once; `top`
/// (ascending) the rest, after both. All groups empty: every supernode in order on the calling thread.
struct SupernodeSchedule {
  std::array<std::vector<int>, 2> groups;
  std::vector<int> top;
};

/// The instruction set of the dense kernels (Eigen's products, Cholesky factorisations and triangular solves).
enum class DenseKernels {
  kAuto,      ///< kAvx2 where the CPU has AVX2 and FMA, else kBaseline
  kBaseline,  ///< baseline x86-64 (SSE2), as the rest of liftmap is compiled
  kAvx2,      ///< AVX2 with FMA: about twice the baseline's speed per core on large blocks
};

/// Whether this build has the AVX2 kernels (x86-64) and the CPU runs them (AVX2 and FMA, enabled by the OS).
[[nodiscard]] bool avx2_kernels_available();

/// Refuses kernels this build or CPU cannot run.
/// \throw std::invalid_argument if `kernels` is kAvx2 and avx2_kernels_available() is false.
void require_dense_kernels(DenseKernels kernels);

/// Computes L with L L^T = B into x (the structure's values, every supernode's block overwritten). The arithmetic
/// depends on the schedule and the kernels, not on the number of threads: one thread runs the groups one after
/// the other. The two kernels round differently (FMA), so a factor's last bits depend on the CPU under
/// kAuto.
/// \return -1 on success, else the first column of a supernode whose diagonal block is not numerically positive
///         definite (the factorisation stops there; supernodes of the other group may be done).
/// \throw std::invalid_argument if `kernels` is kAvx2 and avx2_kernels_available() is false.
int factorize_supernodal(const LowerColumns& B, const SupernodalStructure& L, double* x,
                         const SupernodeSchedule& schedule, DenseKernels kernels = DenseKernels::kAuto);

}  // namespace liftmap
