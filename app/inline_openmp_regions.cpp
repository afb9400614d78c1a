// Executable-only interpositions of two C entry points of other libraries, linked into the liftmap executable and
// the benchmarks (target liftmap_inline_openmp_regions), never into the library: a library must not replace its host
// process's symbols. Both consult liftmap::serial_cholmod_call_active(), true only while SparseCholesky runs CHOLMOD
// single-threaded on this thread; everywhere else they forward to the real function.
// Their names are libgomp's and SuiteSparse's ABI, hence outside our naming convention. What they buy, measured side
// by side, is in docs/performance.md ("OpenMP regions inline").

#include <dlfcn.h>

#include "flatten/sparse_cholesky.h"

// GCC's entry point of every `#pragma omp parallel` region, CHOLMOD's included (it calls nothing else of libgomp's
// region ABI). While CHOLMOD runs serialised, a region runs its body directly: that is what a team of one thread
// does (work-sharing constructs inside bind to the implicit one-thread team, as orphaned ones do). libgomp itself
// still allocates a team and makes a futex wake-up syscall for every region, even one serialised to a single
// thread: CHOLMOD opens one per supernode and per descendant update. If this definition is not the one the dynamic
// linker binds, nothing changes but the speed.
extern "C" void GOMP_parallel(  // NOLINT(readability-identifier-naming)
    void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  using Fn = void (*)(void (*)(void*), void*, unsigned, unsigned);
  // dlsym returns void*: the cast to a function pointer is POSIX's documented use of it.
  static const Fn real = reinterpret_cast<Fn>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  if (liftmap::serial_cholmod_call_active() || real == nullptr) {
    fn(data);
    return;
  }
  real(fn, data, num_threads, flags);
}

// SuiteSparse's clock, which CHOLMOD reads around every BLAS call of its supernodal factorisation for its own
// statistics (Common->CHOLMOD_CPU_*_TIME), which liftmap never reads: it stands still during liftmap's
// factorisations, and is SuiteSparse's own elsewhere.
extern "C" double SuiteSparse_time(void) {  // NOLINT(readability-identifier-naming)
  using Fn = double (*)();
  static const Fn real = reinterpret_cast<Fn>(dlsym(RTLD_NEXT, "SuiteSparse_time"));
  if (liftmap::serial_cholmod_call_active() || real == nullptr) return 0;
  return real();
}
