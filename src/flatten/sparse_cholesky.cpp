#include "flatten/sparse_cholesky.h"

#include <dlfcn.h>
#include <omp.h>

#include <cholmod.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/errors.h"

namespace liftmap {

namespace {
thread_local bool g_serial_regions = false;  // set by SerialBlas on the thread that runs CHOLMOD
}
}  // namespace liftmap

// GCC's entry point of every `#pragma omp parallel` region, CHOLMOD's included (it calls nothing else of libgomp's
// region ABI), defined here so that the executable's definition comes first. While SerialBlas is active on this
// thread, a region runs its body directly: that is what a team of one thread does (work-sharing constructs inside
// bind to the implicit one-thread team, as orphaned ones do). libgomp itself still allocates a team and makes a
// futex wake-up syscall for every region, even one serialised to a single thread: CHOLMOD opens one per supernode
// and per descendant update, ~15k per factorisation on camel-cow at ~1.2 us each, with cache effects on top.
// Measured (profile_flatten, camel-cow, one outer iteration, one run after the other): factorisation 52 -> 29 ms
// per Newton step, the outer iteration 8.1 -> 6.5 s. Elsewhere (our own loops, a host application's) every region
// goes to libgomp. If this definition is not the one the dynamic linker binds (a module loaded with RTLD_LOCAL, a
// runtime other than libgomp), nothing changes but the speed: SerialBlas still keeps the regions to one thread.
// The name is libgomp's ABI, hence outside our naming convention.
extern "C" void GOMP_parallel(  // NOLINT(readability-identifier-naming)
    void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  using Fn = void (*)(void (*)(void*), void*, unsigned, unsigned);
  static const Fn real = reinterpret_cast<Fn>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  if (liftmap::g_serial_regions || real == nullptr) {
    fn(data);
    return;
  }
  real(fn, data, num_threads, flags);
}

namespace liftmap {
namespace {

// Runs CHOLMOD single-threaded while it lives. CHOLMOD's supernodal kernels call BLAS on many small blocks, and a
// threaded BLAS (OpenBLAS built on OpenMP, which sizes its work split by omp_get_max_threads) spends more on
// synchronisation than it gains there (factorisation 4x slower on 2 cores). CHOLMOD itself also opens an OpenMP
// region per supernode with a fixed num_threads(4) clause, which omp_set_num_threads does not override: on
// camel-cow ~5900 thread wake-ups per factorisation. No active parallel levels serialises those. Both are needed:
// with the levels alone, OpenBLAS splits its work for 2 threads, gets a team of 1 and spins forever. The
// triangular solves (three right-hand sides) are the same kind of small-block BLAS calls.
class SerialBlas {
 public:
  SerialBlas() : threads_(omp_get_max_threads()), levels_(omp_get_max_active_levels()) {
    omp_set_num_threads(1);
    omp_set_max_active_levels(0);
    g_serial_regions = true;
  }
  ~SerialBlas() {
    g_serial_regions = false;
    omp_set_max_active_levels(levels_);
    omp_set_num_threads(threads_);
  }
  SerialBlas(const SerialBlas&) = delete;
  SerialBlas& operator=(const SerialBlas&) = delete;

 private:
  int threads_, levels_;
};

}  // namespace

// Supernodal LL^T: the fastest CHOLMOD mode for the 2D-mesh Laplacian-like systems of the flattening stage.
//
// CHOLMOD is given the matrix already permuted by its own fill-reducing ordering, and factorises it in natural
// order. Given the lower triangle of A and an ordering, cholmod_factorize first builds triu(PAP') and then its
// transpose, two scattered copies of the whole matrix with their allocations, at every factorisation (camel-cow:
// cholmod_transpose_sym ~15% of the time in CHOLMOD). Here one gather of the values into P A P', whose pattern
// and source indices are built once in analyze(), replaces both.
struct SparseCholesky::Impl {
  cholmod_common cm{};
  cholmod_factor* L = nullptr;  // factor of P A P' (natural ordering)
  cholmod_sparse* B = nullptr;  // lower triangle of P A P', the matrix CHOLMOD factorises
  std::vector<int> perm;        // row i of P A P' is row perm[i] of A
  std::vector<int> source;      // B's k-th value is A's source[k]-th value
  Eigen::Index n = 0, a_nonzeros = 0;
  bool analyzed = false;

  Impl() {
    cholmod_start(&cm);
    // Failures are reported through factorize()'s return value; CHOLMOD's own warnings would only flood stdout.
    cm.print = 0;
    cm.supernodal = CHOLMOD_SUPERNODAL;
    cm.final_asis = 1;  // keep L supernodal LL' after the factorisation: solve() reads it in that form
    // A matrix that is not positive definite (factorize_with_shift then retries with a diagonal shift) is
    // abandoned at the failing supernode instead of being factorised to the end.
    cm.quick_return_if_not_posdef = 1;
    // CHOLMOD's default supernode relaxation (nrelax 4/16/48, zrelax 0.8/0.1/0.05). Four times coarser supernodes
    // were faster while libgomp's per-region cost came with every supernode (0.091 -> 0.048 s per factorisation
    // on camel-cow); with the regions inline (GOMP_parallel above) the defaults are faster again. Measured with
    // bench/flatten/profile_flatten, one outer iteration, alternating runs: camel-cow 31.5 -> 25.5 ms per
    // factorisation, fandisk-bunny 101-102 -> 83-94 ms. Finer ones hold fewer explicit zeros (camel-cow: 2.36M
    // stored values for 1.59M nonzeros of L at the defaults, 1.98M at zrelax 0.2/0.02/0.01), which the solve reads
    // faster, but the factorisation lost more than the solve gained (19.5 + 7.9 ms against 22.9 + 6.7 ms).
  }
  ~Impl() {
    if (L != nullptr) cholmod_free_factor(&L, &cm);
    if (B != nullptr) cholmod_free_sparse(&B, &cm);
    cholmod_finish(&cm);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  Impl(Impl&&) = delete;
  Impl& operator=(Impl&&) = delete;
};

namespace {

/// Systems with at least this many unknowns are ordered by nested dissection (METIS), smaller ones by AMD.
constexpr Eigen::Index kNestedDissectionUnknowns = 20000;

/// A CHOLMOD view (no copy) of the lower triangle of A.
cholmod_sparse lower_view(const Eigen::SparseMatrix<double>& A) {
  cholmod_sparse v{};
  v.nrow = static_cast<size_t>(A.rows());
  v.ncol = static_cast<size_t>(A.cols());
  v.nzmax = static_cast<size_t>(A.nonZeros());
  v.p = const_cast<int*>(A.outerIndexPtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast): CHOLMOD's C API
  v.i = const_cast<int*>(A.innerIndexPtr());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  v.x = const_cast<double*>(A.valuePtr());    // NOLINT(cppcoreguidelines-pro-type-const-cast)
  v.stype = -1;
  v.itype = CHOLMOD_INT;
  v.xtype = CHOLMOD_REAL;
  v.dtype = CHOLMOD_DOUBLE;
  v.sorted = 1;
  v.packed = 1;
  return v;
}

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Solves L L^T Y = Y in place for a supernodal LL^T factor, K right-hand sides (the columns of the row-major Y).
/// Per supernode: the dense triangle, then the rectangle below it as one dense product into a small buffer and
/// one scattered update per row (forward), or one gather per row and dense dot products (backward). CHOLMOD's own
/// supernodal solve calls BLAS twice per supernode and direction, which for the few right-hand sides of a Newton
/// step costs more in call and buffer overhead than in arithmetic (camel-cow: 12 ms per solve of 3 columns
/// against 25 ms per factorisation).
template <int K>
void supernodal_solve(const cholmod_factor& L, double* y) {
  const auto* super = static_cast<const int*>(L.super);
  const auto* pi = static_cast<const int*>(L.pi);
  const auto* px = static_cast<const int*>(L.px);
  const auto* rows = static_cast<const int*>(L.s);
  const auto* x = static_cast<const double*>(L.x);
  const auto nsuper = static_cast<int>(L.nsuper);
  std::vector<double> w(L.maxesize * K);
  // Forward: L Z = Y. Column j of supernode s has its diagonal at local row j and its rows at rows[pi[s] ..].
  for (int s = 0; s < nsuper; ++s) {
    const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s], m = nsrow - nscol;
    const double* ls = x + px[s];
    double* y1 = y + static_cast<ptrdiff_t>(k1) * K;
    for (int j = 0; j < nscol; ++j) {
      const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow;
      for (int c = 0; c < K; ++c) y1[j * K + c] /= col[j];
      for (int i = j + 1; i < nscol; ++i) {
        for (int c = 0; c < K; ++c) y1[i * K + c] -= col[i] * y1[j * K + c];
      }
    }
    if (m == 0) continue;
    std::fill(w.begin(), w.begin() + static_cast<ptrdiff_t>(m) * K, 0.0);
    for (int j = 0; j < nscol; ++j) {
      const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow + nscol;
      for (int i = 0; i < m; ++i) {
        for (int c = 0; c < K; ++c) w[static_cast<size_t>(i * K + c)] += col[i] * y1[j * K + c];
      }
    }
    const int* r = rows + pi[s] + nscol;
    for (int i = 0; i < m; ++i) {
      double* yi = y + static_cast<ptrdiff_t>(r[i]) * K;
      for (int c = 0; c < K; ++c) yi[c] -= w[static_cast<size_t>(i * K + c)];
    }
  }
  // Backward: L^T X = Z.
  for (int s = nsuper - 1; s >= 0; --s) {
    const int k1 = super[s], nscol = super[s + 1] - k1, nsrow = pi[s + 1] - pi[s], m = nsrow - nscol;
    const double* ls = x + px[s];
    double* y1 = y + static_cast<ptrdiff_t>(k1) * K;
    if (m > 0) {
      const int* r = rows + pi[s] + nscol;
      for (int i = 0; i < m; ++i) {
        const double* yi = y + static_cast<ptrdiff_t>(r[i]) * K;
        for (int c = 0; c < K; ++c) w[static_cast<size_t>(i * K + c)] = yi[c];
      }
      for (int j = 0; j < nscol; ++j) {
        const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow + nscol;
        std::array<double, K> acc{};
        for (int i = 0; i < m; ++i) {
          for (int c = 0; c < K; ++c) acc[static_cast<size_t>(c)] += col[i] * w[static_cast<size_t>(i * K + c)];
        }
        for (int c = 0; c < K; ++c) y1[j * K + c] -= acc[static_cast<size_t>(c)];
      }
    }
    for (int j = nscol - 1; j >= 0; --j) {
      const double* col = ls + static_cast<ptrdiff_t>(j) * nsrow;
      for (int i = j + 1; i < nscol; ++i) {
        for (int c = 0; c < K; ++c) y1[j * K + c] -= col[i] * y1[i * K + c];
      }
      for (int c = 0; c < K; ++c) y1[j * K + c] /= col[j];
    }
  }
}

/// supernodal_solve on k <= 3 columns, row-major.
void supernodal_solve(const cholmod_factor& L, Eigen::Index k, double* y) {
  if (k == 3) supernodal_solve<3>(L, y);
  if (k == 2) supernodal_solve<2>(L, y);
  if (k == 1) supernodal_solve<1>(L, y);
}

}  // namespace

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() != A.cols() || !A.isCompressed())
    throw PipelineError("sparse Cholesky: A must be square and compressed");
  Impl& m = *impl_;
  if (m.L != nullptr) cholmod_free_factor(&m.L, &m.cm);
  if (m.B != nullptr) cholmod_free_sparse(&m.B, &m.cm);
  m.analyzed = false;
  m.n = A.rows();
  m.a_nonzeros = A.nonZeros();
  // The fill-reducing ordering, postordered: METIS's nested dissection for large systems, else CHOLMOD's default
  // (AMD). CHOLMOD's default keeps AMD on the flattening systems, whose fill it finds acceptable, but nested
  // dissection needs fewer flops on these 2D-mesh graphs: camel-cow (46k unknowns) 1.33e8 against 1.54e8 per
  // factorisation, fandisk-bunny (105k) 5.97e8 against 8.09e8, for 0.16-0.35 s more analysis, once per
  // flattening. Measured side by side (profile_flatten, fandisk-bunny, 2 outer iterations, 81 factorisations):
  // 4.71-5.04 s of factorisation against 5.24-5.38 s with AMD, but the flattening as a whole equal within the
  // noise (14.6-15.3 s against 14.9-15.1 s); camel-cow equal (7.09-7.23 s against 7.12-7.32 s for 3 outer
  // iterations). On small systems the analysis would cost more than the factorisations save.
  cholmod_sparse view = lower_view(A);
  const bool nested_dissection = m.n >= kNestedDissectionUnknowns;
  if (nested_dissection) {
    m.cm.nmethods = 1;
    m.cm.method[0].ordering = CHOLMOD_METIS;
  }
  cholmod_factor* L0 = cholmod_analyze(&view, &m.cm);
  m.cm.nmethods = 0;  // CHOLMOD's defaults again
  m.cm.method[0].ordering = CHOLMOD_GIVEN;
  if (nested_dissection && (L0 == nullptr || m.cm.status < CHOLMOD_OK)) {  // a CHOLMOD built without METIS
    if (L0 != nullptr) cholmod_free_factor(&L0, &m.cm);
    L0 = cholmod_analyze(&view, &m.cm);
  }
  if (L0 == nullptr || m.cm.status < CHOLMOD_OK) throw PipelineError("sparse Cholesky: symbolic analysis failed");
  const auto* p0 = static_cast<const int*>(L0->Perm);
  m.perm.assign(p0, p0 + m.n);
  cholmod_free_factor(&L0, &m.cm);
  std::vector<int> inverse(static_cast<size_t>(m.n));
  for (Eigen::Index i = 0; i < m.n; ++i)
    inverse[static_cast<size_t>(m.perm[static_cast<size_t>(i)])] = static_cast<int>(i);

  // The lower triangle of P A P' in compressed columns, each value remembering where it comes from in A.
  struct Entry {
    int col, row, src;
  };
  std::vector<Entry> entries;
  entries.reserve(static_cast<size_t>(m.a_nonzeros));
  for (int c = 0; c < A.cols(); ++c) {
    for (int k = A.outerIndexPtr()[c]; k < A.outerIndexPtr()[c + 1]; ++k) {
      const int r = A.innerIndexPtr()[k];
      if (r < c) continue;  // only the lower triangle is read
      const int pr = inverse[static_cast<size_t>(r)], pc = inverse[static_cast<size_t>(c)];
      entries.push_back({std::min(pr, pc), std::max(pr, pc), k});
    }
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.col != b.col ? a.col < b.col : a.row < b.row; });
  m.B = cholmod_allocate_sparse(static_cast<size_t>(m.n), static_cast<size_t>(m.n), entries.size(), 1, 1, -1,
                                CHOLMOD_REAL, &m.cm);
  if (m.B == nullptr) throw PipelineError("sparse Cholesky: out of memory");
  auto* bp = static_cast<int*>(m.B->p);
  auto* bi = static_cast<int*>(m.B->i);
  m.source.resize(entries.size());
  std::fill(bp, bp + m.n + 1, 0);
  for (size_t e = 0; e < entries.size(); ++e) {
    ++bp[entries[e].col + 1];
    bi[e] = entries[e].row;
    m.source[e] = entries[e].src;
  }
  for (Eigen::Index c = 0; c < m.n; ++c) bp[c + 1] += bp[c];

  // Symbolic factorisation of P A P' as it stands: natural ordering, no postordering (P is already postordered).
  m.cm.nmethods = 1;
  m.cm.method[0].ordering = CHOLMOD_NATURAL;
  m.cm.postorder = 0;
  m.L = cholmod_analyze(m.B, &m.cm);
  m.cm.nmethods = 0;
  m.cm.method[0].ordering = CHOLMOD_GIVEN;
  m.cm.postorder = 1;
  if (m.L == nullptr || m.cm.status < CHOLMOD_OK || m.L->ordering != CHOLMOD_NATURAL) {
    throw PipelineError("sparse Cholesky: symbolic analysis failed");
  }
  m.analyzed = true;
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!impl_->analyzed) analyze(A);
  Impl& m = *impl_;
  if (A.rows() != m.n || A.nonZeros() != m.a_nonzeros) {
    throw PipelineError("sparse Cholesky: the matrix does not have the analysed pattern");
  }
  auto* bx = static_cast<double*>(m.B->x);
  const double* ax = A.valuePtr();
  const auto nb = static_cast<Eigen::Index>(m.source.size());
#pragma omp parallel for schedule(static) if (nb > 100000)
  for (Eigen::Index e = 0; e < nb; ++e) bx[e] = ax[m.source[static_cast<size_t>(e)]];
  const SerialBlas serial;
  cholmod_factorize(m.B, m.L, &m.cm);
  return m.cm.status == CHOLMOD_OK && m.L->minor == m.L->n;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  const Impl& m = *impl_;
  if (!m.analyzed || m.L->xtype == CHOLMOD_PATTERN || m.L->minor != m.L->n || !m.L->is_super || B.rows() != m.n) {
    throw PipelineError("sparse Cholesky: solve failed (no factorisation of this size)");
  }
  // Three columns at a time, permuted into a row-major block (one row per unknown: the solve's scattered
  // accesses touch one cache line per row), and permuted back.
  Eigen::MatrixXd X(m.n, B.cols());
  RowMajor Y;
  for (Eigen::Index c0 = 0; c0 < B.cols(); c0 += 3) {
    const Eigen::Index k = std::min<Eigen::Index>(3, B.cols() - c0);
    Y.resize(m.n, k);
    for (Eigen::Index i = 0; i < m.n; ++i) Y.row(i) = B.block(m.perm[static_cast<size_t>(i)], c0, 1, k);
    supernodal_solve(*m.L, k, Y.data());
    for (Eigen::Index i = 0; i < m.n; ++i) X.block(m.perm[static_cast<size_t>(i)], c0, 1, k) = Y.row(i);
  }
  return X;
}

bool SparseCholesky::analyzed() const { return impl_->analyzed; }

}  // namespace liftmap
