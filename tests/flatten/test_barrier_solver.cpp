#include "flatten/barrier_solver.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <random>

#include "disk_patches.h"
#include "flatten/flattening_checks.h"
#include "flatten/joint_flatten.h"
#include "flatten/sparse_cholesky.h"

namespace liftmap {
namespace {

// SparseCholesky runs CHOLMOD's OpenMP regions inline through its GOMP_parallel shim; every other region (ours, the
// host application's) must still get its threads, and the factorisation must still be right.
TEST(flatten_sparse_cholesky, FactorisesAndLeavesOtherParallelRegionsTheirThreads) {
  const int n = 400;  // a path Laplacian plus identity: CHOLMOD opens regions for it like for the real systems
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

using testing::Combo;

class flatten_barrier : public ::testing::TestWithParam<Combo> {};

TEST_P(flatten_barrier, SolvesFirstSubproblemToOptimality) {
  const Combo combo = GetParam();
  const JointFlattenProblem jp = testing::camel_cow_patch_problem(combo);
  SparseCholesky chol;
  const BarrierResult r = solve_convex_subproblem(jp.subproblem, jp.X0, BarrierOptions{}, chol);
  const double f0 = subproblem_objective(jp.subproblem, jp.X0);
  // p = inf: the Newton systems reach double-precision limits before a 1e-8 gap (see BarrierOptions).
  const double gap = std::isinf(combo.p) ? 1e-5 : 1e-8;
  if (!std::isinf(combo.p)) EXPECT_TRUE(r.converged);
  std::printf("%s: start %.10g optimum %.10g, %d Newton steps, %d centrings\n", combo.name, f0, r.objective,
              r.newton_steps, r.centrings);
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
  const BarrierResult r = solve_convex_subproblem(jp.subproblem, jp.X0, opt.solver, chol);
  const double f0 = subproblem_objective(jp.subproblem, jp.X0);
  std::printf("%d + %d faces: start %.8g, result %.8g, gap bound %.2g, %d Newton steps, %d centrings (%d stalled)\n",
              static_cast<int>(a.F.rows()), static_cast<int>(b.F.rows()), f0, r.objective, r.gap_bound, r.newton_steps,
              r.centrings, r.stalled_centrings);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.stalled_centrings, 0);
  EXPECT_LT(r.objective, f0);
  EXPECT_LE(r.gap_bound, opt.solver.relative_gap * r.objective);
  const BarrierResult again = solve_convex_subproblem(jp.subproblem, r.X, opt.solver, chol);
  std::printf("solved again from the result: %.8g\n", again.objective);
  EXPECT_GE(again.objective, r.objective - r.gap_bound - 1e-12 * r.objective);
}

INSTANTIATE_TEST_SUITE_P(AllCombos, flatten_barrier, ::testing::ValuesIn(testing::kAllCombos),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace liftmap
