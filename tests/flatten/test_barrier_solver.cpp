#include "flatten/barrier_solver.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <limits>
#include <random>

#include "core/errors.h"
#include "disk_patches.h"
#include "flatten/flattening_checks.h"
#include "flatten/joint_flatten.h"
#include "flatten/newton_system.h"
#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem_faces.h"

namespace liftmap {
namespace {

// SparseCholesky factorises in regions of its own (two threads at most) and changes no OpenMP setting: every
// other region (ours, the host application's) must still get its threads, and the factorisation must be right.
TEST(flatten_sparse_cholesky, FactorisesAndLeavesOtherParallelRegionsTheirThreads) {
  const int n = 400;  // a path Laplacian plus identity
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 3.0);
    if (i > 0) trip.emplace_back(i, i - 1, -1.0);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 3);
  const Eigen::MatrixXd x = chol.solve(b);
  const Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Lower>();
  EXPECT_LT((full * x - b).norm(), 1e-12 * b.norm());
  int team = 0;
#pragma omp parallel
  {
#pragma omp single
    team = omp_get_num_threads();
  }
  EXPECT_EQ(team, omp_get_max_threads());
}

// joint_flatten hands the relaxation's analysis to the convex subproblems only where the pattern is the same: a
// pattern with as many entries elsewhere must not pass, nor be factorised.
TEST(flatten_sparse_cholesky, RecognisesOnlyItsOwnPattern) {
  const int n = 50;
  // The diagonal and the sub-diagonal, with entry (moved, moved - 1) moved to (moved, 0) unless moved is 0.
  const auto matrix = [&](int moved) {
    std::vector<Eigen::Triplet<double>> trip;
    for (int i = 0; i < n; ++i) trip.emplace_back(i, i, 4.0);
    for (int i = 1; i < n; ++i) trip.emplace_back(i, i == moved ? 0 : i - 1, -1.0);
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(trip.begin(), trip.end());
    return A;
  };
  const Eigen::SparseMatrix<double> a = matrix(0), b = matrix(10);
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  SparseCholesky chol;
  EXPECT_FALSE(chol.has_pattern_of(a)) << "not analysed yet";
  chol.analyze(a);
  EXPECT_TRUE(chol.has_pattern_of(a));
  EXPECT_TRUE(chol.has_pattern_of(Eigen::SparseMatrix<double>(2.0 * a))) << "other values, same pattern";
  EXPECT_FALSE(chol.has_pattern_of(b)) << "as many entries, one elsewhere";
  EXPECT_FALSE(chol.has_pattern_of(Eigen::SparseMatrix<double>(a.topLeftCorner(n - 1, n - 1)))) << "smaller";
  // factorize() refuses a pattern it has not analysed, even of the same size and entry count, instead of
  // factorising it wrongly.
  EXPECT_TRUE(chol.factorize(Eigen::SparseMatrix<double>(2.0 * a)));
  EXPECT_THROW((void)chol.factorize(b), PipelineError);
}

// A grid "mesh" with two coordinates per vertex, coupled like the Newton systems (random SPD 2 x 2 couplings on each
// edge, a Laplacian-like sum plus a small shift on the diagonal): lower triangle plus garbage above it, which
// SparseCholesky must ignore.
Eigen::SparseMatrix<double> grid_system(int side, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const int nv = side * side, n = 2 * nv;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, 1e-3);
  auto couple = [&](int a, int b) {
    Eigen::Matrix2d M;
    M << u(rng), u(rng), u(rng), u(rng);
    const Eigen::Matrix2d W = M * M.transpose() + 0.1 * Eigen::Matrix2d::Identity();  // SPD edge weight
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) {
        // +W on both diagonal blocks, -W off the diagonal: the sum is positive semidefinite.
        trip.emplace_back(2 * b + r, 2 * a + c, -W(r, c));  // b > a: lower triangle
        trip.emplace_back(2 * a + c, 2 * b + r, 7.0);       // upper triangle: not read
        if (r >= c) {
          trip.emplace_back(2 * a + r, 2 * a + c, W(r, c));
          trip.emplace_back(2 * b + r, 2 * b + c, W(r, c));
        }
      }
    }
  };
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int v = i * side + j;
      if (j + 1 < side) couple(v, v + 1);
      if (i + 1 < side) couple(v, v + side);
      if (i + 1 < side && j + 1 < side) couple(v, v + side + 1);
    }
  }
  for (int k = 0; k < n; ++k) trip.emplace_back(k, k, diag(k));
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  return A;
}

// The factorisation and our supernodal solve against Eigen's simplicial LDL^T on the same lower triangle: on a
// small system (AMD ordering) and one above the nested-dissection threshold (METIS, solved on two threads), with
// 1 to 7 right-hand sides, after a refactorisation with new values, and a matrix that is not positive definite.
TEST(flatten_sparse_cholesky, SolvesLikeAnIndependentFactorisation) {
  std::mt19937 rng(7);
  for (const int side : {40, 110}) {
    Eigen::SparseMatrix<double> A = grid_system(side, rng);
    SparseCholesky chol;
    chol.analyze(A);
    // The larger grid's elimination tree splits into two halves for a two-threaded solve, with a small top.
    const SparseCholesky::SolveSplit split = chol.solve_split();
    if (side == 110) {
      ASSERT_TRUE(split.split);
      EXPECT_GT(std::min(split.group0, split.group1), 0.35);
      EXPECT_GT(split.top, 0);
      EXPECT_LT(split.top, 0.2);
      EXPECT_NEAR(split.group0 + split.group1 + split.top, 1, 1e-12);
    }
    // Analysed but not yet factorised: nothing to solve with.
    EXPECT_THROW((void)chol.solve(Eigen::MatrixXd::Ones(A.rows(), 1)), PipelineError);
    for (int round = 0; round < 2; ++round) {
      if (round == 1) {  // same pattern, new values
        for (Eigen::Index k = 0; k < A.outerSize(); ++k) {
          for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
            if (it.row() == it.col()) it.valueRef() *= 1.5;
          }
        }
      }
      const Eigen::SparseMatrix<double> lower = A.triangularView<Eigen::Lower>();
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> reference(lower);
      ASSERT_EQ(reference.info(), Eigen::Success);
      ASSERT_TRUE(chol.factorize(A)) << "side " << side << " round " << round;
      for (const int k : {1, 3, 4, 7}) {
        const Eigen::MatrixXd b = Eigen::MatrixXd::Random(A.rows(), k);
        const Eigen::MatrixXd x = chol.solve(b);
        const Eigen::MatrixXd expected = reference.solve(b);
        EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm()) << "side " << side << ", " << k << " columns";
        const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
        EXPECT_LT((full * x - b).norm(), 1e-9 * b.norm()) << "side " << side << ", " << k << " columns";
      }
      // The split solve on one thread (liftmap --threads 1): the two halves one after the other, same result.
      const Eigen::MatrixXd b = Eigen::MatrixXd::Random(A.rows(), 3);
      const Eigen::MatrixXd x2 = chol.solve(b);
      const int threads = omp_get_max_threads();
      omp_set_num_threads(1);
      const Eigen::MatrixXd x1 = chol.solve(b);
      omp_set_num_threads(threads);
      EXPECT_LT((x1 - x2).norm(), 1e-12 * x2.norm()) << "side " << side;
    }
    // Not positive definite: one diagonal entry made negative. The factorisation says so and solve refuses.
    Eigen::SparseMatrix<double> bad = A;
    bad.coeffRef(A.rows() / 2, A.rows() / 2) = -1;
    EXPECT_FALSE(chol.factorize(bad));
    EXPECT_THROW((void)chol.solve(Eigen::MatrixXd::Ones(A.rows(), 1)), PipelineError);
    // A matrix of another pattern is refused rather than misread.
    EXPECT_THROW((void)chol.factorize(grid_system(side - 1, rng)), PipelineError);
  }
}

// The faces of a 110 x 110 grid (two unknowns per vertex, vertex 0 fixed) split by the factorisation's halves: every
// face in exactly one list, the faces of lists 0 and 1 entirely inside their half, and the scatter over the three
// lists (two of them on two threads) equal to the serial one.
TEST(flatten_sparse_cholesky, FacePartitionFollowsTheHalves) {
  const int side = 110;
  subproblem::Setup s;
  auto var = [](int v, int k) { return v == 0 ? -1 : 2 * v + k - 2; };
  for (int i = 0; i + 1 < side; ++i) {
    for (int j = 0; j + 1 < side; ++j) {
      const int v = i * side + j;
      for (const std::array<int, 3> tri :
           {std::array<int, 3>{v, v + 1, v + side + 1}, std::array<int, 3>{v, v + side + 1, v + side}}) {
        subproblem::FaceSetup fs;
        for (int c = 0; c < 3; ++c) {
          fs.var[static_cast<size_t>(2 * c)] = var(tri[static_cast<size_t>(c)], 0);
          fs.var[static_cast<size_t>(2 * c + 1)] = var(tri[static_cast<size_t>(c)], 1);
        }
        s.faces.push_back(fs);
      }
    }
  }
  s.n_faces = static_cast<int>(s.faces.size());
  s.n_var = 2 * side * side - 2;
  const subproblem::Pattern pattern = subproblem::make_pattern(s);
  SparseCholesky chol;
  chol.analyze(pattern.A);
  const std::vector<int> halves = chol.unknown_halves();
  ASSERT_EQ(halves.size(), static_cast<size_t>(s.n_var));
  const subproblem::FacePartition parts = subproblem::partition_faces(s, chol);
  std::vector<int> seen(static_cast<size_t>(s.n_faces), 0);
  for (int list = 0; list < 3; ++list) {
    for (const int j : parts.lists[static_cast<size_t>(list)]) {
      ++seen[static_cast<size_t>(j)];
      if (list == 2) continue;
      for (const int v : s.faces[static_cast<size_t>(j)].var) {
        if (v >= 0) EXPECT_EQ(halves[static_cast<size_t>(v)], list) << "face " << j;
      }
    }
  }
  for (const int count : seen) ASSERT_EQ(count, 1);
  EXPECT_GT(parts.lists[0].size(), s.faces.size() / 3);
  EXPECT_GT(parts.lists[1].size(), s.faces.size() / 3);
  EXPECT_LT(parts.lists[2].size(), s.faces.size() / 10);
  // No two faces of different halves share an unknown, so the two threads never write the same row.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Matrix<double, 6, 3>> rows(static_cast<size_t>(s.n_faces));
  for (auto& r : rows) r = r.unaryExpr([&](double) { return u(rng); });
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(s.n_var, 3), expected = X;
  subproblem::subtract_corner_rows<3>(s, parts, rows, X);
  for (int j = 0; j < s.n_faces; ++j) {
    for (int r = 0; r < 6; ++r) {
      const int v = s.faces[static_cast<size_t>(j)].var[static_cast<size_t>(r)];
      if (v >= 0) expected.row(v) -= rows[static_cast<size_t>(j)].row(r);
    }
  }
  EXPECT_LT((X - expected).norm(), 1e-12 * expected.norm());
}

using testing::Combo;

class flatten_barrier : public ::testing::TestWithParam<Combo> {};

TEST_P(flatten_barrier, SolvesFirstSubproblemToOptimality) {
  const Combo combo = GetParam();
  const JointFlattenProblem jp = testing::camel_cow_patch_problem(combo);
  SparseCholesky chol;
  const SubproblemResult r = solve_convex_subproblem(jp.subproblem, jp.X0, SubproblemSettings{}, chol);
  const double f0 = subproblem_objective(jp.subproblem, jp.X0);
  // p = inf: the Newton systems reach double-precision limits before a 1e-8 gap (see SubproblemSettings).
  const double gap = std::isinf(combo.p) ? 1e-5 : 1e-8;
  if (!std::isinf(combo.p)) EXPECT_TRUE(r.converged());
  std::printf("%s: start %.10g optimum %.10g, %d Newton steps, %d centrings\n", combo.name, f0, r.objective,
              r.iterations, r.centrings);
  EXPECT_LT(r.objective, f0);
  EXPECT_LE(r.gap_bound, gap * r.objective);
  EXPECT_EQ(r.X.row(0), jp.X0.row(0)) << "the gauge vertex moved";
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(signed_double_areas(jp.F[k], mesh_positions(jp.subproblem, k, r.X)).minCoeff(), 0);
  }
  // Optimality: no random feasible perturbation nor step toward the start improves on the result.
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::MatrixXd D = Eigen::MatrixXd::NullaryExpr(r.X.rows(), 2, [&] { return normal(rng); });
    D.row(0).setZero();
    for (const double eps : {1e-3, 1e-5}) {
      const double fp = subproblem_objective(jp.subproblem, r.X + eps * D);
      EXPECT_GE(fp, r.objective * (1 - gap));
    }
  }
  for (const double s : {1e-2, 1e-4}) {
    EXPECT_GE(subproblem_objective(jp.subproblem, r.X + s * (jp.X0 - r.X)), r.objective * (1 - gap));
  }
}

// A whole mesh minus a small disk: its Tutte start has slivers (distortion in the thousands), the case where the
// solver once returned far from the optimum while claiming convergence (its Newton decrements had turned negative).
// The claim is checked independently: solving again from the result must not find an objective lower by more than
// the certified gap.
TEST(flatten_barrier, WholeMeshSubproblemCertificateHolds) {
  const auto [a, bb] = testing::punctured_pair("hand.off", "hand.off", 12);
  const testing::TestDisk b = testing::deformed_copy(bb);
  const JointFlattenOptions opt;
  const JointFlattenProblem jp = make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), opt);
  SparseCholesky chol;
  const SubproblemResult r = solve_convex_subproblem(jp.subproblem, jp.X0, opt.solver, chol);
  const double f0 = subproblem_objective(jp.subproblem, jp.X0);
  std::printf("%d + %d faces: start %.8g, result %.8g, gap bound %.2g, %d Newton steps, %d centrings (%d stalled)\n",
              static_cast<int>(a.F.rows()), static_cast<int>(b.F.rows()), f0, r.objective, r.gap_bound, r.iterations,
              r.centrings, r.stalled_centrings);
  ASSERT_TRUE(r.converged());
  EXPECT_EQ(r.stalled_centrings, 0);
  EXPECT_LT(r.objective, f0);
  EXPECT_LE(r.gap_bound, opt.solver.relative_gap * r.objective);
  const SubproblemResult again = solve_convex_subproblem(jp.subproblem, r.X, opt.solver, chol);
  std::printf("solved again from the result: %.8g\n", again.objective);
  EXPECT_GE(again.objective, r.objective - r.gap_bound - 1e-12 * r.objective);
}

// The subproblem solved to relative_gap by the barrier method's own gap bound alone (no dual point of the Newton
// direction).
SubproblemResult solve_by_own_bound(const JointFlattenProblem& jp, double relative_gap, SparseCholesky& chol) {
  SubproblemSettings settings;
  settings.relative_gap = relative_gap;
  settings.barrier.dual_gap_decrement = 0;
  return solve_convex_subproblem(jp.subproblem, jp.X0, settings, chol);
}

// A subproblem solved with the dual point (`with`) and by the method's own bound alone (`without`).
struct DualPointRun {
  SubproblemResult with, without;
};

// Solves jp to relative_gap with the dual point tried from lambda^2 / 2 <= decrement and without it, and checks the
// point's gap: met (relative to T_0 + T_1 at the point, at most the objective plus the gap;
// SubproblemSettings::relative_gap), holding against `best`, a much finer solve (the result no further above its
// optimum than the bound), of the size of the method's own bound at the same barrier parameter (both about nu / t; a
// point built wrongly gives one either never met or far too small), and costing no Newton steps.
DualPointRun check_dual_point(const JointFlattenProblem& jp, const SubproblemResult& best, double relative_gap,
                              double decrement, SparseCholesky& chol) {
  SubproblemSettings with;
  with.relative_gap = relative_gap;
  with.barrier.dual_gap_decrement = decrement;
  const SubproblemResult r = solve_convex_subproblem(jp.subproblem, jp.X0, with, chol);
  const SubproblemResult r0 = solve_by_own_bound(jp, relative_gap, chol);
  std::printf(
      "point tried from lambda^2 / 2 <= %g, relative gap %g: %d Newton steps, bound %.3g (without: %d, %.3g); "
      "above the optimum by %.3g\n",
      decrement, relative_gap, r.iterations, r.gap_bound, r0.iterations, r0.gap_bound, r.objective - best.objective);
  EXPECT_TRUE(r.converged());
  EXPECT_TRUE(r0.converged());
  EXPECT_LE(r.gap_bound, relative_gap * (r.objective + r.gap_bound));
  EXPECT_GE(r.gap_bound, r.objective - best.objective);
  EXPECT_GT(r.gap_bound, 0.3 * r0.gap_bound);
  EXPECT_LE(r.iterations, r0.iterations);
  return {r, r0};
}

// The dual point of a Newton direction (newton_dual_gap.h) certifies a gap before the Newton decrement falls below 1:
// at each relative gap it passes check_dual_point, here with the gap met relative to the objective itself, and over
// all gaps it saves Newton steps.
TEST(flatten_barrier, NewtonDualGapHoldsAndSavesSteps) {
  const JointFlattenProblem jp = testing::camel_cow_patch_problem(testing::kAllCombos[0]);  // p = 2, eq. 3
  SparseCholesky chol;
  const SubproblemResult best = solve_by_own_bound(jp, 1e-10, chol);
  ASSERT_TRUE(best.converged());
  int saved = 0;
  for (const double relative_gap : {1e-2, 1e-3, 1e-4, 1e-6}) {
    const DualPointRun run =
        check_dual_point(jp, best, relative_gap, SubproblemSettings().barrier.dual_gap_decrement, chol);
    EXPECT_LE(run.with.gap_bound, relative_gap * run.with.objective);
    saved += run.without.iterations - run.with.iterations;
  }
  EXPECT_GT(saved, 0);
}

// A whole mesh whose start squeezes faces (the punctured hand and a deformed copy, p = 2): far from the central path
// a few faces' Newton shares leave their epigraph's cones, and the dual point raises their c-cone multiplier or their
// v_e (newton_dual_gap.h) instead of giving up. Tried from lambda^2 / 2 <= 1e4 (the default): at the gap 3e-2 a
// point with 5 faces' v_e and one face's c-cone entry raised ends the centring at step 4 instead of 8, at 3e-3 one
// with 3 v_e raised at step 10 instead of 12; tried at every step, more points have faces raised. Each must pass
// check_dual_point.
TEST(flatten_barrier_whole, NewtonDualGapHoldsOnASqueezedWholeMesh) {
  const auto [a, b] = testing::punctured_pair("hand.off", "hand.off", 12);
  const JointFlattenProblem jp =
      make_joint_flatten_problem(a.flattening_disk(), testing::deformed_copy(b).flattening_disk(), {});
  SparseCholesky chol;
  const SubproblemResult best = solve_by_own_bound(jp, 1e-6, chol);
  ASSERT_TRUE(best.converged());
  for (const double decrement : {SubproblemSettings().barrier.dual_gap_decrement, 1e12}) {
    for (const double relative_gap : {3e-2, 1e-2, 3e-3, 1e-3}) {
      check_dual_point(jp, best, relative_gap, decrement, chol);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllCombos, flatten_barrier, ::testing::ValuesIn(testing::kAllCombos),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace liftmap
