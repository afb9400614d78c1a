#include "flatten/primal_dual_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "flatten/face_cones.h"
#include "flatten/newton_system.h"
#include "flatten/second_order_cone.h"
#include "flatten/subproblem_faces.h"

namespace liftmap {

namespace {

using namespace subproblem;  // NOLINT(google-build-using-namespace): the shared per-face data

constexpr int kMRows = kRows + kAux;  // rows of a face's scaled constraint matrix W^-1 A (cones, objective, unit rows)
using VecR = Eigen::Matrix<double, kRows, 1>;
using FaceRows = Eigen::Matrix<double, kRows, Eigen::Dynamic>;  // per face (column), its cones' rows
using Clock = std::chrono::steady_clock;

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Fraction of the way to the boundary of the cones that a step goes at most (CVXOPT's value).
constexpr double kStepFraction = 0.99;
/// Steps below this length, twice in a row, end the method (precision limit).
constexpr double kShortStep = 1e-3;
/// Iterations over which the method must make progress: halve the gap, or move the objective by a tenth of the
/// requested gap. Near the limit of double precision, short steps alternate with longer ones that go nowhere.
constexpr int kProgressWindow = 5;
/// Largest dual residual |A^T z - c|_inf of a solution (CVXOPT's default feasibility tolerance).
constexpr double kDualTolerance = 1e-7;

/// A vector of every cone: the faces' cones (column j: face j, cone k in rows 3k .. 3k + dim - 1) and, for p = 2,
/// the two objective cones. Slacks s, duals z and their scaled forms are such vectors.
struct ConeVectors {
  FaceRows faces;
  std::array<Eigen::VectorXd, 2> objective;
};

/// A vector over the primal variables: positions (x, the unknown coordinates), auxiliaries (y, kAux per face) and
/// the epigraph variables T_m (t). Directions, right-hand sides and residuals are such vectors.
using Unknowns = NewtonVector;

double max_abs(const Unknowns& u) {
  return std::max({u.x.lpNorm<Eigen::Infinity>(), u.y.lpNorm<Eigen::Infinity>(), std::abs(u.t[0]), std::abs(u.t[1])});
}

/// d, checked. \throw PipelineError if some entry is not finite.
Unknowns finite_step(Unknowns d) {
  if (!d.x.allFinite() || !d.y.allFinite() || !std::isfinite(d.t[0]) || !std::isfinite(d.t[1])) {
    throw PipelineError("convex subproblem: the primal-dual step is not finite");
  }
  return d;
}

/// The iterate: positions, auxiliaries (4 per face), epigraph variables; the dual variables of every cone.
struct Iterate {
  Eigen::VectorXd pos;
  Eigen::Matrix<double, kAux, Eigen::Dynamic> y;
  std::array<double, 2> T{};
  ConeVectors z;
};

VecL local_x(const FaceSetup& fs, const Iterate& it, int j) {
  VecL x;
  x.head<4>() = face_coordinates(fs, it.pos);
  x.segment<kAux>(kC) = it.y.col(j);
  x(kT) = fs.ghost() ? 0.0 : it.T[static_cast<size_t>(fs.mesh)];
  return x;
}

/// The objective cone of mesh m (p = 2): (T_m, sqrt(w_j) e_j over the mesh's faces).
struct ObjectiveCone {
  std::vector<int> faces;
  Eigen::VectorXd sqrt_w;
};

/// The Nesterov-Todd scalings of one face's cones in an iteration (eliminate_face).
struct FaceScaling {
  std::array<soc::Scaling<3>, kMaxCones> w;  // scalings of the face's cones (dimension 1: beta = sqrt(s / z) only)
  VecR lambda;                               // their scaled points
};

/// The scaled directions of one solve, per cone: ds~ = W^-1 A dx and dz~ = W dz.
struct ScaledDirection {
  ConeVectors ds, dz;
};

/// Where one iteration stands: its gap s^T z, mu = gap / nu, objective, and dual residual A^T z - c.
struct IterationState {
  double gap = 0, mu = 0, f0 = 0;
  Unknowns residual;
  double dual_residual = 0;  ///< |A^T z - c|_inf relative to the size of its terms
  double z_max = 0;          ///< the size of those terms
};

/// The primal-dual interior-point method of primal_dual_solver.h: one object per solve, whose solve() is the
/// method's loop (Vandenberghe 2010, §5; the steps as in CVXOPT's coneqp and ECOS): residuals and termination,
/// Nesterov-Todd scalings and the eliminated Newton system, the affine (predictor) direction, the combined
/// (Mehrotra corrector) direction, the step to the cones' boundary, and the step itself.
class PrimalDualSolver : SolverBase {
 public:
  PrimalDualSolver(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0, const SubproblemSettings& settings,
                   SparseCholesky& cholesky, AssemblyStructure* cache);
  SubproblemResult solve();

 private:
  // The start.
  void start_auxiliaries();
  void build_objective_cones(const std::array<double, 2>& e_max);
  void start_duals();

  // The cone program: slacks, A^T, the objective cones.
  bool slacks(const Iterate& x, ConeVectors& S) const;
  [[nodiscard]] Eigen::VectorXd objective_slack(const Iterate& x, size_t m) const;
  [[nodiscard]] Eigen::VectorXd objective_direction(const Unknowns& d, size_t m) const;
  [[nodiscard]] ConeVectors slack_direction(const Unknowns& d) const;
  [[nodiscard]] VecL local_direction(const FaceSetup& fs, const Unknowns& d, int j) const;
  [[nodiscard]] std::array<double, 2> dual_t(const Iterate& x) const;
  [[nodiscard]] bool unused_auxiliary(int j, int a) const;
  /// Per face j (column) and cone k (rows 3k ..), A_k x_j + b_k (with_offset) or A_k x_j, x_j = local(j) the face's
  /// local vector.
  template <class Local>
  [[nodiscard]] FaceRows cone_rows(Local&& local, bool with_offset) const {
    FaceRows out = FaceRows::Zero(kRows, nf_);
#pragma omp parallel for schedule(static) if (nf_ > kParallelFaces)
    for (int j = 0; j < nf_; ++j) {
      const FaceCones& fc = cones_[static_cast<size_t>(j)];
      const VecL xl = local(j);
      for (int k = 0; k < fc.n; ++k) {
        const Cone& cone = fc.cone[static_cast<size_t>(k)];
        Eigen::Vector3d v = cone_value(cone, xl);
        if (!with_offset) v -= cone.b;
        out.col(j).segment(3 * k, cone.dim) = v.head(cone.dim);
      }
    }
    return out;
  }
  /// Runs fn(j, k, dim) for every cone k (of dimension dim) of every face j; the faces on OpenMP threads for large
  /// problems.
  template <class Fn>
  void for_each_cone(Fn&& fn) const {
#pragma omp parallel for schedule(static) if (nf_ > kParallelFaces)
    for (int j = 0; j < nf_; ++j) {
      const FaceCones& fc = cones_[static_cast<size_t>(j)];
      for (int k = 0; k < fc.n; ++k) fn(j, k, fc.cone[static_cast<size_t>(k)].dim);
    }
  }
  void adjoint(const ConeVectors& Z, Unknowns& r, double* z_max = nullptr) const;
  void zero_unused(Eigen::VectorXd& y) const;

  // One iteration.
  IterationState residuals();
  [[nodiscard]] bool converged(const IterationState& is) const;
  bool stalled(const IterationState& is);
  double scale_and_eliminate();
  void scale_objective_cones(double& gap);
  bool eliminate_face(int j, double& gap);
  bool factor_system();
  Unknowns right_hand_side(const ConeVectors& xi, const IterationState& is, ConeVectors& U) const;
  Unknowns affine_direction(const Unknowns& r, double refined_enough);
  [[nodiscard]] ConeVectors corrector_target(const ScaledDirection& aff, double sigma, double mu) const;
  double step_to_boundary(const Unknowns& d, const ConeVectors& U, ScaledDirection& sc) const;
  double take_step(const Unknowns& d, const ScaledDirection& sc, double step);
  bool dual_step(const ScaledDirection& sc, double step, Iterate& next) const;
  SubproblemResult finish();

  // The Newton system H d = r.
  [[nodiscard]] CouplingColumns coupling_columns() const;
  [[nodiscard]] Unknowns solve_newton(const Unknowns& r) const;
  void apply_newton_matrix(const Unknowns& d, Unknowns& h) const;
  [[nodiscard]] double newton_residual(const Unknowns& d, const Unknowns& r, Unknowns& e) const;
  [[nodiscard]] Unknowns refine(Unknowns d, const Unknowns& r, double enough) const;

  Iterate it_;
  std::vector<FaceCones> cones_;
  std::array<ObjectiveCone, 2> obj_;
  ConeVectors S_;  // slacks at it_
  double nu_ = 0;  // degree of the cone program

  // The scalings and the eliminated Newton system of the current iteration.
  NewtonSystem<GramFaceBlock> newton_;
  std::vector<FaceScaling> scal_;
  std::array<soc::Scaling<Eigen::Dynamic>, 2> w_obj_;
  std::array<Eigen::VectorXd, 2> lambda_obj_;
  // Rank-one vectors u_m and coupling factors kappa_m of the objective cones (p = 2): their Hessian part is
  // diag(w_j / beta^2) on the e_j + u_m u_m^T, coupled to T_m by kappa_m u_m, with h_TT on T_m.
  std::array<Eigen::VectorXd, 2> u_obj_;
  std::array<double, 2> kappa_{0, 0}, h_tt_{0, 0};
  // The global coupling through the T_m, set up with the predictor (P^-1 applied to the coupling columns together
  // with its right-hand side) and used by every solve of the iteration.
  std::optional<CoupledSolve> coupled_;

  // Progress and the best certified iterate (what a stop at the precision limit returns).
  int short_steps_ = 0;
  double best_gap_ = kInf;
  Eigen::VectorXd best_pos_;
  std::vector<std::pair<double, double>> history_;  // (gap, objective) at the start of every iteration
};

PrimalDualSolver::PrimalDualSolver(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                   const SubproblemSettings& settings, SparseCholesky& cholesky,
                                   AssemblyStructure* cache)
    : SolverBase(problem, X0, settings, cholesky, cache), newton_(s_, *assembly_, cholesky_) {
  it_.pos = start_positions(X0);
  start_auxiliaries();
  // The cones of every face (their rows depend only on the rotation and the ghost bound).
  cones_.resize(static_cast<size_t>(nf_));
  for (int j = 0; j < nf_; ++j) face_cones(s_.faces[static_cast<size_t>(j)], st_, cones_[static_cast<size_t>(j)]);
  if (!slacks(it_, S_)) throw PipelineError("convex subproblem: the primal-dual start is not strictly feasible");
  nu_ = st_.p_inf ? 0.0 : 2.0;
  for (const FaceCones& fc : cones_) nu_ += fc.n;
  start_duals();
  scal_.resize(static_cast<size_t>(nf_));
  best_pos_ = it_.pos;
}

// Strictly feasible start: every cone's slack well inside (each auxiliary 1.5 times its lower bound).
void PrimalDualSolver::start_auxiliaries() {
  it_.y.setZero(kAux, nf_);
  std::array<double, 2> e_max{0, 0};
  const std::vector<FaceStart> start = strictly_feasible_start(s_, it_.pos);
  for (int j = 0; j < nf_; ++j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    const auto [n, cn, l] = start[static_cast<size_t>(j)];
    const double c = cn + 0.5 * (l - cn), m = l - c;
    it_.y(0, j) = c;
    if (fs.ghost()) continue;
    double e = 0;
    if (st_.h_max) {
      e = std::max(c + 1.5 * n, 1.5 / m);
    } else {
      it_.y(1, j) = c + 1.5 * n;
      it_.y(2, j) = 1.5 / m;
      e = 1.5 * std::hypot(it_.y(1, j), it_.y(2, j));
    }
    it_.y(3, j) = st_.p_inf ? 0.0 : e;
    e_max[static_cast<size_t>(fs.mesh)] = std::max(e_max[static_cast<size_t>(fs.mesh)], e);
  }
  build_objective_cones(e_max);
}

// The faces of each objective cone and the start's epigraph variables T_m, 1.5 times their lower bounds.
void PrimalDualSolver::build_objective_cones(const std::array<double, 2>& e_max) {
  for (int j = 0; j < nf_; ++j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    if (!fs.ghost()) obj_[static_cast<size_t>(fs.mesh)].faces.push_back(j);
  }
  for (size_t m = 0; m < 2; ++m) {
    ObjectiveCone& oc = obj_[m];
    oc.sqrt_w.resize(static_cast<Eigen::Index>(oc.faces.size()));
    for (size_t i = 0; i < oc.faces.size(); ++i) {
      oc.sqrt_w(static_cast<Eigen::Index>(i)) = std::sqrt(s_.faces[static_cast<size_t>(oc.faces[i])].w);
    }
    if (st_.p_inf) {
      it_.T[m] = 1.5 * e_max[m];
    } else {
      double sum = 0;
      for (size_t i = 0; i < oc.faces.size(); ++i) {
        const double e = it_.y(3, oc.faces[i]);
        sum += s_.faces[static_cast<size_t>(oc.faces[i])].w * e * e;
      }
      it_.T[m] = 1.5 * std::sqrt(sum);
    }
  }
}

// Dual start: z = mu0 s^-1 on every cone (s o z = mu0 e: perfectly centred), with mu0 the least-squares fit of the
// dual equation A^T z = c in the directions of the objective (the T_m).
void PrimalDualSolver::start_duals() {
  it_.z.faces.setZero(kRows, nf_);
  for (int j = 0; j < nf_; ++j) {
    const FaceCones& fc = cones_[static_cast<size_t>(j)];
    for (int k = 0; k < fc.n; ++k) {
      const int d = fc.cone[static_cast<size_t>(k)].dim;
      it_.z.faces.col(j).segment(3 * k, d) = soc::inverse(S_.faces.col(j).segment(3 * k, d));
    }
  }
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) it_.z.objective[m] = soc::inverse(S_.objective[m]);
  }
  const auto g = dual_t(it_);
  const double mu0 = (g[0] + g[1]) / (g[0] * g[0] + g[1] * g[1]);
  it_.z.faces *= mu0;
  for (auto& zo : it_.z.objective) zo *= mu0;
}

Eigen::VectorXd PrimalDualSolver::objective_slack(const Iterate& x, size_t m) const {
  const ObjectiveCone& oc = obj_[m];
  Eigen::VectorXd so(oc.faces.size() + 1);
  so(0) = x.T[m];
  for (size_t i = 0; i < oc.faces.size(); ++i) {
    so(static_cast<Eigen::Index>(i) + 1) = oc.sqrt_w(static_cast<Eigen::Index>(i)) * x.y(3, oc.faces[i]);
  }
  return so;
}

// The slacks of every cone at x; false if some cone is not strictly satisfied.
bool PrimalDualSolver::slacks(const Iterate& x, ConeVectors& S) const {
  S.faces = cone_rows([&](int j) { return local_x(s_.faces[static_cast<size_t>(j)], x, j); }, true);
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf_ > kParallelFaces)
  for (int j = 0; j < nf_; ++j) {
    const FaceCones& fc = cones_[static_cast<size_t>(j)];
    for (int k = 0; k < fc.n; ++k) {
      const bool inside = fc.cone[static_cast<size_t>(k)].dim == 1 ? S.faces(3 * k, j) > 0
                                                                   : soc::interior(S.faces.col(j).segment<3>(3 * k));
      if (!inside) ok = 0;
    }
  }
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      S.objective[m] = objective_slack(x, m);
      if (!soc::interior(S.objective[m])) ok = 0;
    }
  }
  return ok == 1;
}

// A^T z in the T_m (the dual equation there reads (A^T z)_T = 1).
std::array<double, 2> PrimalDualSolver::dual_t(const Iterate& x) const {
  std::array<double, 2> g{0, 0};
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) g[m] = x.z.objective[m](0);
    return g;
  }
  for (int j = 0; j < nf_; ++j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    if (fs.ghost()) continue;
    const FaceCones& fc = cones_[static_cast<size_t>(j)];
    for (int k = 0; k < fc.n; ++k) {
      const Cone& cone = fc.cone[static_cast<size_t>(k)];
      for (int i = 0; i < cone.n; ++i) {
        if (cone.var[static_cast<size_t>(i)] != kT) continue;
        g[static_cast<size_t>(fs.mesh)] += cone.A.col(i).head(cone.dim).dot(x.z.faces.col(j).segment(3 * k, cone.dim));
      }
    }
  }
  return g;
}

// Local direction of face j.
VecL PrimalDualSolver::local_direction(const FaceSetup& fs, const Unknowns& d, int j) const {
  Vec6 du;
  for (int r = 0; r < 6; ++r) {
    const int v = fs.var[static_cast<size_t>(r)];
    du(r) = v >= 0 ? d.x(v) : 0.0;
  }
  VecL x;
  x.head<4>() = fs.S * du;
  x.segment<kAux>(kC) = d.y.segment<kAux>(kAux * j);
  x(kT) = fs.ghost() ? 0.0 : d.t[static_cast<size_t>(fs.mesh)];
  return x;
}

// The objective cone m's part A_obj d of a direction d (p = 2): (dT_m, sqrt(w_j) de_j over the mesh's faces).
Eigen::VectorXd PrimalDualSolver::objective_direction(const Unknowns& d, size_t m) const {
  const ObjectiveCone& oc = obj_[m];
  Eigen::VectorXd dso(oc.faces.size() + 1);
  dso(0) = d.t[m];
  for (size_t i = 0; i < oc.faces.size(); ++i) {
    dso(static_cast<Eigen::Index>(i) + 1) = oc.sqrt_w(static_cast<Eigen::Index>(i)) * d.y(kAux * oc.faces[i] + 3);
  }
  return dso;
}

// A d per cone: the change of every cone's slack along the direction d (s = A x + b).
ConeVectors PrimalDualSolver::slack_direction(const Unknowns& d) const {
  ConeVectors ds;
  ds.faces = cone_rows([&](int j) { return local_direction(s_.faces[static_cast<size_t>(j)], d, j); }, false);
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) ds.objective[m] = objective_direction(d, m);
  }
  return ds;
}

// Auxiliary a (0..3: c, r, s, e) of face j appears in no cone: its row of the Newton system is a unit row.
bool PrimalDualSolver::unused_auxiliary(int j, int a) const {
  if (a == 0) return false;
  if (s_.faces[static_cast<size_t>(j)].ghost()) return true;
  return a == 3 ? st_.p_inf : st_.h_max;
}

void PrimalDualSolver::zero_unused(Eigen::VectorXd& y) const {
  for (int j = 0; j < nf_; ++j) {
    for (int a = 1; a < kAux; ++a) {
      if (unused_auxiliary(j, a)) y(kAux * j + a) = 0;
    }
  }
}

// A^T applied to per-cone vectors Z: r on the positions, the auxiliaries and the T_m. Unused auxiliaries (which
// appear in no cone) get 0. If z_max is given, it also gets the largest entry of |A|^T |Z| over the positions and
// auxiliaries (the size of the terms that A^T Z sums), from the same pass over the faces.
void PrimalDualSolver::adjoint(const ConeVectors& Z, Unknowns& r, double* z_max) const {
  const bool magnitude = z_max != nullptr;
  r.x.setZero(nv_);
  r.y.setZero(kAux * nf_);
  r.t = {0, 0};
  Eigen::VectorXd mx, my;
  if (magnitude) {
    mx.setZero(nv_);
    my.setZero(kAux * nf_);
  }
  std::vector<VecL> g(static_cast<size_t>(nf_)), gm(magnitude ? static_cast<size_t>(nf_) : 0);
#pragma omp parallel for schedule(static) if (nf_ > kParallelFaces)
  for (int j = 0; j < nf_; ++j) {
    const FaceCones& fc = cones_[static_cast<size_t>(j)];
    VecL gl = VecL::Zero(), gml = VecL::Zero();
    for (int k = 0; k < fc.n; ++k) {
      const Cone& cone = fc.cone[static_cast<size_t>(k)];
      const auto zk = Z.faces.col(j).segment(3 * k, cone.dim);
      const Eigen::Vector4d gk = cone.A.topRows(cone.dim).transpose() * zk;
      for (int a = 0; a < cone.n; ++a) gl(cone.var[static_cast<size_t>(a)]) += gk(a);
      if (magnitude) {
        const Eigen::Vector4d gmk = cone.A.topRows(cone.dim).cwiseAbs().transpose() * zk.cwiseAbs();
        for (int a = 0; a < cone.n; ++a) gml(cone.var[static_cast<size_t>(a)]) += gmk(a);
      }
    }
    g[static_cast<size_t>(j)] = gl;
    if (magnitude) gm[static_cast<size_t>(j)] = gml;
  }
  for (int j = 0; j < nf_; ++j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    const VecL& gl = g[static_cast<size_t>(j)];
    const Vec6 gu = fs.S.transpose() * gl.head<4>();
    for (int k = 0; k < 6; ++k) {
      const int v = fs.var[static_cast<size_t>(k)];
      if (v >= 0) r.x(v) += gu(k);
    }
    r.y.segment<kAux>(kAux * j) = gl.segment<kAux>(kC);
    if (!fs.ghost()) r.t[static_cast<size_t>(fs.mesh)] += gl(kT);
    if (magnitude) {
      const VecL& gml = gm[static_cast<size_t>(j)];
      const Vec6 gmu = fs.S.cwiseAbs().transpose() * gml.head<4>();
      for (int k = 0; k < 6; ++k) {
        const int v = fs.var[static_cast<size_t>(k)];
        if (v >= 0) mx(v) += gmu(k);
      }
      my.segment<kAux>(kAux * j) = gml.segment<kAux>(kC);
    }
  }
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      const ObjectiveCone& oc = obj_[m];
      r.t[m] += Z.objective[m](0);
      for (size_t i = 0; i < oc.faces.size(); ++i) {
        const double wz = oc.sqrt_w(static_cast<Eigen::Index>(i)) * Z.objective[m](static_cast<Eigen::Index>(i) + 1);
        r.y(kAux * oc.faces[i] + 3) += wz;
        if (magnitude) my(kAux * oc.faces[i] + 3) += std::abs(wz);
      }
    }
  }
  zero_unused(r.y);
  if (magnitude) {
    zero_unused(my);
    *z_max = std::max(mx.lpNorm<Eigen::Infinity>(), my.lpNorm<Eigen::Infinity>());
  }
}

// The iteration's gap, mu, objective and dual residual A^T z - c (0 at a dual feasible point), relative to the dual
// variables' size: the residual in a vertex's coordinates is a sum of terms of the size of its faces' z, up to ~1e6
// on slivers, and cancels to ~1e-10 of them at best.
IterationState PrimalDualSolver::residuals() {
  IterationState is;
  is.gap = scale_and_eliminate();
  is.mu = is.gap / nu_;
  is.f0 = it_.T[0] + it_.T[1];
  adjoint(it_.z, is.residual, &is.z_max);
  is.residual.t[0] -= 1;
  is.residual.t[1] -= 1;
  is.dual_residual = max_abs(is.residual) / std::max(1.0, is.z_max);
  if (is.dual_residual <= kDualTolerance && is.gap < best_gap_) {  // a certificate: f0 - optimum <= gap
    best_gap_ = is.gap;
    best_pos_ = it_.pos;
  }
  return is;
}

bool PrimalDualSolver::converged(const IterationState& is) const {
  return is.gap <= settings_.relative_gap * is.f0 && is.dual_residual <= kDualTolerance;
}

// No progress over the window: the method stops at this strictly feasible iterate, uncertified (precision limit).
bool PrimalDualSolver::stalled(const IterationState& is) {
  history_.emplace_back(is.gap, is.f0);
  if (history_.size() <= kProgressWindow) return false;
  const auto [gap_then, f0_then] = history_[history_.size() - 1 - kProgressWindow];
  return is.gap > 0.5 * gap_then && std::abs(is.f0 - f0_then) <= 0.1 * settings_.relative_gap * is.f0;
}

// Scalings of the objective cones (p = 2): their Hessian part is diag(w_j / beta^2) on the e_j (which joins the
// faces' eliminations) + u_m u_m^T, coupled to T_m by kappa_m u_m, with h_TT on T_m.
void PrimalDualSolver::scale_objective_cones(double& gap) {
  for (size_t m = 0; m < 2; ++m) {
    w_obj_[m] = soc::nesterov_todd(S_.objective[m], it_.z.objective[m]);
    lambda_obj_[m] = soc::apply_w(w_obj_[m], it_.z.objective[m]);
    gap += S_.objective[m].dot(it_.z.objective[m]);
    const soc::Scaling<Eigen::Dynamic>& w = w_obj_[m];
    const ObjectiveCone& oc = obj_[m];
    // W^-2 = (2 a a^T - J) / beta^2, a = J wbar, on (T, sqrt(w) e): e-block (I + 2 wb wb^T) / beta^2 (wb the tail
    // of wbar), T-e -2 wbar_0 wb / beta^2, T-T (2 wbar_0^2 - 1) / beta^2.
    u_obj_[m].resize(static_cast<Eigen::Index>(oc.faces.size()));
    for (size_t i = 0; i < oc.faces.size(); ++i) {
      const auto ii = static_cast<Eigen::Index>(i);
      u_obj_[m](ii) = std::sqrt(2.0) / w.beta * oc.sqrt_w(ii) * w.wbar(ii + 1);
    }
    kappa_[m] = -std::sqrt(2.0) * w.wbar(0) / w.beta;
    h_tt_[m] = (2 * w.wbar(0) * w.wbar(0) - 1) / (w.beta * w.beta);
  }
}

// Face j's cone scalings and lambda, and its Hessian block A^T W^-2 A with the auxiliaries eliminated; adds its
// cones' s^T z to gap. The block is the Gram matrix of M = W^-1 A (rows: the cones' scaled rows, plus the objective
// cone's diagonal on e, plus unit rows for unused auxiliaries), and the elimination uses the QR factorisation
// M_y = Q R of its auxiliaries' columns: the Schur complement is (Q_2^T M_q)^T (Q_2^T M_q), positive semidefinite in
// floating point too. Formed as H_qq - H_qy H_yy^-1 H_yq instead, it lost all precision on camel-cow's slivers
// (W^-2 has eigenvalues ~ wbar_0^2 and ~ 1 / wbar_0^2) and CHOLMOD needed diagonal shifts of 100%.
// Returns false if the auxiliaries' block is singular.
bool PrimalDualSolver::eliminate_face(int j, double& gap) {
  const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
  const FaceCones& fc = cones_[static_cast<size_t>(j)];
  FaceScaling& fsys = scal_[static_cast<size_t>(j)];
  Eigen::Matrix<double, kMRows, kLocal> M = Eigen::Matrix<double, kMRows, kLocal>::Zero();
  int row = 0;
  fsys.lambda.setZero();
  for (int k = 0; k < fc.n; ++k) {
    const Cone& cone = fc.cone[static_cast<size_t>(k)];
    const int dim = cone.dim;
    const auto sk = S_.faces.col(j).segment(3 * k, dim);
    const auto zk = it_.z.faces.col(j).segment(3 * k, dim);
    soc::Scaling<3>& w = fsys.w[static_cast<size_t>(k)];
    Eigen::Matrix<double, 3, 4> Mk = Eigen::Matrix<double, 3, 4>::Zero();
    if (dim == 1) {
      w.beta = std::sqrt(sk(0) / zk(0));
      fsys.lambda(3 * k) = std::sqrt(sk(0) * zk(0));
      Mk.row(0) = cone.A.row(0) / w.beta;
    } else {
      w = soc::nesterov_todd<3>(sk, zk);
      fsys.lambda.segment<3>(3 * k) = soc::apply_w<3>(w, zk);
      Eigen::Vector3d jv = w.v;  // W^-1 = (2 Jv (Jv)^T - J) / beta
      jv.tail<2>() *= -1;
      Mk = 2 * jv * (jv.transpose() * cone.A);
      Mk.row(0) -= cone.A.row(0);
      Mk.bottomRows<2>() += cone.A.bottomRows<2>();
      Mk /= w.beta;
    }
    gap += sk.dot(zk);
    for (int r = 0; r < dim; ++r, ++row) {
      for (int a = 0; a < cone.n; ++a) M(row, cone.var[static_cast<size_t>(a)]) += Mk(r, a);
    }
  }
  if (!st_.p_inf && !fs.ghost()) {
    M(row++, kE) = fs.w > 0 ? std::sqrt(fs.w) / w_obj_[static_cast<size_t>(fs.mesh)].beta : 0.0;
  }
  for (int a = kC; a < kT; ++a) {  // unused auxiliaries: a unit row (zero right-hand side, zero step)
    if (M.col(a).isZero()) M(row++, a) = 1;
  }
  return newton_.faces[static_cast<size_t>(j)].eliminate<kMRows>(M, fs.S);
}

// The scalings of every cone at (s, z) and the Newton system's per-face pieces; returns the gap s^T z.
double PrimalDualSolver::scale_and_eliminate() {
  double gap = 0;
  if (!st_.p_inf) scale_objective_cones(gap);
  // Per face: (its cones' s^T z, 1 if its auxiliaries' block was eliminated, else 0).
  const Eigen::Array2d faces = sum_over_faces<Eigen::Array2d>(nf_, [&](int j) {
    double face_gap = 0;
    const bool ok = eliminate_face(j, face_gap);
    return Eigen::Array2d(face_gap, ok ? 1 : 0);
  });
  gap += faces(0);
  if (faces(1) < nf_) throw PipelineError("convex subproblem: an auxiliary block is singular");
  if (st_.p_inf) {
    h_tt_ = {0, 0};
    for (int j = 0; j < nf_; ++j) {
      const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
      if (!fs.ghost()) h_tt_[static_cast<size_t>(fs.mesh)] += newton_.faces[static_cast<size_t>(j)].h_tt;
    }
  }
  return gap;
}

// Assembles the Schur system in the vertex coordinates, face by face in order, and factorises it (with a relative
// diagonal shift if rounding made it indefinite); false if no shift made it factorise. In face order, not on two
// threads as the barrier method's (for_each_face_partitioned): that changes the sums' rounding, which p = inf's
// iterates follow (docs/performance.md). p = inf: the T couplings were taken before the elimination; they are the
// plain blocks of H (the bordered solve eliminates through P^-1, which includes the auxiliaries).
bool PrimalDualSolver::factor_system() {
  newton_.assemble(SchurAssembly::kFaceOrder);
  return newton_.factorize();
}

// The coupling columns of the T_m: p = inf, H's blocks between T_m and the positions and auxiliaries; p = 2, the
// objective cones' u_m on the e_j.
CouplingColumns PrimalDualSolver::coupling_columns() const {
  if (st_.p_inf) return newton_.face_coupling();
  std::vector<double> u(static_cast<size_t>(nf_), 0.0);
  for (size_t m = 0; m < 2; ++m) {
    const ObjectiveCone& oc = obj_[m];
    for (size_t i = 0; i < oc.faces.size(); ++i) {
      u[static_cast<size_t>(oc.faces[i])] = u_obj_[m](static_cast<Eigen::Index>(i));
    }
  }
  return newton_.rank_two_columns(kE - kC, [&](int j) { return u[static_cast<size_t>(j)]; });
}

Unknowns PrimalDualSolver::solve_newton(const Unknowns& r) const {
  Eigen::MatrixXd Dx, Dy;
  newton_.apply_pinv<1>(r.x, r.y, Dx, Dy);
  return finite_step(coupled_->solve(Dx.col(0), Dy.col(0), r.t));
}

// H d = A^T W^-2 A d, formed cone by cone from the scalings (W^-1 applied twice), plus the unit rows of the unused
// auxiliaries: the Newton matrix that the factorised Schur system, the Woodbury correction and the bordered 2 x 2
// solve represent, without their cancellations.
void PrimalDualSolver::apply_newton_matrix(const Unknowns& d, Unknowns& h) const {
  const ConeVectors ds = slack_direction(d);
  ConeVectors V;
  V.faces = FaceRows::Zero(kRows, nf_);
  for_each_cone([&](int j, int k, int dim) {
    const soc::Scaling<3>& w = scal_[static_cast<size_t>(j)].w[static_cast<size_t>(k)];
    if (dim == 1) {
      V.faces(3 * k, j) = ds.faces(3 * k, j) / (w.beta * w.beta);
    } else {
      const Eigen::Vector3d dsk = ds.faces.col(j).segment<3>(3 * k);
      V.faces.col(j).segment<3>(3 * k) = soc::apply_w_inverse<3>(w, soc::apply_w_inverse<3>(w, dsk));
    }
  });
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      V.objective[m] = soc::apply_w_inverse(w_obj_[m], soc::apply_w_inverse(w_obj_[m], ds.objective[m]));
    }
  }
  adjoint(V, h);
  for (int j = 0; j < nf_; ++j) {
    for (int a = 1; a < kAux; ++a) {
      if (unused_auxiliary(j, a)) h.y(kAux * j + a) = d.y(kAux * j + a);
    }
  }
}

// e = r - H d; returns |e|_inf.
double PrimalDualSolver::newton_residual(const Unknowns& d, const Unknowns& r, Unknowns& e) const {
  apply_newton_matrix(d, e);
  e.x = r.x - e.x;
  e.y = r.y - e.y;
  e.t = {r.t[0] - e.t[0], r.t[1] - e.t[1]};
  return max_abs(e);
}

// Iterative refinement of a solve of H d = r: d += solve(r - H d) while the residual, computed from the cones
// (apply_newton_matrix), is above `enough` and shrinks at least by half, at most settings.primal_dual.max_refinements
// times. The factorised system loses precision to the elimination of nearly active cones (W^-2 with eigenvalues ~
// wbar_0^2 and ~ 1 / wbar_0^2), to the Woodbury correction and to CHOLMOD's diagonal shifts; without refinement the
// dual residual grew from 1e-9 to 1e-4 in the last iterations and the method stalled at relative gaps of 1e-5, at a
// level set by the BLAS kernel's rounding. The residual of the Newton equation becomes the dual residual after a full
// step, so `enough` is a hundredth of the dual tolerance: most solves, early in a subproblem, need no refinement and
// cost one product with H.
Unknowns PrimalDualSolver::refine(Unknowns d, const Unknowns& r, double enough) const {
  Unknowns e;
  double norm = newton_residual(d, r, e);
  for (int k = 0; k < settings_.primal_dual.max_refinements && norm > enough; ++k) {
    const Unknowns c = solve_newton(e);
    Unknowns next = d;
    next.x += c.x;
    next.y += c.y;
    next.t = {d.t[0] + c.t[0], d.t[1] + c.t[1]};
    Unknowns next_e;
    const double next_norm = newton_residual(next, r, next_e);
    if (!(next_norm < norm)) break;
    const bool slow = next_norm > 0.5 * norm;
    d = std::move(next);
    norm = next_norm;
    e = std::move(next_e);
    if (slow) break;
  }
  return d;
}

// Right-hand side A^T W^-1 u + (A^T z - c), u = lambda \ xi - lambda per cone (xi = 0: the predictor), with U = u.
// In exact arithmetic A^T W^-1 lambda = A^T z, and the right-hand side is A^T W^-1 (lambda \ xi) - c; written out,
// the step also corrects whatever dual residual rounding left.
Unknowns PrimalDualSolver::right_hand_side(const ConeVectors& xi, const IterationState& is, ConeVectors& U) const {
  U.faces.setZero(kRows, nf_);
  ConeVectors V;
  V.faces = FaceRows::Zero(kRows, nf_);
  for_each_cone([&](int j, int k, int dim) {
    const FaceScaling& fsys = scal_[static_cast<size_t>(j)];
    if (dim == 1) {
      const double lam = fsys.lambda(3 * k);
      const double u = xi.faces(3 * k, j) / lam - lam;
      U.faces(3 * k, j) = u;
      V.faces(3 * k, j) = u / fsys.w[static_cast<size_t>(k)].beta;
    } else {
      const Eigen::Vector3d lam = fsys.lambda.segment<3>(3 * k);
      const Eigen::Vector3d u = soc::jordan_divide<3>(lam, xi.faces.col(j).segment<3>(3 * k)) - lam;
      U.faces.col(j).segment<3>(3 * k) = u;
      V.faces.col(j).segment<3>(3 * k) = soc::apply_w_inverse(fsys.w[static_cast<size_t>(k)], u);
    }
  });
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      U.objective[m] = soc::jordan_divide(lambda_obj_[m], xi.objective[m]) - lambda_obj_[m];
      V.objective[m] = soc::apply_w_inverse(w_obj_[m], U.objective[m]);
    }
  }
  Unknowns r;
  adjoint(V, r);
  r.x += is.residual.x;
  r.y += is.residual.y;
  r.t[0] += is.residual.t[0];
  r.t[1] += is.residual.t[1];
  return r;
}

// The predictor: H d = r, solved together with P^-1 applied to the coupling columns (one solve with P for both).
Unknowns PrimalDualSolver::affine_direction(const Unknowns& r, double refined_enough) {
  CouplingColumns C = coupling_columns();
  Eigen::MatrixXd Rx(nv_, 3), Ry(kAux * nf_, 3), Dx, Dy;
  Rx << C.x, r.x;
  Ry << C.y, r.y;
  newton_.apply_pinv<3>(Rx, Ry, Dx, Dy);
  CouplingColumns pinv_c{Dx.leftCols<2>(), Dy.leftCols<2>()};
  coupled_ = st_.p_inf ? CoupledSolve::bordered(std::move(C), std::move(pinv_c), h_tt_)
                       : CoupledSolve::rank_two(std::move(C), std::move(pinv_c), h_tt_, kappa_);
  return refine(finite_step(coupled_->solve(Dx.col(2), Dy.col(2), r.t)), r, refined_enough);
}

// The corrector's target xi = sigma mu e - ds~_a o dz~_a (Mehrotra).
ConeVectors PrimalDualSolver::corrector_target(const ScaledDirection& aff, double sigma, double mu) const {
  ConeVectors xi;
  xi.faces = FaceRows::Zero(kRows, nf_);
  for_each_cone([&](int j, int k, int dim) {
    if (dim == 1) {
      xi.faces(3 * k, j) = sigma * mu - aff.ds.faces(3 * k, j) * aff.dz.faces(3 * k, j);
    } else {
      xi.faces.col(j).segment<3>(3 * k) =
          -soc::jordan_product<3>(aff.ds.faces.col(j).segment<3>(3 * k), aff.dz.faces.col(j).segment<3>(3 * k));
      xi.faces(3 * k, j) += sigma * mu;
    }
  });
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      xi.objective[m] = -soc::jordan_product(aff.ds.objective[m], aff.dz.objective[m]);
      xi.objective[m](0) += sigma * mu;
    }
  }
  return xi;
}

// The scaled directions of a solve d: ds~ = W^-1 A dx and dz~ = W dz = U - ds~ per cone (U = lambda \ xi - lambda,
// the right-hand side of W dz + W^-1 ds); returns the largest step that keeps s and z in their cones.
double PrimalDualSolver::step_to_boundary(const Unknowns& d, const ConeVectors& U, ScaledDirection& sc) const {
  const ConeVectors ds = slack_direction(d);
  sc.ds.faces.setZero(kRows, nf_);
  sc.dz.faces.setZero(kRows, nf_);
  double amax = kInf;
#pragma omp parallel for schedule(static) reduction(min : amax) if (nf_ > kParallelFaces)
  for (int j = 0; j < nf_; ++j) {
    const FaceScaling& fsys = scal_[static_cast<size_t>(j)];
    const FaceCones& fc = cones_[static_cast<size_t>(j)];
    for (int k = 0; k < fc.n; ++k) {
      if (fc.cone[static_cast<size_t>(k)].dim == 1) {
        const double lam = fsys.lambda(3 * k);
        const double dst = ds.faces(3 * k, j) / fsys.w[static_cast<size_t>(k)].beta;
        const double dzt = U.faces(3 * k, j) - dst;
        sc.ds.faces(3 * k, j) = dst;
        sc.dz.faces(3 * k, j) = dzt;
        amax = std::min({amax, soc::max_step_linear(lam, dst), soc::max_step_linear(lam, dzt)});
      } else {
        const Eigen::Vector3d lam = fsys.lambda.segment<3>(3 * k);
        const Eigen::Vector3d dsk = ds.faces.col(j).segment<3>(3 * k);
        const Eigen::Vector3d dst = soc::apply_w_inverse(fsys.w[static_cast<size_t>(k)], dsk);
        const Eigen::Vector3d dzt = U.faces.col(j).segment<3>(3 * k) - dst;
        sc.ds.faces.col(j).segment<3>(3 * k) = dst;
        sc.dz.faces.col(j).segment<3>(3 * k) = dzt;
        amax = std::min({amax, soc::max_step(lam, dst), soc::max_step(lam, dzt)});
      }
    }
  }
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      sc.ds.objective[m] = soc::apply_w_inverse(w_obj_[m], ds.objective[m]);
      sc.dz.objective[m] = U.objective[m] - sc.ds.objective[m];
      amax = std::min(
          {amax, soc::max_step(lambda_obj_[m], sc.ds.objective[m]), soc::max_step(lambda_obj_[m], sc.dz.objective[m])});
    }
  }
  return amax;
}

// Dual step of next: z + step dz, dz = W^-1 dz~ per cone; false if some z leaves its cone.
bool PrimalDualSolver::dual_step(const ScaledDirection& sc, double step, Iterate& next) const {
  next.z = it_.z;
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf_ > kParallelFaces)
  for (int j = 0; j < nf_; ++j) {
    const FaceCones& fc = cones_[static_cast<size_t>(j)];
    const FaceScaling& fsys = scal_[static_cast<size_t>(j)];
    for (int k = 0; k < fc.n; ++k) {
      const int dim = fc.cone[static_cast<size_t>(k)].dim;
      const soc::Scaling<3>& w = fsys.w[static_cast<size_t>(k)];
      if (dim == 1) {
        next.z.faces(3 * k, j) += step * sc.dz.faces(3 * k, j) / w.beta;
      } else {
        next.z.faces.col(j).segment<3>(3 * k) +=
            step * soc::apply_w_inverse<3>(w, sc.dz.faces.col(j).segment<3>(3 * k));
      }
      if (!soc::interior(next.z.faces.col(j).segment(3 * k, dim))) ok = 0;
    }
  }
  if (!st_.p_inf) {
    for (size_t m = 0; m < 2; ++m) {
      next.z.objective[m] = it_.z.objective[m] + step * soc::apply_w_inverse(w_obj_[m], sc.dz.objective[m]);
      if (!soc::interior(next.z.objective[m])) ok = 0;
    }
  }
  return ok == 1;
}

// Takes the step: the slacks are recomputed from the primal variables (exact primal feasibility), and the step is
// halved if rounding put a nearly active cone outside (at most 30 times, then no step). Returns the step taken; the
// iterate moves only if it is positive.
double PrimalDualSolver::take_step(const Unknowns& d, const ScaledDirection& sc, double step) {
  Iterate next;
  for (int halvings = 0;; ++halvings, step *= 0.5) {
    if (halvings == 30) return 0;
    next.pos = it_.pos;
    next.pos.tail(nv_) += step * d.x;
    next.y = it_.y;
    for (int j = 0; j < nf_; ++j) next.y.col(j) += step * d.y.segment<kAux>(kAux * j);
    next.T = {it_.T[0] + step * d.t[0], it_.T[1] + step * d.t[1]};
    ConeVectors S_next;
    if (dual_step(sc, step, next) && slacks(next, S_next)) {
      S_ = std::move(S_next);
      it_ = std::move(next);
      return step;
    }
  }
}

SubproblemResult PrimalDualSolver::solve() {
  for (int iter = 0; iter < settings_.max_iterations; ++iter) {
    const auto step_start = Clock::now();
    SubproblemStep trace;
    const IterationState is = residuals();
    trace.centring = iter;
    trace.t = 1 / is.mu;
    trace.objective = is.f0;
    if (converged(is)) {
      result_.status = SubproblemStatus::kConverged;
      break;
    }
    if (stalled(is)) {
      result_.status = SubproblemStatus::kStalled;
      break;
    }
    const auto factor_start = Clock::now();
    trace.seconds_derivatives = std::chrono::duration<double>(factor_start - step_start).count();
    if (!factor_system()) {
      result_.status = SubproblemStatus::kNotFactorizable;
      break;
    }
    trace.seconds_factorization = seconds_since(factor_start);
    const double refined_enough = 1e-2 * kDualTolerance * std::max(1.0, is.z_max);
    // Predictor (affine scaling direction), its step to the boundary, and the centring parameter.
    ConeVectors xi;
    xi.faces = FaceRows::Zero(kRows, nf_);
    for (size_t m = 0; m < 2 && !st_.p_inf; ++m) xi.objective[m] = Eigen::VectorXd::Zero(lambda_obj_[m].size());
    ConeVectors U;
    const Unknowns d_aff = affine_direction(right_hand_side(xi, is, U), refined_enough);
    ScaledDirection sc_aff;
    const double a_aff = std::min(1.0, step_to_boundary(d_aff, U, sc_aff));
    const double sigma = std::pow(1 - a_aff, 3);
    // Combined direction (Mehrotra's corrector), its step, and the step taken.
    const Unknowns r = right_hand_side(corrector_target(sc_aff, sigma, is.mu), is, U);
    const Unknowns d = refine(solve_newton(r), r, refined_enough);
    ScaledDirection sc;
    const double full_step = std::min(1.0, kStepFraction * step_to_boundary(d, U, sc));
    const auto search_start = Clock::now();
    const double step = take_step(d, sc, full_step);
    trace.seconds_line_search = seconds_since(search_start);
    ++result_.iterations;
    trace.step = step;
    trace.lambda2 = is.dual_residual;
    trace.seconds = seconds_since(step_start);
    // Steps this short twice in a row: the directions have reached the limit of double precision.
    short_steps_ = step < kShortStep ? short_steps_ + 1 : 0;
    if (step == 0 || short_steps_ == 2) {
      if (settings_.on_step) settings_.on_step(trace);
      result_.status = SubproblemStatus::kStalled;
      break;
    }
    trace.objective = it_.T[0] + it_.T[1];
    if (settings_.on_step) settings_.on_step(trace);
  }
  return finish();
}

// Converged: the current iterate is the best certified one. Otherwise the best certified one, whose gap is the
// honest bound (+infinity if no iterate was dual feasible).
SubproblemResult PrimalDualSolver::finish() {
  result_.gap_bound = best_gap_;
  const Eigen::VectorXd& pos = std::isfinite(best_gap_) ? best_pos_ : it_.pos;
  return result_at(pos);
}

}  // namespace

SubproblemResult solve_convex_subproblem_primal_dual(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                                     const SubproblemSettings& settings, SparseCholesky& cholesky,
                                                     subproblem::AssemblyStructure* cache) {
  return solve_with<PrimalDualSolver>(problem, X0, settings, cholesky, cache);
}

}  // namespace liftmap
