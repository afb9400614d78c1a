// The flattening is a guest in its host process: a program that links the library keeps its own OpenMP settings
// and team sizes before, during (on its other threads) and after a flattening.

#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <thread>
#include <vector>

#include "disk_patches.h"
#include "flatten/joint_flatten.h"

namespace liftmap {
namespace {

// The team size a parallel region of this thread gets.
int team_size() {
  int size = 0;
#pragma omp parallel
  {
#pragma omp single
    size = omp_get_num_threads();
  }
  return size;
}

TEST(flatten_host_process, KeepsTheHostsOpenMPSettingsAndTeams) {
  omp_set_dynamic(0);
  omp_set_num_threads(3);
  omp_set_max_active_levels(2);
  ASSERT_EQ(team_size(), 3);
  const auto [a, b] = testing::patch_pair("camel.off", "cow.off", 1500, 0, 500);

  // The host's own thread runs parallel regions while the library flattens on another thread.
  std::atomic<bool> done{false};
  JointFlattenResult r;
  std::thread worker([&] {
    r = joint_flatten(a.flattening_disk(), b.flattening_disk(), JointFlattenOptions{});
    done = true;
  });
  std::vector<int> sizes;
  while (!done) {
    // Each region is a fresh team of this thread's ICVs: a process-wide change would shrink it.
    omp_set_num_threads(3);
    sizes.push_back(team_size());
    EXPECT_EQ(omp_get_max_active_levels(), 2);
  }
  worker.join();
  ASSERT_FALSE(sizes.empty());
  for (const int s : sizes) EXPECT_EQ(s, 3) << "a host region ran with another team size during the flattening";
  ASSERT_GE(r.iterations.size(), 2u);

  // And after it, on the thread that called it.
  const JointFlattenResult again = joint_flatten(a.flattening_disk(), b.flattening_disk(), JointFlattenOptions{});
  EXPECT_EQ(again.Phi, r.Phi);
  EXPECT_EQ(omp_get_max_threads(), 3);
  EXPECT_EQ(omp_get_max_active_levels(), 2);
  EXPECT_EQ(omp_get_dynamic(), 0);
  EXPECT_EQ(team_size(), 3);
}

}  // namespace
}  // namespace liftmap
