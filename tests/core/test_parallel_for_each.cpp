#include "core/parallel_for_each.h"
#include "core/thread_count_scope.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace liftmap {
namespace {

TEST(parallel_for_each, RunsEveryItemOnce) {
  const ThreadCountScope two(2);
  std::vector<int> runs(100, 0);
  parallel_for_each(100, 2, [&](int i) { ++runs[static_cast<size_t>(i)]; });
  for (const int r : runs) EXPECT_EQ(r, 1);
  parallel_for_each(0, 2, [&](int) { FAIL() << "no item to run"; });
}

TEST(parallel_for_each, RethrowsTheErrorOfTheLowestItemAfterAllHaveRun) {
  const ThreadCountScope two(2);
  std::atomic<int> ran{0};
  try {
    parallel_for_each(8, 2, [&](int i) {
      ++ran;
      if (i == 3 || i == 6) throw std::runtime_error("item " + std::to_string(i));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "item 3");
  }
  EXPECT_EQ(ran.load(), 8);
}

/// The distinct OpenMP thread numbers that ran n items, with `max_threads` and the caller's count `count`.
std::set<int> threads_used(int n, int max_threads, int count) {
  const ThreadCountScope scope(count);
  std::set<int> used;
  std::mutex m;
  parallel_for_each(n, max_threads, [&](int) {
    const std::lock_guard<std::mutex> lock(m);
    used.insert(omp_get_thread_num());
  });
  return used;
}

TEST(parallel_for_each, KeepsToTheCallersThreadCountAndTheCap) {
  EXPECT_EQ(threads_used(16, 4, 1), std::set<int>{0});  // the caller asked for one thread
  EXPECT_EQ(threads_used(16, 1, 4), std::set<int>{0});  // the cap
  for (const int t : threads_used(16, 2, 4)) EXPECT_LT(t, 2);
}

}  // namespace
}  // namespace liftmap
