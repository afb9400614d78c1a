#include "flatten/joint_flatten.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "disk_patches.h"
#include "flatten/barrier_solver.h"
#include "flatten/flattening_checks.h"
#include "flatten/jacobian.h"
#include "flatten/subproblem_faces.h"

namespace liftmap {
namespace {

/// The liftability invariants of one iterate (docs/algorithm.md, "Facts the tests check").
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
  // Against the circle start (the relaxed start is itself most of the way).
  JointFlattenOptions circle = opt;
  circle.joint_start.newton.max_iterations = 0;
  circle.max_iterations = 0;
  const double circle_energy = joint_flatten(a.flattening_disk(), b.flattening_disk(), circle).iterations[0].energy;
  EXPECT_LT(r.iterations.back().energy, 0.9 * circle_energy) << "no distortion reduction";
  EXPECT_LT(r.iterations.back().energy, r.iterations.front().energy) << "no gain from the start";
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
  JointFlattenOptions opt;  // coarsest gap 1e-2, finest gap 1e-5, gap_fraction 0.3
  std::vector<JointFlattenIteration> its(1);
  its[0].energy = 1000;
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-2);  // first subproblem: the coarsest gap
  its.emplace_back().energy = 10;                    // a 99x gain: clamped to the coarsest gap
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-2);
  its.emplace_back().energy = 10 / (1 + 0.02);  // relative gain 2e-2: a third of it
  EXPECT_NEAR(subproblem_gap(opt, its), 6e-3, 1e-15);
  its.emplace_back().energy = its.back().energy / (1 + 4e-3);  // relative gain 4e-3: a third of it
  EXPECT_NEAR(subproblem_gap(opt, its), 1.2e-3, 1e-15);
  its.emplace_back().energy = its.back().energy * (1 - 1e-6);  // tiny gain: never finer than solver.relative_gap
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-5);
  opt.gap_fraction = 0;  // off: always the solver's own gap
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-5);
  its.resize(1);
  EXPECT_DOUBLE_EQ(subproblem_gap(opt, its), 1e-5);
}

TEST(flatten_joint, StartGapFollowsTheOuterProgress) {
  JointFlattenOptions opt;  // start_gap_fraction 0.15, half of gap_fraction
  EXPECT_DOUBLE_EQ(opt.start_gap_fraction, 0.5 * opt.gap_fraction);
  std::vector<JointFlattenIteration> its(1);
  its[0].energy = 1000;
  EXPECT_EQ(start_gap(opt, its, false), 0);  // first subproblem from the circle: the usual barrier parameter
  its.emplace_back().energy = 10;
  EXPECT_NEAR(start_gap(opt, its, false), 0.15 * 99, 1e-12);  // (the barrier method keeps the larger t anyway)
  its.emplace_back().energy = 10 / (1 + 4e-3);
  EXPECT_NEAR(start_gap(opt, its, false), 0.15 * 4e-3, 1e-15);
  EXPECT_NEAR(start_gap(opt, its, true), 0.15 * 4e-3, 1e-15);  // a relaxed start changes only the first
  opt.start_gap_fraction = 0.5;
  EXPECT_NEAR(start_gap(opt, its, false), 2e-3, 1e-15);
  its.emplace_back().energy = its.back().energy;  // no gain: no guess either
  EXPECT_EQ(start_gap(opt, its, false), 0);
  its.pop_back();
  opt.start_gap_fraction = 0;  // off
  EXPECT_EQ(start_gap(opt, its, false), 0);
}

TEST(flatten_joint, StartGapAtMostAFewTimesTheRotationGain) {
  JointFlattenOptions opt;  // start_gap_fraction 0.15, rotation_gain_start_fraction 2
  EXPECT_DOUBLE_EQ(opt.rotation_gain_start_fraction, 2);
  std::vector<JointFlattenIteration> its(2);
  its[0].energy = 5.447973;  // sphere-ellipsoid at 200k faces per mesh: a 2.8% gain, a 4e-4 rotation gain
  its[1].energy = 5.299117;
  its[1].subproblem_objective = 5.301212;
  const double gain = (its[0].energy - its[1].energy) / its[1].energy;
  const double rotations = (its[1].subproblem_objective - its[1].energy) / its[1].energy;
  EXPECT_NEAR(start_gap(opt, its, true), 2 * rotations, 1e-15);  // not 0.15 * gain = 4.2e-3
  EXPECT_LT(start_gap(opt, its, true), 0.15 * gain / 5);
  its[1].subproblem_objective = its[1].energy * (1 + 0.5 * gain);  // a large rotation gain: the last gain decides
  EXPECT_NEAR(start_gap(opt, its, true), 0.15 * gain, 1e-15);
  its[1].subproblem_objective = its[1].energy * (1 + 1e-9);  // never below half of the finest gap
  EXPECT_NEAR(start_gap(opt, its, true), 0.5 * opt.solver.relative_gap, 1e-18);
  its[1].subproblem_objective = 0;  // no subproblem recorded
  EXPECT_NEAR(start_gap(opt, its, true), 0.15 * gain, 1e-15);
  its[1].subproblem_objective = 5.301212;
  opt.rotation_gain_start_fraction = 0;  // off
  EXPECT_NEAR(start_gap(opt, its, true), 0.15 * gain, 1e-15);
}

TEST(flatten_joint, FirstStartGapAfterTheRelaxationIsAFractionOfItsOwnGap) {
  JointFlattenOptions opt;  // relaxed_start_gap_fraction 0.2, max_subproblem_gap 1e-2
  std::vector<JointFlattenIteration> its(1);
  its[0].energy = 8.1;
  EXPECT_NEAR(start_gap(opt, its, true), 0.2 * 1e-2, 1e-15);  // one centring, deeper than the gap needs
  EXPECT_EQ(start_gap(opt, its, false), 0);                   // from the circle: the usual parameter
  opt.max_subproblem_gap = 4e-3;
  EXPECT_NEAR(start_gap(opt, its, true), 0.2 * 4e-3, 1e-15);
  opt.gap_fraction = 0;  // every subproblem to the solver's own gap: so is the first's start
  EXPECT_NEAR(start_gap(opt, its, true), 0.2 * opt.solver.relative_gap, 1e-18);
  opt.relaxed_start_gap_fraction = 0;  // off
  EXPECT_EQ(start_gap(opt, its, true), 0);
}

// The second subproblem of a camel/cow patch pair (faces_a + faces_b faces): the first one solved from the Tutte
// start to a relative gap of 1e-3, then Algorithm 2's ghost vertices and rotations at its minimiser X, the start.
struct SecondSubproblem {
  JointFlattenProblem jp;
  Eigen::MatrixXd X;
};
SecondSubproblem second_subproblem(int faces_a, int faces_b, SparseCholesky& cholesky) {
  const auto [a, b] = testing::patch_pair("camel.off", "cow.off", faces_a, 0, faces_b);
  SecondSubproblem out{make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), {}), {}};
  SubproblemSettings solver;
  solver.relative_gap = 1e-3;
  out.X = solve_convex_subproblem(out.jp.subproblem, out.jp.X0, solver, cholesky).X;
  place_ghost_vertices(out.jp.subproblem, out.X);
  set_rotations(out.jp.subproblem, out.X);
  return out;
}

// The second subproblem of a faces_a + faces_b patch pair solved twice from its start X to relative_gap, with the
// options changed by vary(k, options) for k = 0, 1; both solves must be certified.
struct TwoWays {
  SecondSubproblem p;
  std::array<SubproblemResult, 2> r;
};
TwoWays solve_two_ways(int faces_a, int faces_b, double relative_gap,
                       const std::function<void(int, SubproblemSettings&)>& vary) {
  SparseCholesky cholesky;
  TwoWays out{second_subproblem(faces_a, faces_b, cholesky), {}};
  for (int k = 0; k < 2; ++k) {
    SubproblemSettings o;
    o.relative_gap = relative_gap;
    vary(k, o);
    out.r[static_cast<size_t>(k)] = solve_convex_subproblem(out.p.jp.subproblem, out.p.X, o, cholesky);
    EXPECT_TRUE(out.r[static_cast<size_t>(k)].converged()) << "variant " << k;
  }
  return out;
}

TEST(flatten_joint, InitialGapSkipsCentringsAndKeepsTheCertificate) {
  // The second subproblem of a real patch pair, from the first one's minimiser, with and without a first barrier
  // parameter matched to a gap of 1e-2: both certified, optima equal within the gap, the first t no lower and no
  // more centrings with it.
  const double gap = 1e-4;
  std::array<double, 2> first_t{0, 0};
  const auto [p, r] = solve_two_ways(1500, 500, gap, [&](int k, SubproblemSettings& o) {
    o.barrier.initial_gap = k == 0 ? 0.0 : 1e-2;
    o.on_step = [&first_t, k](const SubproblemStep& st) {
      if (first_t[static_cast<size_t>(k)] == 0) first_t[static_cast<size_t>(k)] = st.t;
    };
  });
  for (size_t k = 0; k < 2; ++k) {
    std::printf("  initial gap %g: first t %.3g, %d centrings, %d Newton steps, objective %.10g\n", k == 0 ? 0.0 : 1e-2,
                first_t[k], r[k].centrings, r[k].iterations, r[k].objective);
  }
  EXPECT_GT(first_t[1], first_t[0]);
  EXPECT_LE(r[1].centrings, r[0].centrings);
  EXPECT_NEAR(r[1].objective, r[0].objective, gap * r[0].objective);
}

TEST(flatten_joint, IsotropicCurvatureAfterShortStepsKeepsTheOptimum) {
  // The second subproblem of a real patch pair, solved with and without isotropic (gamma, delta) curvature after
  // merit-limited steps: the modified steps happen, both solves are certified and keep every face positively
  // oriented, their optima agree within the gap, and the modified steps save Newton steps.
  const double gap = 1e-6;
  std::array<int, 2> isotropic_steps{0, 0};
  const auto [p, r] = solve_two_ways(3000, 1000, gap, [&](int k, SubproblemSettings& o) {
    o.barrier.isotropic_anticonformal_curvature = k == 1;
    o.on_step = [&isotropic_steps, k](const SubproblemStep& st) {
      isotropic_steps[static_cast<size_t>(k)] += st.isotropic ? 1 : 0;
    };
  });
  for (size_t k = 0; k < 2; ++k) {
    std::printf("  isotropic %zu: %d Newton steps (%d isotropic), objective %.12g\n", k, r[k].iterations,
                isotropic_steps[k], r[k].objective);
    for (int m = 0; m < 2; ++m) {
      EXPECT_GT(
          signed_double_areas(p.jp.F[static_cast<size_t>(m)], mesh_positions(p.jp.subproblem, m, r[k].X)).minCoeff(),
          0);
    }
  }
  EXPECT_EQ(isotropic_steps[0], 0);
  EXPECT_GT(isotropic_steps[1], 0) << "the instance no longer exercises the isotropic steps";
  EXPECT_LT(r[1].iterations, r[0].iterations);
  EXPECT_NEAR(r[1].objective, r[0].objective, gap * r[0].objective);
}

TEST(flatten_joint, AdaptiveGapIsRecordedAndKeepsTheInvariants) {
  const auto [a, b] = testing::patch_pair("camel.off", "cow.off", 1500, 0, 500);
  JointFlattenOptions opt;
  opt.max_iterations = 4;
  const JointFlattenResult r = joint_flatten(a.flattening_disk(), b.flattening_disk(), opt);
  ASSERT_GE(r.iterations.size(), 3u);
  EXPECT_DOUBLE_EQ(r.iterations[1].subproblem_gap, opt.max_subproblem_gap);
  for (size_t i = 1; i < r.iterations.size(); ++i) {
    EXPECT_EQ(r.iterations[i].subproblem_gap, subproblem_gap(opt, {r.iterations.begin(), r.iterations.begin() + i}));
    EXPECT_LE(r.iterations[i].energy, r.iterations[i - 1].energy);
    EXPECT_TRUE(r.iterations[i].subproblem_converged) << "outer iteration " << i;
  }
  expect_liftable(a, r.Phi, "Phi");
  expect_liftable(b, r.Psi, "Psi");
}

// A subproblem solved to a gap coarser than the outer tolerance can end above its start (the gap rule expected more
// progress than was left); it is solved again only if the finer gap is below the gap it had, and off at 0. (The
// whole loop through that path: sphere-ellipsoid refined to 180k faces per mesh, bench section 3; the test patches
// never end above their start, whatever the gap rule's settings.)
TEST(flatten_joint, RefinesOnlySubproblemsCoarserThanTheTolerance) {
  JointFlattenOptions opt;  // relative_tolerance 1e-3, refined_gap_fraction 0.5: solved again at 5e-4
  SubproblemSettings s;
  s.relative_gap = 8.4e-3;
  EXPECT_TRUE(can_refine(opt, s));
  s.relative_gap = 5e-4;
  EXPECT_FALSE(can_refine(opt, s)) << "already at the refined gap: a second solve would repeat the first";
  s.relative_gap = 8.4e-3;
  opt.refined_gap_fraction = 0;
  EXPECT_FALSE(can_refine(opt, s));
  EXPECT_LT(JointFlattenOptions{}.refined_gap_fraction, 1)
      << "a second result above the start must certify convergence";
}

/// Ghost faces at X are well-shaped starts: positively oriented, and with X as their rest shape their Jacobians
/// are rotations (Sigma = sigma = 1, so sigma_tilde = 1 after set_rotations).
void expect_fresh_ghosts(const ConvexSubproblem& sp, const Eigen::MatrixXd& X) {
  const SubproblemMesh& g = sp.ghosts;
  EXPECT_GT(signed_double_areas(g.F, X).minCoeff(), 0) << "a ghost face is flipped or degenerate";
  const Eigen::MatrixXd P = similarity_parts(g.jacobian, g.F, X);
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    EXPECT_NEAR(std::hypot(P(f, 0), P(f, 1)), 1, 1e-9) << "ghost face " << f;
    EXPECT_NEAR(std::hypot(P(f, 2), P(f, 3)), 0, 1e-9) << "ghost face " << f;
  }
}

TEST(flatten_joint, GhostVerticesCloseReflexAndConvexCorners) {
  // An L-shaped hexagon, counter-clockwise; its corner (1, 1) is reflex (interior angle 3 pi / 2). A ghost vertex
  // on the bisector of the smaller angle between the two boundary edges would fall inside the disk there.
  ConvexSubproblem sp;
  const int nb = 6;
  Eigen::MatrixXd X(2 * nb, 2);
  X.topRows(nb) << 0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2;
  X.bottomRows(nb).setZero();
  sp.ghosts.F.resize(2 * nb, 3);
  for (int i = 0; i < nb; ++i) {
    sp.ghosts.F.row(2 * i) << i, (i + nb - 1) % nb, nb + i;
    sp.ghosts.F.row(2 * i + 1) << i, nb + i, (i + 1) % nb;
  }
  place_ghost_vertices(sp, X);
  expect_fresh_ghosts(sp, X);
  // The reflex corner's exterior wedge is the quarter plane towards (2, 2); its ghost lies on its bisector, at half
  // the mean length of the corner's two boundary edges (both 1).
  EXPECT_NEAR(X(nb + 3, 0), 1 + 0.5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(X(nb + 3, 1), 1 + 0.5 / std::sqrt(2.0), 1e-12);
  // A convex corner: (0, 0), exterior wedge of 3 pi / 2 from (0, 1) (towards the previous vertex) counter-clockwise
  // to (1, 0); bisector (-1, -1) / sqrt(2).
  EXPECT_NEAR(X(nb, 0), -0.5 * 2 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(X(nb, 1), -0.5 * 2 / std::sqrt(2.0), 1e-12);
}

TEST(flatten_joint, GhostVerticesArePlacedAfreshForEachSubproblem) {
  // What joint_flatten does between two outer iterations, on a real patch pair: the first subproblem stretches
  // the ghost faces; placing the ghosts afresh restores well-shaped ghost faces, changes no energy (ghost faces
  // carry none) and gives a strictly feasible start for the second subproblem.
  const auto [a, b] = testing::patch_pair("camel.off", "cow.off", 1500, 0, 500);
  JointFlattenProblem jp = make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), {});
  ConvexSubproblem& sp = jp.subproblem;
  expect_fresh_ghosts(sp, jp.X0);
  SparseCholesky cholesky;
  SubproblemSettings solver;
  solver.relative_gap = 1e-3;
  const SubproblemResult first = solve_convex_subproblem(sp, jp.X0, solver, cholesky);
  ASSERT_TRUE(first.converged());
  const Eigen::MatrixXd P = similarity_parts(sp.ghosts.jacobian, sp.ghosts.F, first.X);
  double stretched = 0;
  for (Eigen::Index f = 0; f < P.rows(); ++f) stretched = std::max(stretched, std::hypot(P(f, 0), P(f, 1)));
  EXPECT_GT(stretched, 1.5) << "the first subproblem did not move the ghost faces away from their rest shape";

  Eigen::MatrixXd X = first.X;
  set_rotations(sp, X);
  const double before = subproblem_objective(sp, X);
  place_ghost_vertices(sp, X);
  set_rotations(sp, X);
  expect_fresh_ghosts(sp, X);
  EXPECT_EQ(X.topRows(X.rows() - sp.ghosts.F.rows() / 2), first.X.topRows(X.rows() - sp.ghosts.F.rows() / 2));
  EXPECT_NEAR(subproblem_objective(sp, X), before, 1e-12 * before);
  const SubproblemResult second = solve_convex_subproblem(sp, X, solver, cholesky);
  EXPECT_TRUE(second.converged());
  EXPECT_LE(second.objective, before);
}

TEST(flatten_joint, AssemblyStructureIsSharedOnlyBySubproblemsOfTheSameFaces) {
  // joint_flatten keeps the Newton system's pattern and face partition for all its subproblems. The next subproblem
  // of the same pair (new rotations and ghosts) reuses them and solves exactly as with its own; the subproblem of
  // another pair rebuilds them.
  SparseCholesky cholesky;
  SecondSubproblem p = second_subproblem(1500, 500, cholesky);
  SubproblemSettings o;
  o.relative_gap = 1e-4;
  subproblem::AssemblyStructure cache;
  const SubproblemResult first = solve_convex_subproblem(p.jp.subproblem, p.X, o, cholesky, &cache);
  ASSERT_TRUE(first.converged());
  ASSERT_FALSE(cache.var.empty());
  const auto* index = cache.pattern.index.data();
  Eigen::MatrixXd X = first.X;
  place_ghost_vertices(p.jp.subproblem, X);
  set_rotations(p.jp.subproblem, X);
  const SubproblemResult shared = solve_convex_subproblem(p.jp.subproblem, X, o, cholesky, &cache);
  EXPECT_EQ(cache.pattern.index.data(), index) << "rebuilt for the same faces";
  const SubproblemResult own = solve_convex_subproblem(p.jp.subproblem, X, o, cholesky);
  EXPECT_EQ(shared.X, own.X);
  EXPECT_EQ(shared.iterations, own.iterations);

  SparseCholesky other_cholesky;
  SecondSubproblem q = second_subproblem(900, 400, other_cholesky);
  const SubproblemResult other = solve_convex_subproblem(q.jp.subproblem, q.X, o, other_cholesky, &cache);
  EXPECT_NE(cache.pattern.index.data(), index) << "kept for other faces";
  EXPECT_EQ(cache.var.size(),
            static_cast<size_t>(q.jp.subproblem.meshes[0].F.rows() + q.jp.subproblem.meshes[1].F.rows() +
                                q.jp.subproblem.ghosts.F.rows()));
  EXPECT_EQ(other.X, solve_convex_subproblem(q.jp.subproblem, q.X, o, other_cholesky).X);
}

// An uncut tentacle (a capped tube 6 times as long as its girth) against a short bump with as many boundary
// vertices: plain Tutte underflows the tentacle's tip (joint_flatten failed with "a face is flipped or degenerate
// in outer iteration 0"); the start now keeps every face above 1e-10 of the mean, and every iterate is liftable.
TEST(flatten_joint, UncutTentacleAgainstABump) {
  const testing::TestDisk tentacle = testing::capped_tube(6);
  const testing::TestDisk bump = testing::capped_tube(0.3);
  ASSERT_EQ(tentacle.boundary.size(), bump.boundary.size());
  JointFlattenOptions options;
  options.max_iterations = 6;
  check_pair(tentacle, bump, options);
  const JointFlattenResult r = joint_flatten(tentacle.flattening_disk(), bump.flattening_disk(), options);
  EXPECT_GT(r.iterations.front().min_area_ratio, 1e-10);
  EXPECT_GT(r.start_steps[0], 0) << "the squeezed start was not optimised";
  EXPECT_EQ(r.start_steps[1], 0) << "the bump's plain Tutte start needs no drift";
  EXPECT_LT(r.iterations.back().max_distortion, 1000);
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
