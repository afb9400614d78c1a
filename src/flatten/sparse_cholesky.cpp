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
  // per factorisation (bench/flatten/profile_flatten, same machine, one run after the other): camel-cow's 46k
  // unknowns 0.110 s -> 0.068 s, fandisk-bunny's 0.278 s -> 0.186 s. Four times coarser was the best of 1-8x.
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
  // CHOLMOD's supernodal kernels call BLAS on many small blocks; a threaded BLAS (OpenBLAS built on OpenMP)
  // spends more on synchronisation than it gains there (4x slower on 2 cores): factorise single-threaded.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  impl_->llt.factorize(A);
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
