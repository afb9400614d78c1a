#pragma once
/// Independent work items on the calling thread's OpenMP threads, with exceptions carried back to the caller.
/// The including target must compile with OpenMP (OpenMP::OpenMP_CXX); without it the items run in order.

#include <omp.h>

#include <algorithm>
#include <exception>
#include <vector>

namespace liftmap {

/// Calls work(i) for every i in [0, n), one item at a time per thread, on at most min(max_threads,
/// omp_get_max_threads()) threads: the caller's thread count (omp_set_num_threads, the `--threads` option) is
/// respected, and inside another parallel region the items run on the one thread. The items must be independent
/// (no item reads what another writes), so that the results do not depend on the threads.
/// An exception thrown by an item is caught; once every item has run, the one of the lowest index is rethrown (the
/// error a loop in order would have reported, though the items after it have run).
template <class Work>
void parallel_for_each(int n, int max_threads, const Work& work) {
  std::vector<std::exception_ptr> failed(static_cast<size_t>(std::max(n, 0)));
  const int threads = std::max(1, std::min({max_threads, omp_get_max_threads(), std::max(n, 1)}));
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (int i = 0; i < n; ++i) {
    try {
      work(i);
    } catch (...) {
      failed[static_cast<size_t>(i)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace liftmap
