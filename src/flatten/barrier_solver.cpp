#include "flatten/barrier_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/errors.h"

namespace liftmap {

namespace {

// Local variables of one face: q = (alpha, beta, gamma, delta, c, e, T).
//   c >= |(gamma, delta)|                        (second-order cone; Sigma <= |(alpha,beta)| + c,
//                                                  sigma_tilde >= alpha cos + beta sin - c)
//   e >= h(|(alpha,beta)| + c, 1/(l - c))         (epigraph of E_j, l = alpha cos + beta sin)
//   T >= e                                       (p = inf only: epigraph of the max)
// c and e are tight at the optimum, so minimising over them reproduces (10a) exactly.
constexpr int kA = 0;
constexpr int kC = 4;
constexpr int kE = 5;
constexpr int kT = 6;
using Vec7 = Eigen::Matrix<double, 7, 1>;
using Mat7 = Eigen::Matrix<double, 7, 7>;
using Mat46 = Eigen::Matrix<double, 4, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat62 = Eigen::Matrix<double, 6, 2>;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Below this many faces the per-face loops run serially: thread start-up and contention cost more than they save.
constexpr int kParallelFaces = 4000;

/// Constant data of one face of either mesh.
struct FaceSetup {
  Mat46 S;                 // corners (u0,v0,u1,v1,u2,v2) -> (alpha,beta,gamma,delta)
  std::array<int, 6> pos;  // indices of the corners' coordinates in the position vector
  std::array<int, 6> var;  // indices in the unknowns (-1: the fixed gauge vertex)
  double cs = 1, sn = 0;   // rotation of eq. (7b)
  double w = 0;            // area |t_j|
  double bound = 0;        // ghost faces: upper bound of Sigma_j
  int mesh = 0;            // 0, 1: the two flattenings; 2: ghost face (constraint only)
  [[nodiscard]] bool ghost() const { return mesh == 2; }
};

struct Settings {
  bool h_max = false;
  bool p_inf = false;
};

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
  const double n = std::hypot(q(0), q(1));
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
    const double g4 = e - std::hypot(n + c, 1.0 / m);
    if (!(g4 > 0)) return false;
    out.g[out.n++] = g4;
  }
  return true;
}

void add_log_barrier(double g, const Vec7& dg, const Mat7& d2g, Vec7& grad, Mat7& hess) {
  grad -= dg / g;
  hess += dg * dg.transpose() / (g * g) - d2g / g;
}

/// Gradient and Hessian of the face's barrier sum_k -log(g_k) in the local variables; q must be feasible.
void barrier_derivatives(const Vec7& q, double cs, double sn, bool ghost, double bound, const Settings& s, Vec7& grad,
                         Mat7& hess) {
  grad.setZero();
  hess.setZero();
  const int ke = s.p_inf ? kT : kE;
  const double al = q(0), be = q(1), c = q(kC), e = q(ke);
  const double n = std::hypot(al, be);
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

  {  // g1 = c^2 - gamma^2 - delta^2
    Vec7 dg = Vec7::Zero();
    dg(2) = -2 * q(2);
    dg(3) = -2 * q(3);
    dg(kC) = 2 * c;
    Mat7 d2g = Mat7::Zero();
    d2g(2, 2) = d2g(3, 3) = -2;
    d2g(kC, kC) = 2;
    add_log_barrier(c * c - q(2) * q(2) - q(3) * q(3), dg, d2g, grad, hess);
  }
  if (ghost) {
    add_log_barrier(m, dm, Mat7::Zero(), grad, hess);
    add_log_barrier(bound - n - c, -dn - unit_c, -d2n, grad, hess);
    hess(kE, kE) = 1;  // e is unused: a unit curvature keeps the (c, e) block invertible and de = 0
    return;
  }
  if (s.h_max) {
    // g2 = e - c - n (Sigma <= e), g3 = e m - 1 (1/sigma_tilde <= e, a rotated cone).
    add_log_barrier(e - c - n, unit_e - unit_c - dn, -d2n, grad, hess);
    const Mat7 d2g3 = unit_e * dm.transpose() + dm * unit_e.transpose();
    add_log_barrier(e * m - 1, e * dm + m * unit_e, d2g3, grad, hess);
  } else {
    // g4 = e - R, R = |(r, s)|, r = n + c, s = 1/m.
    const double r = n + c, sv = 1.0 / m;
    const double R = std::hypot(r, sv);
    const Vec7 dr = dn + unit_c;
    const Vec7 ds = -dm / (m * m);
    const Mat7 d2s = 2.0 * dm * dm.transpose() / (m * m * m);
    const Vec7 d_r = (r * dr + sv * ds) / R;
    const Mat7 d2_r = (dr * dr.transpose() + r * d2n + ds * ds.transpose() + sv * d2s) / R - d_r * d_r.transpose() / R;
    add_log_barrier(e - R, unit_e - d_r, -d2_r, grad, hess);
  }
  if (s.p_inf) hess(kE, kE) = 1;  // e is unused
}

double face_energy(const Eigen::Vector4d& a, double cs, double sn, bool h_max) {
  const double n = std::hypot(a(0), a(1));
  const double c = std::hypot(a(2), a(3));
  const double st = a(0) * cs + a(1) * sn - c;
  if (!(st > 0)) return kInf;
  return h_max ? std::max(n + c, 1.0 / st) : std::hypot(n + c, 1.0 / st);
}

/// The per-face data of one subproblem, built once per call.
struct Setup {
  std::vector<FaceSetup> faces;
  int n_faces = 0;
  int n_pos = 0;
  int n_var = 0;
  Settings settings;
};

constexpr int kFixedSlot = 0;

Setup make_setup(const ConvexSubproblem& problem) {
  Setup s;
  s.settings.h_max = problem.h == DistortionCombiner::kMax;
  s.settings.p_inf = std::isinf(problem.p);
  s.n_pos = 2 * problem.n_slots;
  s.n_var = s.n_pos - 2;
  for (int mi = 0; mi < 3; ++mi) {
    const SubproblemMesh& mesh = mi < 2 ? problem.meshes[static_cast<size_t>(mi)] : problem.ghosts;
    if (mesh.theta.size() != mesh.F.rows() || mesh.jacobian.G.rows() != mesh.F.rows()) {
      throw InvalidInputError("convex subproblem: mesh " + std::to_string(mi) + " has inconsistent sizes");
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      FaceSetup fs;
      fs.S = similarity_map(mesh.jacobian.G.row(f));
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.F(f, k);
        if (v < 0 || v >= static_cast<int>(mesh.slot.size())) {
          throw InvalidInputError("convex subproblem: face " + std::to_string(f) + " has no slot");
        }
        const int slot = mesh.slot[static_cast<size_t>(v)];
        if (slot < 0 || slot >= problem.n_slots) throw InvalidInputError("convex subproblem: slot out of range");
        for (int d = 0; d < 2; ++d) {
          fs.pos[static_cast<size_t>(2 * k + d)] = 2 * slot + d;
          fs.var[static_cast<size_t>(2 * k + d)] = slot == kFixedSlot ? -1 : 2 * slot + d - 2;
        }
      }
      fs.cs = std::cos(mesh.theta(f));
      fs.sn = std::sin(mesh.theta(f));
      fs.w = mesh.jacobian.area(f);
      fs.mesh = mi;
      s.faces.push_back(fs);
    }
  }
  s.n_faces = static_cast<int>(s.faces.size());
  return s;
}

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

bool feasible(const Setup& s, const State& z) {
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (s.n_faces > kParallelFaces)
  for (int j = 0; j < s.n_faces; ++j) {
    BarrierArgs args;
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (!barrier_args(local_vars(s, z, j), fs.cs, fs.sn, fs.ghost(), fs.bound, s.settings, args)) ok = 0;
  }
  return ok == 1;
}

/// Bounds of a face's auxiliaries at q: c must lie in (lo, hi), and then E_j = h(n + c, 1/(l - c)).
struct AuxBounds {
  double lo = 0, hi = 0, n = 0, l = 0;
  [[nodiscard]] bool open() const { return hi > lo; }
  [[nodiscard]] double energy(double c, bool h_max) const {
    return h_max ? std::max(n + c, 1.0 / (l - c)) : std::hypot(n + c, 1.0 / (l - c));
  }
};

AuxBounds aux_bounds(const Vec7& q, const FaceSetup& fs) {
  AuxBounds b;
  b.lo = std::hypot(q(2), q(3));
  b.n = std::hypot(q(0), q(1));
  b.l = q(0) * fs.cs + q(1) * fs.sn;
  b.hi = fs.ghost() ? std::min(b.l, fs.bound - b.n) : b.l;
  return b;
}

/// The state z + step (dx, dy, d_t), with the auxiliaries of every face whose linear step leaves their cones
/// put back inside. The auxiliaries only express (10a) in conic form; the positions alone decide whether a
/// point is feasible (every sigma_tilde_j > 0, ghost bounds). Without this repair, the linearly extrapolated
/// c_j, e_j leave their cones long before the positions do, and the line search crawls at steps of 1/128.
/// A repaired c_j moves half the way from its relative place between its bounds at z towards the bound it
/// crossed; a repaired epigraph variable keeps half its slack (fraction to the boundary).
/// \param repair false: the plain linear step, infeasible as soon as any variable leaves its cone
/// \return false if the point is infeasible.
bool step_state(const Setup& s, const State& z, const Eigen::VectorXd& dx, const Eigen::VectorXd& dy,
                const std::array<double, 2>& d_t, double step, bool repair, State& zn) {
  const int nf = s.n_faces;
  const bool h_max = s.settings.h_max, p_inf = s.settings.p_inf;
  zn.pos = z.pos;
  zn.pos.tail(dx.size()) += step * dx;
  zn.c = z.c + step * dy(Eigen::seq(0, Eigen::last, 2));
  zn.e = z.e + step * dy(Eigen::seq(1, Eigen::last, 2));
  zn.T = {z.T[0] + step * d_t[0], z.T[1] + step * d_t[1]};
  // p = inf: the largest E_j at zn and at z of each mesh, to keep T's slack over the maximum.
  std::vector<double> e_new(p_inf ? static_cast<size_t>(nf) : 0, 0.0), e_old(e_new.size(), 0.0);
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
    const double h1 = b1.energy(c, h_max), h0 = b0.energy(q0(kC), h_max);
    if (p_inf) {
      e_new[static_cast<size_t>(j)] = h1;
      e_old[static_cast<size_t>(j)] = h0;
    } else if (!repair && !(zn.e(j) > h1)) {
      ok = 0;
    } else if (!(zn.e(j) > h1)) {
      zn.e(j) = h1 + 0.5 * (z.e(j) - h0);
    }
  }
  if (ok == 0) return false;
  if (p_inf) {
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
  }
  return feasible(s, zn);
}

/// Objective part of the merit, f0(z) = sum over meshes of sqrt(sum_j w_j e_j^2) or T_m.
std::array<double, 2> mesh_sums(const Setup& s, const State& z) {
  std::array<double, 2> S{0, 0};
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (!fs.ghost()) S[static_cast<size_t>(fs.mesh)] += fs.w * z.e(j) * z.e(j);
  }
  return S;
}

/// merit(z1) - merit(z0) for merit = t f0 + barrier, computed term by term (as log ratios and differences) so
/// that it stays accurate when t f0 is large; both states must be feasible.
double merit_difference(const Setup& s, const State& z0, const State& z1, double t) {
  double d = 0;
#pragma omp parallel for schedule(static) reduction(+ : d) if (s.n_faces > kParallelFaces)
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    BarrierArgs a0, a1;
    barrier_args(local_vars(s, z0, j), fs.cs, fs.sn, fs.ghost(), fs.bound, s.settings, a0);
    barrier_args(local_vars(s, z1, j), fs.cs, fs.sn, fs.ghost(), fs.bound, s.settings, a1);
    for (int k = 0; k < a0.n; ++k) d -= std::log(a1.g[static_cast<size_t>(k)] / a0.g[static_cast<size_t>(k)]);
  }
  if (s.settings.p_inf) {
    d += t * ((z1.T[0] - z0.T[0]) + (z1.T[1] - z0.T[1]));
  } else {
    std::array<double, 2> d_s{0, 0};
    for (int j = 0; j < s.n_faces; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      if (!fs.ghost()) d_s[static_cast<size_t>(fs.mesh)] += fs.w * (z1.e(j) - z0.e(j)) * (z1.e(j) + z0.e(j));
    }
    const auto S0 = mesh_sums(s, z0);
    const auto S1 = mesh_sums(s, z1);
    for (size_t m = 0; m < 2; ++m) d += t * d_s[m] / (std::sqrt(S0[m]) + std::sqrt(S1[m]));
  }
  return d;
}

/// Per-face pieces of the Newton system after eliminating (c_j, e_j).
struct FaceSystem {
  Mat6 K;                // Schur complement in the face's corner coordinates
  Mat62 B;               // coupling corners -> (c, e): S^T H_ay
  Eigen::Matrix2d Pinv;  // inverse of the (c, e) block
  Vec6 gx;               // gradient in the corner coordinates
  Eigen::Vector2d gy;    // gradient in (c, e)
  Eigen::Vector2d hyT;   // coupling (c, e) -> T
  Vec6 hxT;              // coupling corners -> T
  double h_tt = 0;
  double g_t = 0;
};

/// Sparse lower-triangular pattern of the Schur system and where each face's entries go.
struct Pattern {
  Eigen::SparseMatrix<double> A;
  std::vector<std::array<int, 36>> index;  // per face, entry (r, c) of K -> value index, -1 if not stored
};

Pattern make_pattern(const Setup& s) {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(s.n_faces) * 21);
  for (const FaceSetup& fs : s.faces) {
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) {
        const int vr = fs.var[static_cast<size_t>(r)], vc = fs.var[static_cast<size_t>(c)];
        if (vr >= 0 && vc >= 0 && vr >= vc) trip.emplace_back(vr, vc, 0.0);
      }
    }
  }
  Pattern p;
  p.A.resize(s.n_var, s.n_var);
  p.A.setFromTriplets(trip.begin(), trip.end());
  p.A.makeCompressed();
  p.index.resize(static_cast<size_t>(s.n_faces));
  const int* outer = p.A.outerIndexPtr();
  const int* inner = p.A.innerIndexPtr();
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) {
        int& idx = p.index[static_cast<size_t>(j)][static_cast<size_t>(6 * r + c)];
        idx = -1;
        const int vr = fs.var[static_cast<size_t>(r)], vc = fs.var[static_cast<size_t>(c)];
        if (vr < 0 || vc < 0 || vr < vc) continue;
        const int* it = std::lower_bound(inner + outer[vc], inner + outer[vc + 1], vr);
        idx = static_cast<int>(it - inner);
      }
    }
  }
  return p;
}

double total_nu(const Setup& s) {
  // Barrier parameters: 2 per second-order cone, 1 per convex-function constraint.
  const double per_face = 2.0 + (s.settings.h_max ? 1.0 + 2.0 : 1.0);
  double nu = 0;
  for (const FaceSetup& fs : s.faces) nu += fs.ghost() ? 4.0 : per_face;
  return nu;
}

}  // namespace

double subproblem_objective(const ConvexSubproblem& problem, const Eigen::MatrixXd& X) {
  const bool h_max = problem.h == DistortionCombiner::kMax;
  double total = 0;
  for (const SubproblemMesh& mesh : problem.meshes) {
    double acc = 0;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      Vec6 u;
      for (int k = 0; k < 3; ++k) u.segment<2>(2 * k) = X.row(mesh.slot[static_cast<size_t>(mesh.F(f, k))]).transpose();
      const Eigen::Vector4d a = similarity_map(mesh.jacobian.G.row(f)) * u;
      const double E = face_energy(a, std::cos(mesh.theta(f)), std::sin(mesh.theta(f)), h_max);
      if (std::isinf(problem.p)) {
        acc = std::max(acc, E);
      } else {
        acc += mesh.jacobian.area(f) * E * E;
      }
    }
    total += std::isinf(problem.p) ? acc : std::sqrt(acc);
  }
  return total;
}

BarrierResult solve_convex_subproblem(const ConvexSubproblem& problem, const Eigen::MatrixXd& X0,
                                      const BarrierOptions& options, SparseCholesky& cholesky) {
  if (X0.rows() != problem.n_slots || X0.cols() != 2 || problem.n_slots < 2) {
    throw InvalidInputError("convex subproblem: X0 must be #slots by 2");
  }
  Setup s = make_setup(problem);
  const Settings& st = s.settings;
  Pattern pattern = make_pattern(s);
  if (!cholesky.analyzed()) cholesky.analyze(pattern.A);

  // Strictly feasible start for the auxiliaries: c between |(gamma,delta)| and alpha cos + beta sin.
  State z;
  z.pos.resize(s.n_pos);
  for (int i = 0; i < problem.n_slots; ++i) z.pos.segment<2>(2 * i) = X0.row(i).transpose();
  z.c.resize(s.n_faces);
  z.e.resize(s.n_faces);
  z.T = {0, 0};
  for (int j = 0; j < s.n_faces; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    const Vec7 q = local_vars(s, z, j);
    const double cn = std::hypot(q(2), q(3));
    const double l = q(0) * fs.cs + q(1) * fs.sn;
    if (!(l - cn > 0)) {
      throw InvalidInputError("convex subproblem: the start is not strictly feasible (sigma_tilde <= 0 on face " +
                              std::to_string(j) + ")");
    }
    z.c(j) = cn + 0.1 * (l - cn);
    if (fs.ghost()) {
      s.faces[static_cast<size_t>(j)].bound = kGhostStretch * (std::hypot(q(0), q(1)) + cn);
      z.e(j) = 0;
      continue;
    }
    const double m = l - z.c(j);
    const double n = std::hypot(q(0), q(1));
    z.e(j) = 1.5 * (st.h_max ? std::max(n + z.c(j), 1.0 / m) : std::hypot(n + z.c(j), 1.0 / m));
    z.T[static_cast<size_t>(fs.mesh)] = std::max(z.T[static_cast<size_t>(fs.mesh)], z.e(j));
  }

  const double nu = total_nu(s);
  auto f0 = [&](const State& zz) {
    if (st.p_inf) return zz.T[0] + zz.T[1];
    const auto S = mesh_sums(s, zz);
    return std::sqrt(S[0]) + std::sqrt(S[1]);
  };
  // Start on the central path as nearly as a single t allows: t0 minimises |t grad f0 + grad barrier| in the
  // directions where f0 varies (the e_j for p = 2, the T_m for p = inf).
  double t = nu / f0(z);
  {
    double gf_gphi = 0, gf_gf = 0;
    const auto S = mesh_sums(s, z);
    std::array<double, 2> barrier_t{0, 0};
    for (int j = 0; j < s.n_faces; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      if (fs.ghost()) continue;
      Vec7 g;
      Mat7 H;
      barrier_derivatives(local_vars(s, z, j), fs.cs, fs.sn, false, 0.0, st, g, H);
      if (st.p_inf) {
        barrier_t[static_cast<size_t>(fs.mesh)] += g(kT);
      } else {
        const double df = fs.w * z.e(j) / std::sqrt(S[static_cast<size_t>(fs.mesh)]);
        gf_gphi += df * g(kE);
        gf_gf += df * df;
      }
    }
    if (st.p_inf) {
      gf_gphi = barrier_t[0] + barrier_t[1];
      gf_gf = 2;
    }
    if (gf_gphi < 0) t = -gf_gphi / gf_gf;
  }

  std::vector<FaceSystem> sys(static_cast<size_t>(s.n_faces));
  BarrierResult result;
  const int nv = s.n_var;
  const int nf = s.n_faces;

  // Applies P^{-1} to columns (R_x; R_y) where P is the Hessian without the global coupling; Y is 2 nf rows.
  auto apply_pinv = [&](const Eigen::MatrixXd& Rx, const Eigen::MatrixXd& Ry, Eigen::MatrixXd& Dx,
                        Eigen::MatrixXd& Dy) {
    const Eigen::Index k = Rx.cols();
    Eigen::MatrixXd Rt = Rx;
    for (int j = 0; j < nf; ++j) {
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      const Eigen::MatrixXd corr = fsys.B * (fsys.Pinv * Ry.middleRows(2 * j, 2));
      for (int r = 0; r < 6; ++r) {
        const int v = fs.var[static_cast<size_t>(r)];
        if (v >= 0) Rt.row(v) -= corr.row(r);
      }
    }
    Dx = cholesky.solve(Rt);
    Dy.resize(2 * nf, k);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
    for (int j = 0; j < nf; ++j) {
      const FaceSystem& fsys = sys[static_cast<size_t>(j)];
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      Eigen::MatrixXd dxl = Eigen::MatrixXd::Zero(6, k);
      for (int r = 0; r < 6; ++r) {
        const int v = fs.var[static_cast<size_t>(r)];
        if (v >= 0) dxl.row(r) = Dx.row(v);
      }
      Dy.middleRows(2 * j, 2) = fsys.Pinv * (Ry.middleRows(2 * j, 2) - fsys.B.transpose() * dxl);
    }
  };

  bool done = false;
  double last_shift = 0;  // relative diagonal shift of the last factorisation that needed one
  while (!done) {
    // Centring: Newton's method on t f0 + barrier.
    bool stalled = false;
    for (;;) {
      if (result.newton_steps >= options.max_newton_steps) {
        done = true;
        break;
      }
      const auto S = mesh_sums(s, z);
#pragma omp parallel for schedule(static) if (nf > kParallelFaces)
      for (int j = 0; j < nf; ++j) {
        const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
        FaceSystem& fsys = sys[static_cast<size_t>(j)];
        const Vec7 q = local_vars(s, z, j);
        Vec7 g;
        Mat7 H;
        barrier_derivatives(q, fs.cs, fs.sn, fs.ghost(), fs.bound, st, g, H);
        if (!st.p_inf && !fs.ghost()) {
          const double rs = std::sqrt(S[static_cast<size_t>(fs.mesh)]);
          g(kE) += t * fs.w * q(kE) / rs;
          H(kE, kE) += t * fs.w / rs;
        }
        const Eigen::Matrix2d Pyy = H.block<2, 2>(kC, kC);
        fsys.Pinv = Pyy.inverse();
        fsys.Pinv = 0.5 * (fsys.Pinv + fsys.Pinv.transpose());
        const Eigen::Matrix<double, 4, 2> Hay = H.block<4, 2>(kA, kC);
        // Schur complement Haa - Hay Pyy^-1 Hay^T with the subtracted term formed as W^T W, W = L^-1 Hay^T
        // (Pyy = L L^T): symmetric and positive semidefinite by construction. Pyy's entries span up to 20
        // orders of magnitude on nearly active faces, and the plain product with its inverse is then neither.
        Eigen::Matrix4d Haa = H.block<4, 4>(kA, kA);
        const Eigen::LLT<Eigen::Matrix2d> pyy_llt(Pyy);
        if (pyy_llt.info() == Eigen::Success) {
          const Eigen::Matrix<double, 2, 4> W = pyy_llt.matrixL().solve(Hay.transpose());
          Haa -= W.transpose() * W;
        } else {
          Haa -= Hay * fsys.Pinv * Hay.transpose();
        }
        Haa = 0.5 * (Haa + Haa.transpose());
        // The exact Schur complement is positive semidefinite; rounding in the elimination of nearly active
        // constraints (huge, nearly cancelling terms) can leave negative eigenvalues: clamp them.
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(Haa);
        if (eig.eigenvalues()(0) < 0) {
          Haa = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
        }
        fsys.K = fs.S.transpose() * Haa * fs.S;
        if (eig.eigenvalues()(0) < 1e-8 * eig.eigenvalues()(3)) {
          // Ill-conditioned block: the product's rounding (relative to its largest entries) can again leave
          // negative eigenvalues of a few percent of the smaller ones, enough to make the sum indefinite.
          Eigen::SelfAdjointEigenSolver<Mat6> eig6(0.5 * (fsys.K + fsys.K.transpose()));
          fsys.K =
              eig6.eigenvectors() * eig6.eigenvalues().cwiseMax(0.0).asDiagonal() * eig6.eigenvectors().transpose();
        }
        fsys.B = fs.S.transpose() * Hay;
        fsys.gx = fs.S.transpose() * g.head<4>();
        fsys.gy = g.segment<2>(kC);
        fsys.hyT = H.block<2, 1>(kC, kT);
        fsys.hxT = fs.S.transpose() * H.block<4, 1>(kA, kT);
        fsys.h_tt = H(kT, kT);
        fsys.g_t = g(kT);
      }
      // Assemble the Schur system and the gradient.
      double* values = pattern.A.valuePtr();
      std::fill(values, values + pattern.A.nonZeros(), 0.0);
      Eigen::VectorXd gx = Eigen::VectorXd::Zero(nv);
      Eigen::VectorXd gy(2 * nf);
      std::array<double, 2> g_t{t, t}, h_tt{0, 0};
      for (int j = 0; j < nf; ++j) {
        const FaceSystem& fsys = sys[static_cast<size_t>(j)];
        const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
        const auto& idx = pattern.index[static_cast<size_t>(j)];
        for (int r = 0; r < 6; ++r) {
          const int v = fs.var[static_cast<size_t>(r)];
          if (v >= 0) gx(v) += fsys.gx(r);
          for (int c = 0; c < 6; ++c) {
            const int i = idx[static_cast<size_t>(6 * r + c)];
            if (i >= 0) values[i] += fsys.K(r, c);
          }
        }
        gy.segment<2>(2 * j) = fsys.gy;
        if (fs.ghost()) continue;
        g_t[static_cast<size_t>(fs.mesh)] += fsys.g_t;
        h_tt[static_cast<size_t>(fs.mesh)] += fsys.h_tt;
      }
      if (cholesky.factorize(pattern.A)) {
        last_shift = 0;
      } else {
        // Rounding in the eliminated blocks of nearly active constraints can make the Schur complement
        // numerically indefinite late in the solve: shift the diagonal until it factorises. Any positive
        // definite matrix still gives a descent direction, and the line search keeps the iterate feasible.
        // The shift is relative to each diagonal entry: the curvatures span many orders of magnitude.
        const Eigen::VectorXd diag = pattern.A.diagonal();
        // Start near the shift that worked last time: each attempt is a full factorisation.
        double shift = std::max(1e-14, 1e-2 * last_shift);
        bool ok = false;
        for (; shift < 1e3 && !ok; shift *= 100) {
          for (int v = 0; v < nv; ++v) pattern.A.coeffRef(v, v) = diag(v) * (1 + shift);
          ok = cholesky.factorize(pattern.A);
          if (ok) last_shift = shift;
        }
        if (!ok) {
          // Numerical limit of double precision reached: the iterate is strictly feasible; stop here and let
          // the caller judge the gap bound.
          done = true;
          break;
        }
      }

      // Newton direction, with the global coupling of (10a) handled on top of P^{-1}.
      Eigen::MatrixXd Rx(nv, 3), Ry(2 * nf, 3);
      Rx.setZero();
      Ry.setZero();
      Rx.col(0) = -gx;
      Ry.col(0) = -gy;
      for (int j = 0; j < nf; ++j) {
        const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
        if (fs.ghost()) continue;
        const int col = 1 + fs.mesh;
        if (st.p_inf) {
          Ry.block<2, 1>(2 * j, col) = sys[static_cast<size_t>(j)].hyT;
          for (int r = 0; r < 6; ++r) {
            const int v = fs.var[static_cast<size_t>(r)];
            if (v >= 0) Rx(v, col) += sys[static_cast<size_t>(j)].hxT(r);
          }
        } else {
          const double Sm = S[static_cast<size_t>(fs.mesh)];
          Ry(2 * j + 1, col) = std::sqrt(t / (Sm * std::sqrt(Sm))) * fs.w * z.e(j);
        }
      }
      Eigen::MatrixXd Dx, Dy;
      apply_pinv(Rx, Ry, Dx, Dy);
      Eigen::VectorXd dx = Dx.col(0), dy = Dy.col(0);
      std::array<double, 2> d_t{0, 0};
      if (st.p_inf) {
        // Bordered system [[P, Q], [Q^T, h_tt]]: Schur complement on the two epigraph variables.
        Eigen::Matrix2d M;
        Eigen::Vector2d rhs;
        for (int a = 0; a < 2; ++a) {
          rhs(a) = -g_t[static_cast<size_t>(a)] - Rx.col(1 + a).dot(Dx.col(0)) - Ry.col(1 + a).dot(Dy.col(0));
          for (int b = 0; b < 2; ++b) {
            M(a, b) = (a == b ? h_tt[static_cast<size_t>(a)] : 0.0) - Rx.col(1 + a).dot(Dx.col(1 + b)) -
                      Ry.col(1 + a).dot(Dy.col(1 + b));
          }
        }
        const Eigen::Vector2d sol = M.ldlt().solve(rhs);
        d_t = {sol(0), sol(1)};
        dx -= Dx.middleCols(1, 2) * sol;
        dy -= Dy.middleCols(1, 2) * sol;
      } else {
        // Woodbury for P - U U^T, U = the two rank-one terms of the Hessians of sqrt(S_m).
        Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
        Eigen::Vector2d utd;
        for (int a = 0; a < 2; ++a) {
          utd(a) = Ry.col(1 + a).dot(Dy.col(0));
          for (int b = 0; b < 2; ++b) M(a, b) -= Ry.col(1 + a).dot(Dy.col(1 + b));
        }
        const Eigen::Vector2d coef = M.partialPivLu().solve(utd);
        dx += Dx.middleCols(1, 2) * coef;
        dy += Dy.middleCols(1, 2) * coef;
      }
      double lambda2 = -(gx.dot(dx) + gy.dot(dy));
      if (st.p_inf) lambda2 -= g_t[0] * d_t[0] + g_t[1] * d_t[1];
      if (!std::isfinite(lambda2)) throw PipelineError("convex subproblem: the Newton step is not finite");
      ++result.newton_steps;
      if (lambda2 / 2 <= options.newton_tolerance) break;

      // Backtracking line search: halve until feasible, then until Armijo's condition on the merit holds.
      // First along the plain Newton direction; if that stops short, also with the auxiliaries repaired (see
      // step_state), where only the positions limit the step, and keep the point of lower merit.
      auto line_search = [&](bool repair, State& out, double& merit) {
        double step = 1;
        for (int halvings = 0; halvings < 60; ++halvings, step *= 0.5) {
          if (!step_state(s, z, dx, dy, d_t, step, repair, out)) continue;
          merit = merit_difference(s, z, out, t);
          if (merit <= -0.25 * step * lambda2) return step;
        }
        return 0.0;
      };
      State zn;
      double merit = 0;
      double step = line_search(false, zn, merit);
      if (step < 1.0 / 64) {  // crawling: the auxiliaries, not the positions, are what block the step
        State zr;
        double merit_r = 0;
        const double step_r = line_search(true, zr, merit_r);
        if (step_r > 0 && (step == 0 || merit_r < merit)) {
          zn = std::move(zr);
          step = step_r;
        }
      }
      if (step == 0) {  // no progress possible at this precision, short of the Newton tolerance
        stalled = true;
        break;
      }
      z = std::move(zn);
    }
    ++result.centrings;
    if (stalled) ++result.stalled_centrings;
    const double gap = nu / t;
    result.gap_bound = gap;
    if (done) break;
    if (gap <= options.relative_gap * f0(z)) {
      // nu / t bounds the gap only at a centred point: a last centring that stalled certifies nothing.
      result.converged = !stalled;
      break;
    }
    t *= options.barrier_growth;
  }

  result.X.resize(problem.n_slots, 2);
  for (int i = 0; i < problem.n_slots; ++i) result.X.row(i) = z.pos.segment<2>(2 * i).transpose();
  result.objective = subproblem_objective(problem, result.X);
  return result;
}

}  // namespace liftmap
