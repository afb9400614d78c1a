// The big sweep (ctest label "slow"): hundreds of seeded landmark configurations over the genus-0 demo meshes.
#include <gtest/gtest.h>

#include <cstdio>

#include "cut_test_util.h"

namespace liftmap {
namespace {

TEST(cut_sweep, HundredsOfRandomConfigurations) {
  const char* meshes[] = {"camel", "cow",       "bull", "dino",    "triceratops", "homer",
                          "man",   "armadillo", "bear", "fandisk", "hand",        "blobby"};
  const auto n = static_cast<unsigned>(std::size(meshes));
  std::mt19937 rng(2014);
  constexpr int kConfigurations = 300;
  for (int i = 0; i < kConfigurations; ++i) {
    const test::Case c{meshes[rng() % n], meshes[rng() % n]};
    const int k = 2 + static_cast<int>(rng() % 19);
    const auto pattern = static_cast<test::Pattern>(rng() % 3);
    const auto seed = static_cast<unsigned>(rng());
    std::printf("[%d/%d] %s-%s k=%d pattern=%d seed=%u\n", i + 1, kConfigurations, c.a, c.b, k,
                static_cast<int>(pattern), seed);
    std::fflush(stdout);
    test::run(c, k, pattern, seed);
  }
}

}  // namespace
}  // namespace liftmap
