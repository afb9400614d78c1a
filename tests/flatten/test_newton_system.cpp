#include "flatten/newton_system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/errors.h"
#include "disk_patches.h"
#include "flatten/jacobian.h"
#include "flatten/sparse_cholesky.h"
#include "flatten/subproblem.h"

namespace liftmap {
namespace {

using namespace subproblem;  // NOLINT(google-build-using-namespace)

// The mesh of a flattening with every vertex at the slot slot_of(v).
template <class SlotOf>
SubproblemMesh subproblem_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, SlotOf&& slot_of) {
  SubproblemMesh m;
  m.V = V;
  m.F = F;
  m.jacobian = jacobian_operator(V, F);
  m.theta = Eigen::VectorXd::Zero(F.rows());
  for (Eigen::Index v = 0; v < V.rows(); ++v) m.slot.push_back(slot_of(static_cast<int>(v)));
  return m;
}

// A small real instance of problem (10)'s structure: a 60-face camel patch and a deformed copy whose boundary
// vertices share their slots with the patch's (constraint 10b), and five of the patch's faces as ghost faces.
ConvexSubproblem patch_problem(double p) {
  const testing::TestDisk a = testing::mesh_patch("camel.off", 0, 60);
  const testing::TestDisk b = testing::deformed_copy(a);
  const int na = static_cast<int>(a.V.rows());
  std::vector<int> b_slot(static_cast<size_t>(b.V.rows()), -1);
  for (const VertexId v : b.boundary) b_slot[static_cast<size_t>(v.idx)] = v.idx;
  int next = na;
  for (int& s : b_slot) {
    if (s < 0) s = next++;
  }
  ConvexSubproblem problem;
  problem.meshes[0] = subproblem_mesh(a.V, a.F, [](int v) { return v; });
  problem.meshes[1] = subproblem_mesh(b.V, b.F, [&](int v) { return b_slot[static_cast<size_t>(v)]; });
  problem.ghosts = subproblem_mesh(a.V, a.F.topRows(5), [](int v) { return v; });
  problem.n_slots = next;
  problem.p = p;
  return problem;
}

// The local Hessian's rows per face: HessianFaceBlock takes H = M^T M (7 columns), GramFaceBlock M itself (9 columns).
constexpr int kHessianRows = 9;
constexpr int kGramRows = 16;

// Face j's selection E_j of the unknowns (x, y, t): rows (alpha, beta, gamma, delta) = S u, the face's A auxiliaries,
// and the T of its mesh (p = inf; none for ghost faces).
Eigen::MatrixXd selection(const Setup& s, int j, int aux, bool p_inf) {
  const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
  const int n = s.n_var + aux * s.n_faces + 2;
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(4 + aux + 1, n);
  for (int r = 0; r < 6; ++r) {
    const int v = fs.var[static_cast<size_t>(r)];
    if (v >= 0) E.block(0, v, 4, 1) = fs.S.col(r);
  }
  for (int a = 0; a < aux; ++a) E(4 + a, s.n_var + aux * j + a) = 1;
  if (p_inf && !fs.ghost()) E(4 + aux, s.n_var + aux * s.n_faces + fs.mesh) = 1;
  return E;
}

// Relative distance allowed between the Newton system's solve and the dense one.
constexpr double kAgreement = 1e-9;

struct Case {
  bool gram;  // GramFaceBlock (primal-dual) or HessianFaceBlock (barrier)
  bool p_inf;
  SchurAssembly order;
  const char* name;
};

class flatten_newton_system : public ::testing::TestWithParam<Case> {};

// Everything the test draws at random for one system: the faces' Gram factors, and for p = 2 the objective's
// rank-two columns and coupling.
struct RandomSystem {
  std::vector<Eigen::MatrixXd> M;  // per face, Rows by 4 + A + 1
  Eigen::VectorXd u;               // p = 2: per face, its entry of u_m on the auxiliary e
  std::array<double, 2> kappa{0, 0}, h{0, 0};
};

RandomSystem draw(const Setup& s, int rows, int aux, bool p_inf, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> scale(-1.5, 1.5);
  RandomSystem rs;
  for (int j = 0; j < s.n_faces; ++j) {
    // Rows of very different sizes per face, as the scaled cones of nearly active faces have.
    Eigen::MatrixXd M = Eigen::MatrixXd::NullaryExpr(rows, 4 + aux + 1, [&] { return normal(rng); });
    M *= std::pow(10.0, scale(rng));
    if (!p_inf || s.faces[static_cast<size_t>(j)].ghost()) M.col(4 + aux).setZero();
    rs.M.push_back(M);
  }
  rs.u = Eigen::VectorXd::NullaryExpr(s.n_faces, [&] { return normal(rng); });
  for (size_t m = 0; m < 2; ++m) {
    rs.kappa[m] = 2 * normal(rng);
    rs.h[m] = rs.kappa[m] * rs.kappa[m] + 1;  // diag(h) - K C^T A^-1 C K >= I: H positive definite
  }
  return rs;
}

// The dense H of the same system, assembled from the faces' local Hessians and the coupling (without it, if not
// `coupled`: P, with an identity on (T_0, T_1)).
Eigen::MatrixXd dense_hessian(const Setup& s, const RandomSystem& rs, int aux, bool p_inf, bool coupled = true) {
  const int n = s.n_var + aux * s.n_faces + 2;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < s.n_faces; ++j) {
    const Eigen::MatrixXd E = selection(s, j, aux, p_inf && coupled);
    const Eigen::MatrixXd& M = rs.M[static_cast<size_t>(j)];
    H += E.transpose() * (M.transpose() * M) * E;
  }
  if (!coupled) H.bottomRightCorner<2, 2>().setIdentity();
  if (p_inf || !coupled) return H;
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(n, 2);
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (!fs.ghost()) U(s.n_var + aux * j + aux - 1, fs.mesh) = rs.u(j);
  }
  H += U * U.transpose();
  for (int m = 0; m < 2; ++m) {
    const int tm = s.n_var + aux * s.n_faces + m;
    H.col(tm) += rs.kappa[static_cast<size_t>(m)] * U.col(m);
    H.row(tm) += rs.kappa[static_cast<size_t>(m)] * U.col(m).transpose();
    H(tm, tm) = rs.h[static_cast<size_t>(m)];
  }
  return H;
}

// The Newton system's solve of H d = r, r = (rx, ry, rt).
template <class Face>
Eigen::VectorXd newton_solve(const Setup& s, const RandomSystem& rs, const Case& c, const Eigen::VectorXd& r) {
  constexpr int kA = Face::kAux;
  SparseCholesky cholesky;
  AssemblyStructure cache;
  NewtonSystem<Face> sys(s, assembly_structure(s, cholesky, cache), cholesky);
  std::array<double, 2> h_tt{0, 0};
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    Face& f = sys.faces[static_cast<size_t>(j)];
    const Eigen::MatrixXd& M = rs.M[static_cast<size_t>(j)];
    if constexpr (std::is_same_v<Face, GramFaceBlock>) {
      EXPECT_TRUE(f.template eliminate<kGramRows>(M, fs.S));
    } else {
      f.eliminate(M.transpose() * M, fs.S, false);
    }
    if (!fs.ghost()) h_tt[static_cast<size_t>(fs.mesh)] += f.h_tt;
  }
  sys.assemble(c.order);
  EXPECT_TRUE(sys.factorize());
  CouplingColumns C = c.p_inf ? sys.face_coupling() : sys.rank_two_columns(kA - 1, [&](int j) { return rs.u(j); });
  const int n_y = kA * s.n_faces;
  Eigen::MatrixXd Rx(s.n_var, 3), Ry(n_y, 3), Dx, Dy;
  Rx << C.x, r.head(s.n_var);
  Ry << C.y, r.segment(s.n_var, n_y);
  sys.template apply_pinv<3>(Rx, Ry, Dx, Dy);
  CouplingColumns pinv_c{Dx.leftCols<2>(), Dy.leftCols<2>()};
  const CoupledSolve coupled = c.p_inf ? CoupledSolve::bordered(std::move(C), std::move(pinv_c), h_tt)
                                       : CoupledSolve::rank_two(std::move(C), std::move(pinv_c), rs.h, rs.kappa);
  const NewtonVector d = coupled.solve(Dx.col(2), Dy.col(2), {r(s.n_var + n_y), r(s.n_var + n_y + 1)});
  Eigen::VectorXd out(r.size());
  out << d.x, d.y, d.t[0], d.t[1];
  return out;
}

// The eliminated, factorised and coupled solve against a dense LDL^T solve of the same H, on the faces of a real
// patch pair with random local Hessians whose scales span three orders of magnitude.
TEST_P(flatten_newton_system, SolvesAgreeWithADenseSolve) {
  const Case c = GetParam();
  const ConvexSubproblem problem = patch_problem(c.p_inf ? std::numeric_limits<double>::infinity() : 2.0);
  const subproblem::Setup s = make_setup(problem);
  ASSERT_GT(s.n_faces, 100);
  const int aux = c.gram ? GramFaceBlock::kAux : HessianFaceBlock::kAux;
  std::mt19937 rng(7);
  const RandomSystem rs = draw(s, c.gram ? kGramRows : kHessianRows, aux, c.p_inf, rng);
  const Eigen::MatrixXd H = dense_hessian(s, rs, aux, c.p_inf);
  std::normal_distribution<double> normal;
  const Eigen::VectorXd r = Eigen::VectorXd::NullaryExpr(H.rows(), [&] { return normal(rng); });
  const Eigen::VectorXd reference = H.ldlt().solve(r);
  const Eigen::VectorXd d =
      c.gram ? newton_solve<GramFaceBlock>(s, rs, c, r) : newton_solve<HessianFaceBlock>(s, rs, c, r);
  ASSERT_TRUE(d.allFinite());
  // The residual of the Newton equation at the level of rounding, and the solution close to the dense one.
  EXPECT_LT((H * d - r).norm(), 1e-10 * H.norm() * d.norm());
  EXPECT_LT((d - reference).norm(), kAgreement * reference.norm());
  // The coupling matters: a solve that left it out would miss the agreement above by a factor of 1000 at least.
  const Eigen::VectorXd uncoupled = dense_hessian(s, rs, aux, c.p_inf, false).ldlt().solve(r);
  EXPECT_GT((uncoupled - reference).norm(), 1e3 * kAgreement * reference.norm());
  std::printf("%s: |d - dense| / |dense| = %.2g, without the coupling %.2g\n", c.name,
              (d - reference).norm() / reference.norm(), (uncoupled - reference).norm() / reference.norm());
}

INSTANTIATE_TEST_SUITE_P(blocks, flatten_newton_system,
                         ::testing::Values(Case{false, false, SchurAssembly::kPartitioned, "barrier_p2"},
                                           Case{false, true, SchurAssembly::kPartitioned, "barrier_pinf"},
                                           Case{true, false, SchurAssembly::kFaceOrder, "primal_dual_p2"},
                                           Case{true, true, SchurAssembly::kFaceOrder, "primal_dual_pinf"},
                                           Case{true, true, SchurAssembly::kPartitioned,
                                                "primal_dual_pinf_partitioned"}),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

// (alpha, beta, gamma, delta) of the planar map taking the rest triangle Q's edges to the moved triangle P's.
Eigen::Vector4d planar_similarity_parts(const Eigen::Matrix2d& P, const Eigen::Matrix2d& Q) {
  const Eigen::Matrix2d J = P * Q.inverse();
  return {0.5 * (J(0, 0) + J(1, 1)), 0.5 * (J(1, 0) - J(0, 1)), 0.5 * (J(0, 0) - J(1, 1)), 0.5 * (J(0, 1) + J(1, 0))};
}

// The start's bounds on a planar grid, with the rotations R_j of its rest positions, against the Jacobians computed
// directly in the plane (lo = |(gamma, delta)|, n = |(alpha, beta)| and l = alpha, which do not depend on the
// faces' frames), at rest and after an interior vertex moved so far that faces fold; the error names the first face
// whose bounds cross.
TEST(flatten_newton_system, StartBoundsAgreeWithPlanarJacobians) {
  const testing::TestDisk grid = testing::jittered_planar_grid(6, 5, 0.2, 3);
  const Eigen::MatrixXd rest = grid.V.leftCols<2>();
  ConvexSubproblem problem;
  problem.meshes[0] = subproblem_mesh(grid.V, grid.F, [](int v) { return v; });
  const Eigen::MatrixXd parts = similarity_parts(problem.meshes[0].jacobian, grid.F, rest);
  for (Eigen::Index f = 0; f < grid.F.rows(); ++f) problem.meshes[0].theta(f) = std::atan2(parts(f, 1), parts(f, 0));
  problem.meshes[1] = problem.meshes[0];
  problem.ghosts = subproblem_mesh(grid.V, grid.F.topRows(0), [](int v) { return v; });
  problem.n_slots = static_cast<int>(grid.V.rows());
  const subproblem::Setup s = make_setup(problem);
  auto expected = [&](const Eigen::MatrixXd& moved, int j) {
    const int f = j % static_cast<int>(grid.F.rows());
    Eigen::Matrix2d P, Q;
    for (int k = 0; k < 2; ++k) {
      P.col(k) = (moved.row(grid.F(f, k + 1)) - moved.row(grid.F(f, 0))).transpose();
      Q.col(k) = (rest.row(grid.F(f, k + 1)) - rest.row(grid.F(f, 0))).transpose();
    }
    const Eigen::Vector4d a = planar_similarity_parts(P, Q);
    return FaceStart{std::hypot(a(0), a(1)), std::hypot(a(2), a(3)), a(0)};
  };
  auto positions = [&](const Eigen::MatrixXd& U) {
    Eigen::VectorXd pos(s.n_pos);
    for (int v = 0; v < problem.n_slots; ++v) pos.segment<2>(2 * v) = U.row(v).transpose();
    return pos;
  };
  const std::vector<FaceStart> at_rest = strictly_feasible_start(s, positions(rest));
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceStart e = expected(rest, j), f = at_rest[static_cast<size_t>(j)];
    EXPECT_NEAR(f.lo, e.lo, 1e-12);
    EXPECT_NEAR(f.n, e.n, 1e-12);
    EXPECT_NEAR(f.l, e.l, 1e-12);
    EXPECT_NEAR(f.l, 1, 1e-12);  // the grid at rest: every Jacobian the identity after its rotation R_j
  }
  // An interior vertex moved past its neighbours: the first face whose bounds cross is named.
  Eigen::MatrixXd moved = rest;
  int vertex = -1;
  for (int v = 0; v < problem.n_slots && vertex < 0; ++v) {
    if (rest(v, 0) > 0.3 && rest(v, 1) > 0.3) vertex = v;
  }
  ASSERT_GE(vertex, 0);
  moved(vertex, 0) += 5;
  int first = -1;
  for (int j = 0; j < s.n_faces && first < 0; ++j) {
    const FaceStart e = expected(moved, j);
    if (!(e.l - e.lo > 0)) first = j;
  }
  ASSERT_GE(first, 0);
  try {
    strictly_feasible_start(s, positions(moved));
    ADD_FAILURE() << "a start with folded faces was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("on face " + std::to_string(first) + ")"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace liftmap
