#include "flatten/sparse_cholesky.h"

#include <omp.h>

#include <Eigen/CholmodSupport>

#include "core/errors.h"

namespace liftmap {

// Supernodal LL^T: the fastest CHOLMOD mode for the 2D-mesh Laplacian-like systems of the flattening stage.
struct SparseCholesky::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  bool analyzed = false;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {
  // Failures are reported through factorize()'s return value; CHOLMOD's own warnings would only flood stdout.
  cholmod_common& cm = impl_->llt.cholmod();
  cm.print = 0;
  // Coarser supernodes than CHOLMOD's defaults (nrelax 4/16/48, zrelax 0.8/0.1/0.05): each supernode is a few BLAS
  // calls, and on these 2D-mesh systems the defaults make many tiny ones whose call overhead dominates. Measured
  // per factorisation (bench/flatten/profile_flatten, same machine, one run after the other, serialised as in
  // factorize): camel-cow's 46k unknowns 0.091 s -> 0.048 s, fandisk-bunny's 0.215 s -> 0.122 s. Four times
  // coarser was the best of 1-8x.
  cm.nrelax[0] = 16;
  cm.nrelax[1] = 64;
  cm.nrelax[2] = 192;
  cm.zrelax[0] = 0.8;
  cm.zrelax[1] = 0.4;
  cm.zrelax[2] = 0.2;
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
  // Factorise single-threaded. CHOLMOD's supernodal kernels call BLAS on many small blocks, and a threaded BLAS
  // (OpenBLAS built on OpenMP, which sizes its work split by omp_get_max_threads) spends more on
  // synchronisation than it gains there (4x slower on 2 cores). CHOLMOD itself also opens an OpenMP region per
  // supernode with a fixed num_threads(4) clause, which omp_set_num_threads does not override: on camel-cow
  // ~5900 thread wake-ups per factorisation. No active parallel levels serialises those. Both are needed:
  // with the levels alone, OpenBLAS splits its work for 2 threads, gets a team of 1 and spins forever.
  const int threads = omp_get_max_threads();
  const int levels = omp_get_max_active_levels();
  omp_set_num_threads(1);
  omp_set_max_active_levels(0);
  impl_->llt.factorize(A);
  omp_set_max_active_levels(levels);
  omp_set_num_threads(threads);
  return impl_->llt.info() == Eigen::Success;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
  Eigen::MatrixXd X = impl_->llt.solve(B);
  if (impl_->llt.info() != Eigen::Success) throw PipelineError("sparse Cholesky: solve failed");
  return X;
}

bool SparseCholesky::analyzed() const { return impl_->analyzed; }

}  // namespace liftmap
