#include "flatten/sparse_cholesky.h"

#include <dlfcn.h>
#include <omp.h>

#include <Eigen/CholmodSupport>

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
struct SparseCholesky::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  bool analyzed = false;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {
  // Failures are reported through factorize()'s return value; CHOLMOD's own warnings would only flood stdout.
  cholmod_common& cm = impl_->llt.cholmod();
  cm.print = 0;
  // CHOLMOD's default supernode relaxation (nrelax 4/16/48, zrelax 0.8/0.1/0.05). Four times coarser supernodes
  // were faster while libgomp's per-region cost came with every supernode (0.091 -> 0.048 s per factorisation on
  // camel-cow); with the regions inline (GOMP_parallel above) the defaults are faster again. Measured with
  // bench/flatten/profile_flatten, one outer iteration, alternating runs: camel-cow 31.5 -> 25.5 ms per
  // factorisation, fandisk-bunny 101-102 -> 83-94 ms.
}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  impl_->llt.analyzePattern(A);
  if (impl_->llt.info() != Eigen::Success) throw PipelineError("sparse Cholesky: symbolic analysis failed");
  impl_->analyzed = true;
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!impl_->analyzed) analyze(A);
  const SerialBlas serial;
  impl_->llt.factorize(A);
  return impl_->llt.info() == Eigen::Success;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  const SerialBlas serial;
  Eigen::MatrixXd X = impl_->llt.solve(B);
  if (impl_->llt.info() != Eigen::Success) throw PipelineError("sparse Cholesky: solve failed");
  return X;
}

bool SparseCholesky::analyzed() const { return impl_->analyzed; }

}  // namespace liftmap
