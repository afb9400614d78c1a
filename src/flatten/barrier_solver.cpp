#include "flatten/barrier_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"
#include "flatten/epigraph_norm.h"
#include "flatten/face_auxiliaries.h"
#include "flatten/newton_dual_gap.h"
#include "flatten/newton_system.h"
#include "flatten/subproblem_faces.h"

namespace liftmap {

namespace {

using namespace subproblem;  // NOLINT(google-build-using-namespace): the shared per-face data

// Local variables of one face: q = (alpha, beta, gamma, delta, c, e, T).
//   c >= |(gamma, delta)|                        (second-order cone; Sigma <= |(alpha,beta)| + c,
//                                                  sigma_tilde >= alpha cos + beta sin - c)
//   e >= h(|(alpha,beta)| + c, 1/(l - c))         (epigraph of E_j, l = alpha cos + beta sin)
//   T >= e                                       (p = inf only: epigraph of the max)
// For p = 2 the objective sqrt(sum_j w_j e_j^2) of each mesh m has its own epigraph variable, kept in T_m as
// well: T_m >= |(sqrt(w_j) e_j)_j|, a second-order cone over all faces of the mesh with barrier
// -log(T_m^2 - S_m), S_m = sum_j w_j e_j^2. The objective is then linear, t (T_0 + T_1), and the cone's Hessian
// is a diagonal plus a POSITIVE rank-one term per mesh. (The direct form t sqrt(S_m) has a diagonal minus a
// rank-one Hessian, and its Woodbury correction I - U^T P^-1 U lost all precision and turned indefinite on
// whole-mesh disks: negative Newton decrements, read as convergence, far from the optimum.)
// T_m is not a free variable: it always sits at the minimiser of t T_m - log(T_m^2 - S_m) for the current
// S_m, T_m = (1 + sqrt(1 + t^2 S_m)) / t, where the cone's slack is exactly 2 T_m / t. Free, the line search
// squeezed it against its cone (slack 1e-8) and the Newton systems lost all precision.
// c, e and T are tight at the optimum, so minimising over them reproduces (10a) exactly.
constexpr int kA = 0;
constexpr int kC = 4;
constexpr int kE = 5;
constexpr int kT = 6;
using Vec7 = Eigen::Matrix<double, 7, 1>;
using Mat7 = Eigen::Matrix<double, 7, 7>;

constexpr double kInf = std::numeric_limits<double>::infinity();
/// BarrierSettings::centring_tolerance for p = inf, whose repaired steps need centrings closer to the central path:
/// at 2 (p = 2's), the p = inf instances of the differential test stopped short of their certified gap.
constexpr double kPInfCentringTolerance = 0.125;

/// The arguments g_k > 0 of the log-barrier terms -log(g_k) of one face; false if outside the domain.
struct BarrierArgs {
  std::array<double, 4> g{};
  int n = 0;
};

bool barrier_args(const Vec7& q, double cs, double sn, bool ghost, double bound, const Settings& s, BarrierArgs& out) {
  // For p = inf the epigraph variable of E_j is T itself (no per-face e, which would be squeezed between
  // T >= e and e >= E_j on the maximal faces and ruin the conditioning of the elimination).
  const double c = q(kC), e = s.p_inf ? q(kT) : q(kE);
  const double g1 = c * c - q(2) * q(2) - q(3) * q(3);
  const double n = std::sqrt(q(0) * q(0) + q(1) * q(1));
  const double m = q(0) * cs + q(1) * sn - c;
  if (!(c > 0) || !(g1 > 0) || !(m > 0)) return false;
  out.n = 0;
  out.g[out.n++] = g1;
  if (ghost) {  // constraint only: sigma_tilde >= l - c > 0 and Sigma <= n + c < bound
    const double g6 = bound - n - c;
    if (!(g6 > 0)) return false;
    out.g[out.n++] = m;
    out.g[out.n++] = g6;
    return true;
  }
  if (s.h_max) {
    const double g2 = e - c - n;
    const double g3 = e * m - 1;
    if (!(g2 > 0) || !(g3 > 0)) return false;
    out.g[out.n++] = g2;
    out.g[out.n++] = g3;
  } else {
    const double g4 = e - std::sqrt((n + c) * (n + c) + 1 / (m * m));
    if (!(g4 > 0)) return false;
    out.g[out.n++] = g4;
  }
  return true;
}

void add_log_barrier(double g, const Vec7& dg, const Mat7& d2g, Vec7& grad, Mat7& hess) {
  grad -= dg / g;
  hess += dg * dg.transpose() / (g * g) - d2g / g;
}

/// Adds -log(g1), g1 = c^2 - gamma^2 - delta^2 (the cone of c, every face), on the variables it depends on: the
/// terms of add_log_barrier, entry by entry in the same order (the same rounding).
void add_cone_barrier(const Vec7& q, Vec7& grad, Mat7& hess) {
  const double ga = q(2), de = q(3), c = q(kC);
  const double g1 = c * c - ga * ga - de * de;
  const Eigen::Vector3d dg(-2 * ga, -2 * de, 2 * c);
  const Eigen::Vector3d d2g(-2, -2, 2);  // the diagonal of its Hessian, which has no other entries
  constexpr std::array<int, 3> kVars{2, 3, kC};
  for (int a = 0; a < 3; ++a) {
    grad(kVars[a]) -= dg(a) / g1;
    for (int b = 0; b < 3; ++b) {
      hess(kVars[a], kVars[b]) += dg(a) * dg(b) / (g1 * g1) - (a == b ? d2g(a) : 0.0) / g1;
    }
  }
}

/// Adds -log(g4), g4 = e - R, R = |(r, s)|, r = n + c, s = 1/m (the epigraph of E_j with h of eq. 3), on the
/// variables it depends on: (alpha, beta, c, e), with e = q(ke). Terms on these 4 variables instead of 7 x 7 outer
/// products cut the per-face derivative loop of a Newton step on camel-cow from 14.1 to 10.5 ms (of ~66 ms per
/// step), with gradients and Hessians equal to 1e-12 relative on every face of an outer iteration.
void add_epigraph_norm_barrier(const Vec7& q, double cs, double sn, int ke, Vec7& grad, Mat7& hess) {
  const EpigraphNorm en = epigraph_norm(q(0), q(1), q(kC), cs, sn);
  const double g4 = q(ke) - en.R;
  Eigen::Vector4d dg = -en.d;
  dg(3) += 1;
  dg /= g4;
  const Eigen::Matrix4d h4 = dg * dg.transpose() + en.d2 / g4;
  const std::array<int, 4> vars{0, 1, kC, ke};
  for (int a = 0; a < 4; ++a) {
    grad(vars[a]) -= dg(a);
    for (int b = 0; b < 4; ++b) hess(vars[a], vars[b]) += h4(a, b);
  }
}

/// Gradient and Hessian of the face's barrier sum_k -log(g_k) in the local variables; q must be feasible.
void barrier_derivatives(const Vec7& q, double cs, double sn, bool ghost, double bound, const Settings& s, Vec7& grad,
                         Mat7& hess) {
  grad.setZero();
  hess.setZero();
  add_cone_barrier(q, grad, hess);
  const int ke = s.p_inf ? kT : kE;
  if (!ghost && !s.h_max) {
    add_epigraph_norm_barrier(q, cs, sn, ke, grad, hess);
    if (s.p_inf) hess(kE, kE) = 1;  // e is unused
    return;
  }
  const double al = q(0), be = q(1), c = q(kC), e = q(ke);
  const double n = std::sqrt(al * al + be * be);
  const double m = al * cs + be * sn - c;
  Vec7 dn = Vec7::Zero();
  dn(0) = al / n;
  dn(1) = be / n;
  Mat7 d2n = Mat7::Zero();
  const double n3 = n * n * n;
  d2n(0, 0) = be * be / n3;
  d2n(1, 1) = al * al / n3;
  d2n(0, 1) = d2n(1, 0) = -al * be / n3;
  Vec7 dm = Vec7::Zero();
  dm(0) = cs;
  dm(1) = sn;
  dm(kC) = -1;
  const Vec7 unit_c = Vec7::Unit(kC), unit_e = Vec7::Unit(ke);
  if (ghost) {
    add_log_barrier(m, dm, Mat7::Zero(), grad, hess);
    add_log_barrier(bound - n - c, -dn - unit_c, -d2n, grad, hess);
    hess(kE, kE) = 1;  // e is unused: a unit curvature keeps the (c, e) block invertible and de = 0
    return;
  }
  // h of eq. 2: g2 = e - c - n (Sigma <= e), g3 = e m - 1 (1/sigma_tilde <= e, a rotated cone).
  add_log_barrier(e - c - n, unit_e - unit_c - dn, -d2n, grad, hess);
  const Mat7 d2g3 = unit_e * dm.transpose() + dm * unit_e.transpose();
  add_log_barrier(e * m - 1, e * dm + m * unit_e, d2g3, grad, hess);
  if (s.p_inf) hess(kE, kE) = 1;  // e is unused
}

// Centrings in a row that may stall (precision limit, no gap bound) before the method gives up on higher t.
constexpr int kMaxConsecutiveStalls = 3;

/// The iterate: positions, per-face auxiliaries, and the epigraph variables of the max (p = inf).
struct State {
  Eigen::VectorXd pos;
  Eigen::VectorXd c, e;
  std::array<double, 2> T{};
};

Vec7 local_vars(const Setup& s, const State& z, int j) {
  const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
  Vec6 u;
  for (int k = 0; k < 6; ++k) u(k) = z.pos(fs.pos[static_cast<size_t>(k)]);
  Vec7 q;
  q.head<4>() = fs.S * u;
  q(kC) = z.c(j);
  q(kE) = z.e(j);
  q(kT) = fs.ghost() ? 0.0 : z.T[static_cast<size_t>(fs.mesh)];
  return q;
}

/// S_m = sum_j w_j e_j^2 over the faces of each mesh (p = 2: the cone T_m >= sqrt(S_m)).
std::array<double, 2> mesh_sums(const Setup& s, const State& z) {
  std::array<double, 2> S{0, 0};
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (!fs.ghost()) S[static_cast<size_t>(fs.mesh)] += fs.w * z.e(j) * z.e(j);
  }
  return S;
}

/// p = 2: the epigraph variable T_m that minimises t T_m - log(T_m^2 - S_m); its slack T_m^2 - S_m is 2 T_m / t.
double optimal_epigraph(double S, double t) { return (1 + std::sqrt(1 + t * t * S)) / t; }

bool feasible(const Setup& s, const State& z) {
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (s.n_faces > kParallelFaces)
  for (int j = 0; j < s.n_faces; ++j) {
    BarrierArgs args;
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (!barrier_args(local_vars(s, z, j), fs.cs, fs.sn, fs.ghost(), fs.bound, s.settings, args)) ok = 0;
  }
  if (ok == 1 && !s.settings.p_inf) {
    const auto S = mesh_sums(s, z);
    for (size_t m = 0; m < 2; ++m) {
      if (!(z.T[m] > std::sqrt(S[m]))) return false;
    }
  }
  return ok == 1;
}

/// Bounds of a face's auxiliaries at q: c must lie in (lo, hi), and then E_j = h(n + c, 1/(l - c)).
struct AuxBounds {
  double lo = 0, hi = 0, n = 0, l = 0;
  [[nodiscard]] bool open() const { return hi > lo; }
  [[nodiscard]] double energy(double c, bool h_max) const {
    const double s = 1.0 / (l - c);
    return h_max ? std::max(n + c, s) : std::sqrt((n + c) * (n + c) + s * s);
  }
};

AuxBounds aux_bounds(const Vec7& q, const FaceSetup& fs) {
  AuxBounds b;
  b.lo = std::sqrt(q(2) * q(2) + q(3) * q(3));
  b.n = std::sqrt(q(0) * q(0) + q(1) * q(1));
  b.l = q(0) * fs.cs + q(1) * fs.sn;
  b.hi = fs.ghost() ? std::min(b.l, fs.bound - b.n) : b.l;
  return b;
}

/// p = 2: moves a face's auxiliaries (c_j, e_j) to the minimiser of its FaceAuxiliaryProblem at its fixed positions
/// (solve_face_auxiliaries).
/// Because the merit is concave in S_m, this never raises the merit (it lowers an upper bound that touches it).
/// Auxiliaries that sit at their optimum for the positions cannot be squeezed against their cones; without this,
/// repeated fraction-to-the-boundary repairs put c_j within 1e-16 of |(gamma, delta)|, the gradients reached
/// 1e16 and the Newton directions stopped being descent directions.
/// \param coef t / T_m of the face's mesh (unused for ghosts)
/// \param q the face's local variables; q(kC) is the warm start of c if it lies inside its bounds
/// \return false if the positions themselves are infeasible (no c_j exists).
bool centre_auxiliaries(const FaceSetup& fs, const Settings& st, double coef, Vec7& q) {
  const AuxBounds b = aux_bounds(q, fs);
  if (!b.open()) return false;
  FaceAuxiliaryProblem p;
  p.lo = b.lo;
  p.n = b.n;
  p.l = b.l;
  p.bound = fs.bound;
  p.ghost = fs.ghost();
  p.h_max = st.h_max;
  p.quad = fs.ghost() ? 0.0 : coef * fs.w;
  FaceAuxiliaries aux;
  if (!solve_face_auxiliaries(p, q(kC), aux)) return false;
  q(kC) = aux.c;
  q(kE) = aux.e;
  return true;
}

/// p = 2: centre_auxiliaries on every face of z (coefficients t / T_ref[m]), then the epigraph variables at their
/// optimum for the new S_m. \return false if some face's positions are infeasible.
bool centre_all_auxiliaries(const Setup& s, double t, const std::array<double, 2>& T_ref, State& z) {
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (s.n_faces > kParallelFaces)
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    Vec7 q = local_vars(s, z, j);
    if (!centre_auxiliaries(fs, s.settings, t / T_ref[static_cast<size_t>(fs.ghost() ? 0 : fs.mesh)], q)) {
      ok = 0;
      continue;
    }
    z.c(j) = q(kC);
    z.e(j) = q(kE);
  }
  const auto S = mesh_sums(s, z);
  for (size_t m = 0; m < 2; ++m) z.T[m] = optimal_epigraph(S[m], t);
  return ok == 1;
}

/// p = inf: the state z + step (dx, dy, d_t), with the auxiliaries of every face whose linear step leaves their cones
/// put back inside. The auxiliaries only express (10a) in conic form; the positions alone decide whether a
/// point is feasible (every sigma_tilde_j > 0, ghost bounds). Without this repair, the linearly extrapolated
/// c_j, e_j leave their cones long before the positions do, and the line search crawls at steps of 1/128.
/// A repaired c_j moves half the way from its relative place between its bounds at z towards the bound it
/// crossed; a repaired epigraph variable keeps half its slack (fraction to the boundary).
/// \param repair false: the plain linear step, infeasible as soon as any variable leaves its cone
/// \return false if the point is infeasible.
bool step_state_inf(const Setup& s, const State& z, const Eigen::VectorXd& dx, const Eigen::VectorXd& dy,
                    const std::array<double, 2>& d_t, double step, bool repair, State& zn) {
  const int nf = s.n_faces;
  const bool h_max = s.settings.h_max;
  zn.pos = z.pos;
  zn.pos.tail(dx.size()) += step * dx;
  zn.c = z.c + step * dy(Eigen::seq(0, Eigen::last, 2));
  zn.e = z.e + step * dy(Eigen::seq(1, Eigen::last, 2));
  zn.T = {z.T[0] + step * d_t[0], z.T[1] + step * d_t[1]};
  // The largest E_j at zn and at z of each mesh, to keep T's slack over the maximum.
  std::vector<double> e_new(static_cast<size_t>(nf), 0.0), e_old(e_new.size(), 0.0);
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf > kParallelFaces)
  for (int j = 0; j < nf; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    const Vec7 q1 = local_vars(s, zn, j);
    const AuxBounds b1 = aux_bounds(q1, fs);
    if (!b1.open()) {
      ok = 0;
      continue;
    }
    const Vec7 q0 = local_vars(s, z, j);
    const AuxBounds b0 = aux_bounds(q0, fs);
    double c = q1(kC);
    if (!repair && !(c > b1.lo && c < b1.hi)) {
      ok = 0;
      continue;
    }
    if (!(c > b1.lo && c < b1.hi)) {
      // Half the way from its old relative place towards the bound it crossed (fraction to the boundary).
      const double r0 = (q0(kC) - b0.lo) / (b0.hi - b0.lo);
      const double r = c <= b1.lo ? 0.5 * r0 : 1 - 0.5 * (1 - r0);
      c = b1.lo + r * (b1.hi - b1.lo);
      zn.c(j) = c;
    }
    if (fs.ghost()) continue;
    e_new[static_cast<size_t>(j)] = b1.energy(c, h_max);
    e_old[static_cast<size_t>(j)] = b0.energy(q0(kC), h_max);
  }
  if (ok == 0) return false;
  std::array<double, 2> max_new{0, 0}, max_old{0, 0};
  for (int j = 0; j < nf; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (fs.ghost()) continue;
    const auto m = static_cast<size_t>(fs.mesh);
    max_new[m] = std::max(max_new[m], e_new[static_cast<size_t>(j)]);
    max_old[m] = std::max(max_old[m], e_old[static_cast<size_t>(j)]);
  }
  for (size_t m = 0; m < 2; ++m) {
    if (!repair && !(zn.T[m] > max_new[m])) return false;
    if (!(zn.T[m] > max_new[m])) zn.T[m] = max_new[m] + 0.5 * (z.T[m] - max_old[m]);
  }
  return feasible(s, zn);
}

/// p = 2: the positions z + step dx, with every face's auxiliaries re-centred there (centre_auxiliaries, warm
/// started from the linear step z + step dy where that is feasible) and the epigraph variables at their optimum.
/// The positions alone decide feasibility. \return false if the point is infeasible.
bool step_state_2(const Setup& s, const State& z, const Eigen::VectorXd& dx, const Eigen::VectorXd& dy, double step,
                  double t, State& zn) {
  const int nf = s.n_faces;
  zn.pos = z.pos;
  zn.pos.tail(dx.size()) += step * dx;
  zn.c = z.c + step * dy(Eigen::seq(0, Eigen::last, 2));
  zn.e = z.e + step * dy(Eigen::seq(1, Eigen::last, 2));
  int ok = 1;
  // Check every face's positions before re-centring anything: most rejected trial steps stop here, cheaply.
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf > kParallelFaces)
  for (int j = 0; j < nf; ++j) {
    if (!aux_bounds(local_vars(s, zn, j), s.faces[static_cast<size_t>(j)]).open()) ok = 0;
  }
  if (ok == 0) return false;
  return centre_all_auxiliaries(s, t, z.T, zn) && feasible(s, zn);
}

/// merit(z1) - merit(z0) for merit = t f0 + barrier, computed term by term (as log ratios and differences) so
/// that it stays accurate when t f0 is large; both states must be feasible.
double merit_difference(const Setup& s, const State& z0, const State& z1, double t) {
  double d = sum_over_faces<double>(s.n_faces, [&](int j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    BarrierArgs a0, a1;
    barrier_args(local_vars(s, z0, j), fs.cs, fs.sn, fs.ghost(), fs.bound, s.settings, a0);
    barrier_args(local_vars(s, z1, j), fs.cs, fs.sn, fs.ghost(), fs.bound, s.settings, a1);
    double dj = 0;
    for (int k = 0; k < a0.n; ++k) dj -= std::log(a1.g[static_cast<size_t>(k)] / a0.g[static_cast<size_t>(k)]);
    return dj;
  });
  d += t * ((z1.T[0] - z0.T[0]) + (z1.T[1] - z0.T[1]));
  if (!s.settings.p_inf) {  // -log of the objective cones' slacks 2 T_m / t
    for (size_t m = 0; m < 2; ++m) d -= std::log(z1.T[m] / z0.T[m]);
  }
  return d;
}

/// A face's gradient of t f0 + barrier: in its corner coordinates, its auxiliaries (c, e) and its mesh's T.
struct FaceGradient {
  Vec6 gx;
  Eigen::Vector2d gy;
  double g_t = 0;
};

// Bound of f0 minus the optimum at a point whose Newton decrement for t f0 + barrier is lambda (f0 linear): nu / t
// at the central point, plus sqrt(nu) ||x - x*(t)|| / t <= sqrt(nu) lambda / (1 - lambda) / t off it.
double gap_bound(double nu, double lambda, double t) {
  return lambda < 1 ? (nu + lambda * std::sqrt(nu) / (1 - lambda)) / t : kInf;
}

double total_nu(const Setup& s) {
  // Barrier parameters: 2 per second-order cone, 1 per convex-function constraint.
  const double per_face = 2.0 + (s.settings.h_max ? 1.0 + 2.0 : 1.0);
  double nu = s.settings.p_inf ? 0.0 : 2.0 * 2;  // p = 2: the two objective cones
  for (const FaceSetup& fs : s.faces) nu += fs.ghost() ? 4.0 : per_face;
  return nu;
}

}  // namespace

namespace {

using Clock = std::chrono::steady_clock;

/// Newton's direction for t f0 + barrier: positions x, auxiliaries y (2 per face), epigraph variables t.
using NewtonDirection = NewtonVector;

/// The state of one centring (Newton's method on t f0 + barrier at a fixed t).
struct Centring {
  /// Its nu / t can meet the gap (f0 only decreases during a centring): the only centring polished to
  /// newton_tolerance. The others end, after one more step, once lambda^2 / 2 is below `tolerance`, because the
  /// next barrier parameter starts with Newton decrements of ~1e7 anyway.
  bool last = false;
  double tolerance = 0;
  /// This step's Newton system gives every face's (gamma, delta) block isotropic curvature (p = 2,
  /// BarrierSettings::isotropic_anticonformal_curvature): set after a step that Armijo's condition shortened.
  bool isotropic = false;
  bool roughly_centred = false;
  bool stalled = false;    ///< no step along the Newton direction decreased the merit before the tolerance
  double end_lambda2 = 0;  ///< Newton decrement where the centring ended
  double dual_gap = kInf;  ///< the gap of the dual point of the last Newton direction, if it ended the centring
};

/// How a Newton step of a centring ended.
enum class StepEnd {
  kNextStep,      ///< the centring goes on
  kCentringEnds,  ///< centred (or stalled): the barrier parameter may grow
  kMethodStops,   ///< the step cap or the precision limit of the factorisation: the method stops
};

/// The barrier method of barrier_solver.h (Boyd and Vandenberghe, Convex Optimization, §11.3): one object per
/// solve, whose solve() is the method's loop: centre (Newton's method on t f0 + barrier), stop if the gap bound is
/// met, increase t. A Newton step: the per-face derivatives with the auxiliaries eliminated, the Schur system
/// assembled and factorised, the direction with the global coupling of (10a), the decrement, the line search.
class BarrierSolver : SolverBase {
 public:
  BarrierSolver(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0, const SubproblemSettings& settings,
                SparseCholesky& cholesky, AssemblyStructure* cache);
  SubproblemResult solve();

 private:
  // The start.
  void start_auxiliaries(const Eigen::MatrixXd& X0);
  void start_barrier_parameter();
  [[nodiscard]] double centring_balance(const std::array<double, 2>& S_start) const;

  // The outer loop.
  [[nodiscard]] Centring begin_centring() const;
  bool centre(Centring& c);
  bool end_centring(const Centring& c, bool stopped);
  void increase_barrier_parameter();

  // One Newton step.
  StepEnd newton_step(Centring& c);
  void epigraph_at_optimum();
  void eliminate_face(int j, bool isotropic);
  void assemble();
  [[nodiscard]] CouplingColumns coupling_columns() const;
  [[nodiscard]] NewtonDirection newton_direction();
  [[nodiscard]] double dual_gap(const NewtonDirection& d) const;
  StepEnd line_search_step(Centring& c, const NewtonDirection& d, double lambda2, SubproblemStep& trace,
                           Clock::time_point step_start, Clock::time_point& search_start);
  double line_search(const NewtonDirection& d, double lambda2, bool repair, State& out, double& merit,
                     bool& merit_limited) const;
  void report(SubproblemStep& trace, Clock::time_point step_start, Clock::time_point search_start, double step,
              bool repaired) const;
  [[nodiscard]] double f0() const { return z_.T[0] + z_.T[1]; }

  State z_;
  double nu_ = 0;
  double t_ = 0;

  // This step's Newton system (the faces' blocks with their auxiliaries eliminated), the faces' gradients, the
  // assembled gradient, and the epigraph variables' derivatives.
  NewtonSystem<HessianFaceBlock> newton_;
  std::array<double, 2> sums_{0, 0};  // S_m at z_
  std::array<double, 2> cone_{1, 1};  // p = 2: slacks T_m^2 - S_m of the objective cones
  std::vector<FaceGradient> grad_;
  Eigen::VectorXd gx_, gy_;
  std::array<double, 2> g_t_{0, 0}, h_tt_{0, 0};

  State centred_;  // the iterate at the end of the last centring that ended centred, and its gap bound
  double centred_gap_ = kInf;
  int consecutive_stalls_ = 0;  // centrings in a row that stalled without a gap bound
};

BarrierSolver::BarrierSolver(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                             const SubproblemSettings& settings, SparseCholesky& cholesky, AssemblyStructure* cache)
    : SolverBase(problem, X0, settings, cholesky, cache), newton_(s_, *assembly_, cholesky_) {
  start_auxiliaries(X0);
  nu_ = total_nu(s_);
  start_barrier_parameter();
  grad_.resize(static_cast<size_t>(nf_));
}

// Strictly feasible start for the auxiliaries: c between |(gamma,delta)| and alpha cos + beta sin.
void BarrierSolver::start_auxiliaries(const Eigen::MatrixXd& X0) {
  z_.pos = start_positions(X0);
  const std::vector<FaceStart> start = strictly_feasible_start(s_, z_.pos);
  z_.c.resize(nf_);
  z_.e.resize(nf_);
  z_.T = {0, 0};
  for (int j = 0; j < nf_; ++j) {
    const FaceStart& f = start[static_cast<size_t>(j)];
    z_.c(j) = f.lo + 0.1 * (f.l - f.lo);
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    if (fs.ghost()) {
      z_.e(j) = 0;
      continue;
    }
    const double m = f.l - z_.c(j);
    z_.e(j) = 1.5 * (st_.h_max ? std::max(f.n + z_.c(j), 1.0 / m) : std::hypot(f.n + z_.c(j), 1.0 / m));
    z_.T[static_cast<size_t>(fs.mesh)] = std::max(z_.T[static_cast<size_t>(fs.mesh)], z_.e(j));
  }
}

// The t that best centres the start, -<grad f0, grad barrier> / |grad f0|^2 in the directions where f0 varies (the
// e_j for p = 2, the T_m for p = inf; S_start: the meshes' sums S_m at the start); 0 if the barrier does not push
// against f0 there.
double BarrierSolver::centring_balance(const std::array<double, 2>& S_start) const {
  // Per face: (gf_gphi, gf_gf, barrier_t).
  const Eigen::Array3d sums = sum_over_faces<Eigen::Array3d>(nf_, [&](int j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    if (fs.ghost()) return Eigen::Array3d::Zero().eval();
    Vec7 g;
    Mat7 H;
    barrier_derivatives(local_vars(s_, z_, j), fs.cs, fs.sn, false, 0.0, st_, g, H);
    if (st_.p_inf) return Eigen::Array3d(0, 0, g(kT));
    const double df = fs.w * z_.e(j) / std::sqrt(S_start[static_cast<size_t>(fs.mesh)]);
    return Eigen::Array3d(df * g(kE), df * df, 0);
  });
  double gf_gphi = sums(0), gf_gf = sums(1);
  const double barrier_t = sums(2);
  if (st_.p_inf) {
    gf_gphi = barrier_t;
    gf_gf = 2;
  }
  return gf_gphi < 0 ? -gf_gphi / gf_gf : 0.0;
}

// Start on the central path as nearly as a single t allows (centring_balance), then, for p = 2, initial_barrier_factor
// times further and at least the t of initial_gap, with the epigraph variables and auxiliaries centred for it.
void BarrierSolver::start_barrier_parameter() {
  const auto S_start = mesh_sums(s_, z_);
  const double start_objective_2 = std::sqrt(S_start[0]) + std::sqrt(S_start[1]);  // (10a) at the start, p = 2
  t_ = nu_ / (st_.p_inf ? f0() : start_objective_2);
  const double balance = centring_balance(S_start);
  if (balance > 0) t_ = balance;
  if (st_.p_inf) return;
  t_ *= settings_.barrier.initial_barrier_factor;
  if (settings_.barrier.initial_gap > 0) t_ = std::max(t_, nu_ / (settings_.barrier.initial_gap * start_objective_2));
  // The epigraph variable where the barrier's derivative in T_m balances t: t = 2 T_m / (T_m^2 - S_m). Its
  // gradient in e_j is then 2 w_j e_j / (T_m^2 - S_m) ~ t w_j e_j / sqrt(S_m), that of t sqrt(S_m).
  for (size_t m = 0; m < 2; ++m) z_.T[m] = optimal_epigraph(S_start[m], t_);
  centre_all_auxiliaries(s_, t_, z_.T, z_);
}

SubproblemResult BarrierSolver::solve() {
  for (;;) {
    Centring c = begin_centring();
    const bool stopped = !centre(c);
    if (end_centring(c, stopped)) break;
    increase_barrier_parameter();
  }
  return result_at(z_.pos);
}

Centring BarrierSolver::begin_centring() const {
  Centring c;
  c.last = nu_ / t_ <= settings_.relative_gap * f0();
  c.tolerance = st_.p_inf ? kPInfCentringTolerance : settings_.barrier.centring_tolerance;
  return c;
}

// Newton's method on t f0 + barrier; false if the method must stop (step cap, precision limit).
bool BarrierSolver::centre(Centring& c) {
  for (;;) {
    if (result_.iterations >= settings_.max_iterations) {
      result_.status = SubproblemStatus::kIterationLimit;
      return false;
    }
    switch (newton_step(c)) {
      case StepEnd::kNextStep:
        continue;
      case StepEnd::kCentringEnds:
        return true;
      case StepEnd::kMethodStops:
        return false;
    }
  }
}

// The centring's gap bound; true if the method ends: stopped, converged, or stalled for good.
bool BarrierSolver::end_centring(const Centring& c, bool stopped) {
  ++result_.centrings;
  if (c.stalled) ++result_.stalled_centrings;
  // Gap bound at a point whose Newton decrement is lambda < 1 (exactly nu / t on the central path), or the gap of the
  // dual point that ended the centring.
  const double gap = std::min(gap_bound(nu_, std::sqrt(c.end_lambda2), t_), c.dual_gap);
  result_.gap_bound = gap;
  if (stopped) return true;
  if (gap <= settings_.relative_gap * f0()) {
    // The bound holds only near a central point: a last centring that stalled certifies nothing.
    result_.status = c.stalled ? SubproblemStatus::kStalled : SubproblemStatus::kConverged;
    return true;
  }
  consecutive_stalls_ = c.stalled && !std::isfinite(gap) ? consecutive_stalls_ + 1 : 0;
  if (!c.stalled && std::isfinite(gap)) {
    centred_ = z_;
    centred_gap_ = gap;
  }
  if (consecutive_stalls_ >= kMaxConsecutiveStalls) {
    // The Newton systems are beyond the limit of double precision and a higher t does not bring them back (a
    // 500-face instance went on stalling to t = 1e139, where the Newton step overflowed). A single stall can
    // pass: the next centring may end centred again. Return the last centred point with its bound; if no
    // centring ever ended centred, the iterate as it is (strictly feasible, no bound): going on only multiplied t
    // (homer to bull with 12 random landmarks, from a start of max distortion 1e11: 400 Newton steps to t = 1e116,
    // 39 s, the objective unchanged in its first 6 digits).
    if (std::isfinite(centred_gap_)) {
      z_ = std::move(centred_);
      result_.gap_bound = centred_gap_;
    }
    result_.status = SubproblemStatus::kStalled;
    return true;
  }
  return false;
}

// The next barrier parameter: barrier_growth times this one, but (p = 2) not beyond the one whose central point
// meets the gap with room for the decrement's term, and at least twice this one. Overshooting by up to 20x put the
// last centring deeper into the precision limit than needed: a 500-face instance stalled there. For p = inf, whose
// repairs are sensitive to the schedule, the shorter last step cost camel_cow_pinf_max 22 more Newton steps (to the
// cap of 400).
void BarrierSolver::increase_barrier_parameter() {
  const double t_meet = nu_ / (0.5 * settings_.relative_gap * f0());
  t_ *= st_.p_inf ? settings_.barrier.barrier_growth
                  : std::clamp(t_meet / t_, 2.0, std::max(2.0, settings_.barrier.barrier_growth));
}

void BarrierSolver::report(SubproblemStep& trace, Clock::time_point step_start, Clock::time_point search_start,
                           double step, bool repaired) const {
  if (!settings_.on_step) return;
  trace.step = step;
  trace.repaired = repaired;
  trace.objective = f0();
  const auto now = Clock::now();
  trace.seconds = std::chrono::duration<double>(now - step_start).count();
  trace.seconds_line_search =
      search_start == step_start ? 0.0 : std::chrono::duration<double>(now - search_start).count();
  settings_.on_step(trace);
}

// p = 2: the epigraph variables at their optimum for this t, and the slacks T_m^2 - S_m of their cones.
void BarrierSolver::epigraph_at_optimum() {
  sums_ = mesh_sums(s_, z_);
  cone_ = {1, 1};
  if (st_.p_inf) return;
  for (size_t m = 0; m < 2; ++m) {
    z_.T[m] = optimal_epigraph(sums_[m], t_);
    cone_[m] = 2 * z_.T[m] / t_;
  }
}

// Face j's derivatives of the barrier (plus, p = 2, the per-face part of the objective cone's barrier: the diagonal
// of its Hessian in e_j; the rank-one part couples the faces and is added by Woodbury in newton_direction), with its
// auxiliaries (c, e) eliminated (HessianFaceBlock), and its gradient.
void BarrierSolver::eliminate_face(int j, bool isotropic) {
  const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
  const Vec7 q = local_vars(s_, z_, j);
  Vec7 g;
  Mat7 H;
  barrier_derivatives(q, fs.cs, fs.sn, fs.ghost(), fs.bound, st_, g, H);
  if (!st_.p_inf && !fs.ghost()) {
    const double gm = cone_[static_cast<size_t>(fs.mesh)];
    g(kE) += 2 * fs.w * q(kE) / gm;
    H(kE, kE) += 2 * fs.w / gm;
  }
  newton_.faces[static_cast<size_t>(j)].eliminate(H, fs.S, isotropic && !fs.ghost());
  FaceGradient& fg = grad_[static_cast<size_t>(j)];
  fg.gx = fs.S.transpose() * g.head<4>();
  fg.gy = g.segment<2>(kC);
  fg.g_t = g(kT);
}

// Assembles the Schur system and the gradient: the faces of the two halves of the factorisation's split on two
// threads (FacePartition), the rest after them; then the epigraph variables' derivatives.
void BarrierSolver::assemble() {
  newton_.assemble(SchurAssembly::kPartitioned);
  gx_ = Eigen::VectorXd::Zero(nv_);
  gy_.resize(2 * nf_);
  std::array<std::array<double, 2>, 3> list_g_t{}, list_h_tt{};  // per face list, summed in list order below
  for_each_face_partitioned(assembly_->parts, [&](int j, int list) {
    const FaceGradient& fg = grad_[static_cast<size_t>(j)];
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    for (int r = 0; r < 6; ++r) {
      const int v = fs.var[static_cast<size_t>(r)];
      if (v >= 0) gx_(v) += fg.gx(r);
    }
    gy_.segment<2>(2 * j) = fg.gy;
    if (fs.ghost()) return;
    list_g_t[static_cast<size_t>(list)][static_cast<size_t>(fs.mesh)] += fg.g_t;
    list_h_tt[static_cast<size_t>(list)][static_cast<size_t>(fs.mesh)] += newton_.faces[static_cast<size_t>(j)].h_tt;
  });
  g_t_ = {t_, t_};
  h_tt_ = {0, 0};
  for (size_t list = 0; list < 3; ++list) {
    for (size_t m = 0; m < 2; ++m) {
      g_t_[m] += list_g_t[list][m];
      h_tt_[m] += list_h_tt[list][m];
    }
  }
  if (!st_.p_inf) {  // derivatives of t T_m - log(T_m^2 - S_m) in T_m (the first is 0 at the optimal T_m)
    for (size_t m = 0; m < 2; ++m) {
      g_t_[m] = 0;
      h_tt_[m] = 2 * (z_.T[m] * z_.T[m] + sums_[m]) / (cone_[m] * cone_[m]);
    }
  }
}

// The coupling columns of (10a): p = inf, H's blocks between the T_m and the rest; p = 2, the vectors v_m of the
// rank-one parts v_m v_m^T of the objective cones' Hessians, v_m = 2 w_j e_j / cone_m on the e_j of mesh m.
CouplingColumns BarrierSolver::coupling_columns() const {
  if (st_.p_inf) return newton_.face_coupling();
  return newton_.rank_two_columns(kE - kC, [&](int j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    return 2 * fs.w * z_.e(j) / cone_[static_cast<size_t>(fs.mesh)];
  });
}

// The Newton direction: P^-1 applied to the gradient and the two coupling columns in one solve, then the global
// coupling of (10a) (CoupledSolve): p = inf, bordered by the T_m; p = 2, the rank-two part, coupled to the T_m by
// beta_m v_m, beta_m = -2 T_m / cone_m.
NewtonDirection BarrierSolver::newton_direction() {
  CouplingColumns C = coupling_columns();
  Eigen::MatrixXd Rx(nv_, 3), Ry(2 * nf_, 3);
  Rx << -gx_, C.x;
  Ry << -gy_, C.y;
  Eigen::MatrixXd Dx, Dy;
  newton_.apply_pinv<3>(Rx, Ry, Dx, Dy);
  CouplingColumns pinv_c{Dx.rightCols<2>(), Dy.rightCols<2>()};
  const CoupledSolve coupled = st_.p_inf ? CoupledSolve::bordered(std::move(C), std::move(pinv_c), h_tt_)
                                         : CoupledSolve::rank_two(std::move(C), std::move(pinv_c), h_tt_,
                                                                  {-2 * z_.T[0] / cone_[0], -2 * z_.T[1] / cone_[1]});
  return coupled.solve(Dx.col(0), Dy.col(0), {-g_t_[0], -g_t_[1]});
}

// The gap of the dual point built from the Newton direction d at the iterate (newton_dual_gap.h).
double BarrierSolver::dual_gap(const NewtonDirection& d) const {
  NewtonPoint p;
  p.t = t_;
  p.T = z_.T;
  p.point = [&](int j) {
    const Vec7 q = local_vars(s_, z_, j);
    return FaceValues{q.head<4>(), q(kC), q(kE)};
  };
  p.direction = [&](int j) {
    const FaceSetup& fs = s_.faces[static_cast<size_t>(j)];
    return FaceValues{fs.S * gather_corners<1>(fs, d.x), d.y(2 * j), d.y(2 * j + 1)};
  };
  p.parts = &assembly_->parts;
  p.position_extent = z_.pos.cwiseAbs().maxCoeff();
  return newton_dual_gap(s_, p);
}

StepEnd BarrierSolver::newton_step(Centring& c) {
  const auto step_start = Clock::now();
  SubproblemStep trace{.centring = result_.centrings, .t = t_, .isotropic = c.isotropic};
  auto search_start = step_start;  // set when the line search starts
  epigraph_at_optimum();
#pragma omp parallel for schedule(static) if (nf_ > kParallelFaces)
  for (int j = 0; j < nf_; ++j) eliminate_face(j, c.isotropic);
  assemble();
  const auto factor_start = Clock::now();
  trace.seconds_derivatives = std::chrono::duration<double>(factor_start - step_start).count();
  // Numerical limit of double precision reached: the iterate is strictly feasible; stop here and let the caller
  // judge the gap bound.
  if (!newton_.factorize()) {
    result_.status = SubproblemStatus::kNotFactorizable;
    return StepEnd::kMethodStops;
  }
  trace.seconds_factorization = seconds_since(factor_start);
  const NewtonDirection d = newton_direction();
  const double lambda2 = -(gx_.dot(d.x) + gy_.dot(d.y)) - (g_t_[0] * d.t[0] + g_t_[1] * d.t[1]);
  if (!std::isfinite(lambda2)) throw PipelineError("convex subproblem: the Newton step is not finite");
  ++result_.iterations;
  trace.lambda2 = lambda2;
  c.end_lambda2 = std::abs(lambda2);
  if (lambda2 < 0) {
    // Not a descent direction: the Newton system lost its precision. Never read this as convergence, unless the
    // decrement is rounding noise within the precision tolerance.
    c.stalled = -lambda2 / 2 > settings_.barrier.precision_tolerance;
    report(trace, step_start, search_start, 0, false);
    return StepEnd::kCentringEnds;
  }
  if (c.last && !c.isotropic && lambda2 / 2 <= settings_.barrier.dual_gap_decrement) {
    // The centring has reached its point if the Newton direction's dual point certifies the gap already.
    const double gap = dual_gap(d);
    if (gap <= settings_.relative_gap * f0()) {
      c.dual_gap = gap;
      report(trace, step_start, search_start, 0, false);
      return StepEnd::kCentringEnds;
    }
  }
  if (c.isotropic && lambda2 / 2 <= c.tolerance) {
    // The decrement of a modified system certifies nothing: redo the step with the true Newton system.
    c.isotropic = false;
    return StepEnd::kNextStep;
  }
  if (lambda2 / 2 <= settings_.barrier.newton_tolerance ||
      (c.last && lambda2 / 2 <= c.tolerance &&
       gap_bound(nu_, std::sqrt(lambda2), t_) <= settings_.relative_gap * f0())) {
    report(trace, step_start, search_start, 0, false);
    return StepEnd::kCentringEnds;
  }
  c.roughly_centred = !c.isotropic && !c.last && lambda2 / 2 <= c.tolerance;
  return line_search_step(c, d, lambda2, trace, step_start, search_start);
}

// Backtracking line search: halve until feasible, then until Armijo's condition on the merit holds; false in
// merit_limited if the last rejected trial was feasible. p = 2: the positions' step with the auxiliaries re-centred
// at each trial point (step_state_2), which lets the positions take steps 5-10 times longer than with the linearly
// extrapolated auxiliaries. p = inf: along the plain Newton direction, or with the auxiliaries repaired
// (step_state_inf) where only the positions limit the step. Returns the step (0: none found in 60 halvings).
double BarrierSolver::line_search(const NewtonDirection& d, double lambda2, bool repair, State& out, double& merit,
                                  bool& merit_limited) const {
  double step = 1;
  for (int halvings = 0; halvings < 60; ++halvings, step *= 0.5) {
    const bool ok = st_.p_inf ? step_state_inf(s_, z_, d.x, d.y, d.t, step, repair, out)
                              : step_state_2(s_, z_, d.x, d.y, step, t_, out);
    if (!ok) {
      merit_limited = false;
      continue;
    }
    merit = merit_difference(s_, z_, out, t_);
    if (merit <= -0.25 * step * lambda2) return step;
    merit_limited = true;
  }
  return 0.0;
}

// The step along d: the line search (p = inf: also with repaired auxiliaries if the plain one crawls, keeping the
// point of lower merit), then the move, or the end of the centring if no progress is possible.
StepEnd BarrierSolver::line_search_step(Centring& c, const NewtonDirection& d, double lambda2, SubproblemStep& trace,
                                        Clock::time_point step_start, Clock::time_point& search_start) {
  search_start = Clock::now();
  bool merit_limited = false;  // the trial before the accepted one failed Armijo's condition, not feasibility
  State zn;
  double merit = 0;
  bool repaired = !st_.p_inf;
  double step = line_search(d, lambda2, repaired, zn, merit, merit_limited);
  if (st_.p_inf && step < 1.0 / 64) {  // crawling: the auxiliaries, not the positions, block the step
    State zr;
    double merit_r = 0;
    const double step_r = line_search(d, lambda2, true, zr, merit_r, merit_limited);
    if (step_r > 0 && (step == 0 || merit_r < merit)) {
      zn = std::move(zr);
      step = step_r;
      repaired = true;
    }
  }
  if (step == 0 || (step < 1 && lambda2 / 2 <= settings_.barrier.precision_tolerance)) {
    // No progress possible at this precision: so close to the central point (Newton decrement below the precision
    // tolerance, where a full Newton step is accepted in exact arithmetic) that only rounding shortens the step,
    // the centring has done its job; further steps crawl at 1e-7 (seen on camel-cow). Farther away, a failed line
    // search means the centring stalled.
    c.stalled = !c.roughly_centred && lambda2 / 2 > settings_.barrier.precision_tolerance;
    if (step > 0) z_ = std::move(zn);
    report(trace, step_start, search_start, step, false);
    return StepEnd::kCentringEnds;
  }
  // p = 2: step_state_2 centred the accepted point's auxiliaries with the coefficients t / T_m of the previous point,
  // then set T_m to the optimum for the new S_m (centring them again with the new T_m saved no Newton steps).
  z_ = std::move(zn);
  report(trace, step_start, search_start, step, repaired);
  c.isotropic = settings_.barrier.isotropic_anticonformal_curvature && !st_.p_inf && step < 1 && merit_limited;
  return c.roughly_centred ? StepEnd::kCentringEnds : StepEnd::kNextStep;
}

}  // namespace

SubproblemResult solve_convex_subproblem(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                         const SubproblemSettings& settings, SparseCholesky& cholesky,
                                         subproblem::AssemblyStructure* cache) {
  return solve_with<BarrierSolver>(problem, X0, settings, cholesky, cache);
}

}  // namespace liftmap
