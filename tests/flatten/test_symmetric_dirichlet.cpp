#include "flatten/symmetric_dirichlet.h"

#include <gtest/gtest.h>
#include <Eigen/LU>

#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "disk_patches.h"
#include "flatten/flattening_checks.h"
#include "flatten/flattening_start.h"
#include "flatten/tutte.h"

namespace liftmap {
namespace {

/// E(U) computed independently of the solver: J from the hat gradients, |J|^2 + |J^-1|^2 - 4 with an explicit
/// inverse.
double symmetric_dirichlet(const JacobianOperator& op, const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  double e = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
    for (int k = 0; k < 3; ++k) {
      J += U.row(F(f, k)).transpose() * op.G.block<1, 2>(f, 2 * k);
    }
    e += op.area(f) * (J.squaredNorm() + J.inverse().squaredNorm() - 4);
  }
  return e;
}

std::vector<char> boundary_flags(const testing::TestDisk& d) {
  std::vector<char> fixed(static_cast<size_t>(d.mesh->n_vertices()), 0);
  for (const VertexId v : d.boundary) fixed[static_cast<size_t>(v.idx)] = 1;
  return fixed;
}

/// n points on the unit circle, evenly spaced: a disk's boundary positions.
Eigen::MatrixXd unit_circle(size_t n) {
  Eigen::MatrixXd B(static_cast<Eigen::Index>(n), 2);
  for (Eigen::Index i = 0; i < B.rows(); ++i) {
    const double a = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(B.rows());
    B.row(i) << std::cos(a), std::sin(a);
  }
  return B;
}

/// The tube's positions scaled to area pi, as in joint_flatten.
Eigen::MatrixXd area_pi(const testing::TestDisk& d) {
  const JacobianOperator rest = jacobian_operator(d.V, d.F);
  return d.V * std::sqrt(std::numbers::pi / rest.area.sum());
}

/// A planar disk: a jittered grid of the unit square.
testing::TestDisk planar_grid(int n) { return testing::jittered_planar_grid(n, n, 0.3, 3); }

// With the boundary where the plane's rest shape has it, the minimum (energy 0) is the identity: the method must
// find it from a smooth interior displacement of it, which only its exact gradient and Hessian do in a few steps.
TEST(flatten_symmetric_dirichlet, RecoversTheIdentityOfAPlanarDisk) {
  const testing::TestDisk d = planar_grid(12);
  Eigen::MatrixXd U0 = d.V.leftCols(2);
  for (Eigen::Index v = 0; v < U0.rows(); ++v) {
    const double bump = std::sin(std::numbers::pi * d.V(v, 0)) * std::sin(std::numbers::pi * d.V(v, 1));
    U0.row(v) += 0.03 * bump * Eigen::RowVector2d(1, 0.5);
  }
  ASSERT_GT(signed_double_areas(d.F, U0).minCoeff(), 0);
  const JacobianOperator op = jacobian_operator(d.V, d.F);
  ASSERT_GT(symmetric_dirichlet(op, d.F, U0), 1e-3) << "the start is already the identity";
  const SymmetricDirichletResult r =
      minimize_symmetric_dirichlet(op, d.F, boundary_flags(d), U0, {.max_iterations = 30, .relative_decrease = 0});
  EXPECT_LT(r.energy, 1e-12);
  EXPECT_LT(r.iterations, 15);
  EXPECT_LT((r.U - d.V.leftCols(2)).cwiseAbs().maxCoeff(), 1e-6);
}

// On a drifted start of an uncut tube: the energy falls, every face stays positive, the boundary stays, and the
// reported energies are the energy.
TEST(flatten_symmetric_dirichlet, LowersATubesStartWithoutFlipping) {
  const testing::TestDisk d = testing::capped_tube(6);
  const Eigen::MatrixXd B = unit_circle(d.boundary.size());
  const Eigen::MatrixXd V = area_pi(d);
  const JacobianOperator op = jacobian_operator(V, d.F);
  const FlatteningStart s = flattening_start(*d.mesh, V, d.boundary, B,
                                             [&](const Eigen::MatrixXd& U) { return symmetric_dirichlet(op, d.F, U); });
  ASSERT_TRUE(s.squeezed);
  const SymmetricDirichletResult r = minimize_symmetric_dirichlet(op, d.F, boundary_flags(d), s.U);
  EXPECT_NEAR(r.energy_start, symmetric_dirichlet(op, d.F, s.U), 1e-9 * r.energy_start);
  EXPECT_NEAR(r.energy, symmetric_dirichlet(op, d.F, r.U), 1e-9 * r.energy);
  EXPECT_LT(r.energy, 0.25 * r.energy_start);
  EXPECT_GT(signed_double_areas(d.F, r.U).minCoeff(), 0);
  for (const VertexId v : d.boundary) ASSERT_EQ(r.U.row(v.idx), s.U.row(v.idx));
}

// From a drifted start of an uncut tube (crushed faces at its far end), proxy steps while they halve the energy, then
// projected Newton: never a flipped face, the boundary kept, the proxy steps counted; after one step an energy far
// below projected Newton's one (a crushed face grows by a third per Newton step), after three still below, and after
// thirty (both past a plateau where both crawl) not above projected Newton's thirty by more than a percent.
TEST(flatten_symmetric_dirichlet, ProxyStepsLowerACrushedStartFasterThanNewton) {
  const testing::TestDisk d = testing::capped_tube(6);
  const Eigen::MatrixXd V = area_pi(d);
  const JacobianOperator op = jacobian_operator(V, d.F);
  const FlatteningStart s = flattening_start(*d.mesh, V, d.boundary, unit_circle(d.boundary.size()),
                                             [&](const Eigen::MatrixXd& U) { return symmetric_dirichlet(op, d.F, U); });
  ASSERT_TRUE(s.squeezed);
  const auto run = [&](int steps, double proxy) {
    return minimize_symmetric_dirichlet(
        op, d.F, boundary_flags(d), s.U,
        {.max_iterations = steps, .relative_decrease = 0, .proxy_while_decrease = proxy});
  };
  // Here (start 2863): one step 598 against 2003, three 523 against 834, thirty 164.5 against 165.0.
  const SymmetricDirichletResult newton1 = run(1, 0), proxy1 = run(1, 0.5);
  EXPECT_EQ(newton1.proxy_steps, 0);
  EXPECT_EQ(proxy1.proxy_steps, 1);
  EXPECT_LT(proxy1.energy, 0.5 * newton1.energy) << newton1.energy_start;
  const SymmetricDirichletResult newton3 = run(3, 0), proxy3 = run(3, 0.5);
  EXPECT_LT(proxy3.energy, newton3.energy);
  const SymmetricDirichletResult newton30 = run(30, 0), proxy30 = run(30, 0.5);
  EXPECT_LT(proxy30.energy, 1.01 * newton30.energy);
  EXPECT_LT(proxy30.proxy_steps, proxy30.iterations) << "never switched to projected Newton";
  for (const SymmetricDirichletResult* r : {&proxy1, &proxy3, &proxy30}) {
    EXPECT_NEAR(r->energy, symmetric_dirichlet(op, d.F, r->U), 1e-9 * r->energy);
    EXPECT_GT(signed_double_areas(d.F, r->U).minCoeff(), 0);
    for (const VertexId v : d.boundary) ASSERT_EQ(r->U.row(v.idx), s.U.row(v.idx));
  }
}

/// Two copies of a tube sharing their boundary slots (the joint flattening's layout: the boundary first, then copy
/// 0's interior, then copy 1's, each in vertex order), started from the same drifted start.
struct TwoTubes {
  testing::TestDisk d = testing::capped_tube(6);
  JacobianOperator op0, op1;
  std::vector<int> slot0, slot1;
  Eigen::MatrixXd X0;
  int nb = 0, n_interior = 0;

  /// op1: copy 1's rest shape, copy 0's scaled by `scale1` (1: the same data, bitwise).
  explicit TwoTubes(double scale1) {
    const Eigen::MatrixXd B = unit_circle(d.boundary.size());
    const Eigen::MatrixXd V = area_pi(d);
    op0 = jacobian_operator(V, d.F);
    op1 = jacobian_operator(scale1 * V, d.F);
    const FlatteningStart s = flattening_start(
        *d.mesh, V, d.boundary, B, [&](const Eigen::MatrixXd& U) { return symmetric_dirichlet(op0, d.F, U); });
    const auto nv = static_cast<size_t>(d.mesh->n_vertices());
    nb = static_cast<int>(d.boundary.size());
    slot0.assign(nv, -1);
    for (int i = 0; i < nb; ++i) slot0[static_cast<size_t>(d.boundary[static_cast<size_t>(i)].idx)] = i;
    slot1 = slot0;
    n_interior = static_cast<int>(nv) - nb;
    for (int v = 0, k = 0; v < static_cast<int>(nv); ++v) {
      if (slot0[static_cast<size_t>(v)] >= 0) continue;
      slot0[static_cast<size_t>(v)] = nb + k;
      slot1[static_cast<size_t>(v)] = nb + n_interior + k;
      ++k;
    }
    X0.resize(nb + 2 * n_interior, 2);
    for (size_t v = 0; v < nv; ++v) {
      X0.row(slot0[v]) = s.U.row(static_cast<Eigen::Index>(v));
      X0.row(slot1[v]) = s.U.row(static_cast<Eigen::Index>(v));
    }
  }

  [[nodiscard]] SymmetricDirichletResult relax(bool own_solve, double proxy_while_decrease = 0) const {
    std::vector<char> fixed(static_cast<size_t>(X0.rows()), 0);
    fixed[0] = 1;
    const std::vector<SymmetricDirichletTerm> terms{
        {.jacobian = &op0, .F = &d.F, .slot = &slot0, .weight = 1, .own_solve = own_solve},
        {.jacobian = &op1, .F = &d.F, .slot = &slot1, .weight = 1, .own_solve = own_solve}};
    return minimize_symmetric_dirichlet(
        terms, fixed, X0,
        {.max_iterations = 40, .relative_decrease = 1e-6, .proxy_while_decrease = proxy_while_decrease});
  }
};

// Two copies of a tube lowered together: the joint factorisation eliminates the copies' unknowns in different orders,
// but with own_solve each copy's interior step is solved from its own faces, so the two interiors stay bitwise
// identical (the identity on moved copies rests on it; without own_solve they end 5e-3 apart), and the energy falls
// as for one copy.
class TwoIdenticalTerms : public ::testing::TestWithParam<double> {};

TEST_P(TwoIdenticalTerms, StayBitwiseIdentical) {
  const TwoTubes t(1.0);
  const SymmetricDirichletResult r = t.relax(true, GetParam());
  ASSERT_GT(r.iterations, 3);
  if (GetParam() > 0) {
    EXPECT_GT(r.proxy_steps, 0);
  } else {
    EXPECT_EQ(r.proxy_steps, 0);
  }
  EXPECT_LT(r.energy, 0.5 * r.energy_start);
  const Eigen::MatrixXd interior0 = r.U.middleRows(t.nb, t.n_interior), interior1 = r.U.bottomRows(t.n_interior);
  EXPECT_EQ((interior0 - interior1).cwiseAbs().maxCoeff(), 0.0);
  // The boundary moved (it is free but for slot 0), and the copies' faces are all positive.
  EXPECT_GT((r.U.topRows(t.nb) - t.X0.topRows(t.nb)).cwiseAbs().maxCoeff(), 1e-3);
  Eigen::MatrixXd U0(t.d.mesh->n_vertices(), 2);
  for (size_t v = 0; v < t.slot0.size(); ++v) U0.row(static_cast<Eigen::Index>(v)) = r.U.row(t.slot0[v]);
  EXPECT_GT(signed_double_areas(t.d.F, U0).minCoeff(), 0);
  EXPECT_NEAR(r.energy, 2 * symmetric_dirichlet(t.op0, t.d.F, U0), 1e-9 * r.energy);
}

// Projected Newton throughout, and the first steps along the reweighted proxy.
INSTANTIATE_TEST_SUITE_P(flatten_symmetric_dirichlet, TwoIdenticalTerms, ::testing::Values(0.0, 0.5));

// Terms whose data differ (copy 1's rest shape 1.5 times copy 0's) have no symmetry to keep: own_solve leaves them to
// the joint step, bitwise the same result as without it.
TEST(flatten_symmetric_dirichlet, OwnSolveIsSkippedForTermsThatDiffer) {
  const TwoTubes t(1.5);
  const SymmetricDirichletResult with = t.relax(true), without = t.relax(false);
  ASSERT_GT(with.iterations, 3);
  EXPECT_EQ(with.iterations, without.iterations);
  EXPECT_EQ((with.U - without.U).cwiseAbs().maxCoeff(), 0.0);
}

TEST(flatten_symmetric_dirichlet, RejectsAFlippedStart) {
  const testing::TestDisk d = planar_grid(4);
  Eigen::MatrixXd U = d.V.leftCols(2);
  U.col(0) *= -1;
  EXPECT_THROW(minimize_symmetric_dirichlet(jacobian_operator(d.V, d.F), d.F, boundary_flags(d), U), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
