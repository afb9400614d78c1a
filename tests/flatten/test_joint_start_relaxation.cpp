#include "flatten/joint_start_relaxation.h"

#include <gtest/gtest.h>
#include <Eigen/SVD>

#include <cmath>
#include <numbers>

#include "disk_patches.h"
#include "flatten/flattening_checks.h"
#include "flatten/jacobian.h"
#include "flatten/joint_flatten.h"

namespace liftmap {
namespace {

/// A planar disk: a jittered grid of the rectangle [0, 2] x [0, 1] (the circle is far from its optimal boundary).
testing::TestDisk planar_rectangle(int n) { return testing::jittered_planar_grid(2 * n, n, 0.25, 5); }

/// Largest max(Sigma, 1/sigma) over the faces of mesh k at X.
double max_distortion(const ConvexSubproblem& sp, int k, const Eigen::MatrixXd& X) {
  const SubproblemMesh& m = sp.meshes[static_cast<size_t>(k)];
  return true_distortion(similarity_parts(m.jacobian, m.F, mesh_positions(sp, k, X))).maxCoeff();
}

void expect_feasible(const ConvexSubproblem& sp, const Eigen::MatrixXd& X) {
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(signed_double_areas(sp.meshes[static_cast<size_t>(k)].F, mesh_positions(sp, k, X)).minCoeff(), 0);
  }
  EXPECT_GT(signed_double_areas(sp.ghosts.F, X).minCoeff(), 0) << "a ghost face flipped: a boundary angle sum >= 2 pi";
}

JointFlattenOptions without_relaxation() {
  JointFlattenOptions o;
  o.joint_start.newton.max_iterations = 0;
  return o;
}

// A planar rectangle mapped onto itself: the start puts its boundary on the unit circle, and only a relaxation whose
// boundary moves can find the isometry (energy 0, every face a rotation) that the fixed circle rules out.
TEST(flatten_joint_start_relaxation, FindsTheIsometryOfAPlanarDiskThatTheCircleRulesOut) {
  const testing::TestDisk a = planar_rectangle(8), b = planar_rectangle(8);
  JointFlattenProblem jp = make_joint_flatten_problem(a.flattening_disk(), b.flattening_disk(), without_relaxation());
  ASSERT_GT(max_distortion(jp.subproblem, 0, jp.X0), 1.5) << "the circle start is already nearly isometric";
  JointStartRelaxationOptions o;
  o.newton = {.max_iterations = 60, .relative_decrease = 0};
  o.ghost_weight = 1e-9;  // the ghosts' rest shape is the circle's: nearly free, they only keep angle sums < 2 pi
  const SymmetricDirichletResult r = relax_joint_start(jp.subproblem, jp.X0, o);
  expect_feasible(jp.subproblem, r.U);
  EXPECT_LT(r.energy, 1e-6 * r.energy_start);
  EXPECT_LT(max_distortion(jp.subproblem, 0, r.U), 1 + 1e-4);
  EXPECT_LT(max_distortion(jp.subproblem, 1, r.U), 1 + 1e-4);
  EXPECT_EQ(r.U.row(0), jp.X0.row(0)) << "the gauge slot moved";
}

// On an uncut tentacle against a bump, the relaxation (100 steps at most) lowers the start's energy (8) and keeps every
// face of both disks and every ghost face positively oriented, and joint_flatten reports it.
TEST(flatten_joint_start_relaxation, LowersTheStartOfAnUncutTentacleWithoutFlipping) {
  const testing::TestDisk tentacle = testing::capped_tube(6), bump = testing::capped_tube(0.3);
  JointFlattenProblem jp =
      make_joint_flatten_problem(tentacle.flattening_disk(), bump.flattening_disk(), without_relaxation());
  JointStartRelaxationOptions o;
  o.newton.max_iterations = 100;
  const SymmetricDirichletResult r = relax_joint_start(jp.subproblem, jp.X0, o);
  expect_feasible(jp.subproblem, r.U);
  EXPECT_GT(r.iterations, 0);
  EXPECT_LT(r.energy, 0.75 * r.energy_start);
  JointFlattenOptions one;
  one.max_iterations = 0;
  one.joint_start = o;
  const JointFlattenResult with = joint_flatten(tentacle.flattening_disk(), bump.flattening_disk(), one);
  one.joint_start.newton.max_iterations = 0;
  const JointFlattenResult without = joint_flatten(tentacle.flattening_disk(), bump.flattening_disk(), one);
  EXPECT_GT(with.joint_start.steps, 0);
  EXPECT_EQ(without.joint_start.steps, 0);
  EXPECT_LT(with.iterations[0].energy, without.iterations[0].energy);
  EXPECT_LT(with.iterations[0].max_distortion, without.iterations[0].max_distortion);
}

}  // namespace
}  // namespace liftmap
