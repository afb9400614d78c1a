#pragma once
/// OpenMP's thread count of the calling thread, set for a scope (map_meshes, the outputs of map_files, tests).

#include <omp.h>

namespace liftmap {

/// Sets the calling thread's nthreads-var ICV (omp_set_num_threads) for the object's lifetime and restores it after;
/// threads <= 0 leaves it alone. Other threads of the process are not affected.
class ThreadCountScope {
 public:
  explicit ThreadCountScope(int threads) : saved_(omp_get_max_threads()), set_(threads > 0) {
    if (set_) omp_set_num_threads(threads);
  }
  ~ThreadCountScope() {
    if (set_) omp_set_num_threads(saved_);
  }
  ThreadCountScope(const ThreadCountScope&) = delete;
  ThreadCountScope& operator=(const ThreadCountScope&) = delete;
  ThreadCountScope(ThreadCountScope&&) = delete;
  ThreadCountScope& operator=(ThreadCountScope&&) = delete;

 private:
  int saved_;
  bool set_;
};

}  // namespace liftmap
