#include "flatten/joint_flatten.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "disk_patches.h"
#include "flatten/flattening_checks.h"

namespace liftmap {
namespace {

/// The liftability invariants of one iterate (NOTES.md, "Facts worth testing").
void expect_liftable(const testing::TestDisk& d, const Eigen::MatrixXd& U, const char* what) {
  EXPECT_GT(signed_double_areas(d.F, U).minCoeff(), 0) << what << ": flipped or degenerate face";
  const Eigen::VectorXd sums = angle_sums(*d.mesh, U);
  double worst_interior = 0, max_boundary = 0;
  for (int v = 0; v < d.mesh->n_vertices(); ++v) {
    if (d.mesh->is_boundary(VertexId(v))) {
      max_boundary = std::max(max_boundary, sums(v));
    } else {
      worst_interior = std::max(worst_interior, std::abs(sums(v) - 2 * std::numbers::pi));
    }
  }
  EXPECT_LT(worst_interior, 1e-8) << what;
  EXPECT_LT(max_boundary, 2 * std::numbers::pi) << what;
}

void check_pair(const testing::TestDisk& a, const testing::TestDisk& b, const JointFlattenOptions& base) {
  JointFlattenOptions opt = base;
  opt.keep_iterates = true;
  const JointFlattenResult r = joint_flatten(a.flattening_disk(), b.flattening_disk(), opt);
  ASSERT_GE(r.iterations.size(), 2u);
  ASSERT_EQ(r.Phi_iterates.size(), r.iterations.size());
  for (size_t i = 0; i < r.iterations.size(); ++i) {
    const auto& it = r.iterations[i];
    std::printf("  iterate %zu: energy %.8g (M %.6g, N %.6g), max distortion %.4g, %d Newton steps, %.3f s\n", i,
                it.energy, it.energy_m, it.energy_n, it.max_distortion, it.newton_steps, it.seconds);
    const std::string what = "iterate " + std::to_string(i);
    expect_liftable(a, r.Phi_iterates[i], what.c_str());
    expect_liftable(b, r.Psi_iterates[i], what.c_str());
    // Common boundary, exactly: the two flattenings share the boundary unknowns.
    for (size_t k = 0; k < a.boundary.size(); ++k) {
      ASSERT_EQ(r.Phi_iterates[i].row(a.boundary[k].idx), r.Psi_iterates[i].row(b.boundary[k].idx));
    }
    // The true energy (8) never increases (up to the subproblem's optimality tolerance).
    if (i > 0) EXPECT_LE(it.energy, r.iterations[i - 1].energy * (1 + 1e-7)) << what;
  }
  EXPECT_LT(r.iterations.back().energy, 0.9 * r.iterations.front().energy) << "no distortion reduction";
  EXPECT_EQ(r.Phi, r.Phi_iterates.back());
}

TEST(flatten_joint, CamelCowPatches) {
  const auto [a, b] = testing::patch_pair("camel.off", "cow.off", 1500, 0, 500);
  check_pair(a, b, {});
}

TEST(flatten_joint, CowCamelPatchesMaxDilation) {
  const auto [a, b] = testing::patch_pair("cow.off", "camel.off", 400, 2000, 3000);
  JointFlattenOptions opt;
  opt.h = DistortionCombiner::kMax;
  opt.max_iterations = 3;
  check_pair(a, b, opt);
}

TEST(flatten_joint, DeformedCopySameConnectivity) {
  const testing::TestDisk a = testing::mesh_patch("man.off", 2000, 800);
  const testing::TestDisk b = testing::deformed_copy(a);
  check_pair(a, b, {});
}

TEST(flatten_joint, InfinityNormPatches) {
  const auto [a, b] = testing::patch_pair("armadillo.off", "bear.off", 300, 100, 1000);
  JointFlattenOptions opt;
  opt.p = std::numeric_limits<double>::infinity();
  opt.max_iterations = 2;
  check_pair(a, b, opt);
}

TEST(flatten_joint, AutoSolverIsBarrierForTwoNormAndPrimalDualForInfinityNorm) {
  JointFlattenOptions opt;
  EXPECT_FALSE(uses_primal_dual(opt));
  opt.p = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(uses_primal_dual(opt));
  opt.method = SubproblemSolver::kBarrier;
  EXPECT_FALSE(uses_primal_dual(opt));
  opt.p = 2;
  opt.method = SubproblemSolver::kPrimalDual;
  EXPECT_TRUE(uses_primal_dual(opt));
}

TEST(flatten_joint, SubproblemGapFollowsTheOuterProgress) {
  JointFlattenOptions opt;  // relative_tolerance 1e-3, finest gap 1e-5, gap_fraction 0.1
  std::vector<JointFlattenIteration> its(1);
  its[0].energy = 1000;
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-3);  // first subproblem: the outer tolerance
  its.emplace_back().energy = 10;                    // a 99x gain: clamped to the outer tolerance
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-3);
  its.emplace_back().energy = 10 / (1 + 4e-3);  // relative gain 4e-3: a tenth of it
  EXPECT_NEAR(subproblem_gap(opt, its), 4e-4, 1e-15);
  its.emplace_back().energy = its.back().energy * (1 - 1e-6);  // tiny gain: never finer than solver.relative_gap
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-5);
  opt.gap_fraction = 0;  // off: always the solver's own gap
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-5);
  its.resize(1);
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-5);
}

TEST(flatten_joint, AdaptiveGapIsRecordedAndKeepsTheInvariants) {
  const auto [a, b] = testing::patch_pair("camel.off", "cow.off", 1500, 0, 500);
  JointFlattenOptions opt;
  opt.max_iterations = 4;
  const JointFlattenResult r = joint_flatten(a.flattening_disk(), b.flattening_disk(), opt);
  ASSERT_GE(r.iterations.size(), 3u);
  EXPECT_DOUBLE_EQ(r.iterations[1].subproblem_gap, opt.relative_tolerance);
  for (size_t i = 1; i < r.iterations.size(); ++i) {
    EXPECT_EQ(r.iterations[i].subproblem_gap, subproblem_gap(opt, {r.iterations.begin(), r.iterations.begin() + i}));
    EXPECT_LE(r.iterations[i].energy, r.iterations[i - 1].energy);
    EXPECT_TRUE(r.iterations[i].subproblem_converged) << "outer iteration " << i;
  }
  expect_liftable(a, r.Phi, "Phi");
  expect_liftable(b, r.Psi, "Psi");
}

TEST(flatten_joint, RejectsMismatchedBoundaries) {
  const testing::TestDisk a = testing::mesh_patch("cow.off", 0, 200);
  const testing::TestDisk b = testing::mesh_patch("cow.off", 900, 400);
  if (a.boundary.size() == b.boundary.size()) GTEST_SKIP();
  EXPECT_THROW(joint_flatten(a.flattening_disk(), b.flattening_disk()), InvalidInputError);
  FlatteningDisk reversed = a.flattening_disk();
  std::reverse(reversed.boundary.begin(), reversed.boundary.end());
  EXPECT_THROW(joint_flatten(a.flattening_disk(), reversed), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
