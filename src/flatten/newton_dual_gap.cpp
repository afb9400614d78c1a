#include "flatten/newton_dual_gap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "flatten/epigraph_norm.h"
#include "flatten/newton_system.h"

namespace liftmap::subproblem {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// An energy face's c-cone multiplier z1(0) is at least this times |(v_alpha, v_beta)|, its epigraph share's: the least
/// -v_c = z1(0) for which the epigraph's cones can hold the share is exactly |(v_alpha, v_beta)| (epigraph_least_a),
/// and the margin keeps the rounding of a from exceeding it.
constexpr double kLeastCMargin = 1 + 1e-12;

/// Rounds of objective_cone_shares' scaling at most: two without raised faces, one more for each time a lower scale
/// raises more of them (at most four seen, on the punctured hand with up to 89 faces raised).
constexpr int kObjectiveConeRounds = 8;

/// The objective cones' multipliers are kept inside by this much relative (objective_cone_shares).
constexpr double kConeMargin = 1e-13;

/// Local variables (alpha, beta, gamma, delta, c, e) of a face.
using Vec6L = Eigen::Matrix<double, 6, 1>;
using Mat6L = Eigen::Matrix<double, 6, 6>;
constexpr int kC = 4;
constexpr int kE = 5;

Vec6L local(const FaceValues& f) {
  Vec6L q;
  q << f.a, f.c, f.e;
  return q;
}

/// The share -(grad F + hess F dq) / t of the term F = -log(g) (g > 0, gradient dg, Hessian d2g) in N variables.
template <int N>
Eigen::Matrix<double, N, 1> log_barrier_share(double g, const Eigen::Matrix<double, N, 1>& dg,
                                              const Eigen::Matrix<double, N, N>& d2g,
                                              const Eigen::Matrix<double, N, 1>& dq, double t) {
  return (dg / g * (1 - dg.dot(dq) / g) + d2g * dq / g) / t;
}

/// The multiplier -(grad F + hess F ds) / t of the second-order cone term F = -log(s^T J s) of the cone
/// c >= |(gamma, delta)|, s = (c, gamma, delta).
Eigen::Vector3d cone_share(const Vec6L& q, const Vec6L& dq, double t) {
  const Eigen::Vector3d s(q(kC), q(2), q(3)), ds(dq(kC), dq(2), dq(3));
  const Eigen::Vector3d Js(s(0), -s(1), -s(2)), Jds(ds(0), -ds(1), -ds(2));
  const double g = s.dot(Js);
  return (2 * Js / g + 2 * Jds / g - 4 * Js * s.dot(Jds) / (g * g)) / t;
}

/// n = |(alpha, beta)| with its gradient and Hessian in the local variables.
struct Norm {
  double n = 0;
  Vec6L d = Vec6L::Zero();
  Mat6L d2 = Mat6L::Zero();
};

Norm norm_of(const Vec6L& q) {
  Norm r;
  const double al = q(0), be = q(1);
  r.n = std::sqrt(al * al + be * be);
  r.d(0) = al / r.n;
  r.d(1) = be / r.n;
  const double n3 = r.n * r.n * r.n;
  r.d2(0, 0) = be * be / n3;
  r.d2(1, 1) = al * al / n3;
  r.d2(0, 1) = r.d2(1, 0) = -al * be / n3;
  return r;
}

/// The gradient of m = alpha cos + beta sin - c.
Vec6L m_gradient(const FaceSetup& fs) {
  Vec6L dm = Vec6L::Zero();
  dm(0) = fs.cs;
  dm(1) = fs.sn;
  dm(kC) = -1;
  return dm;
}

/// What the first pass keeps of a face: the part of its gap that does not depend on the objective cones' scaling,
/// its epigraph's share on (alpha, beta, c, e) and its values there, and its share on (alpha, beta, gamma, delta)
/// for the residual.
struct FaceShares {
  double gap = 0;
  Eigen::Vector4d epigraph = Eigen::Vector4d::Zero();
  Eigen::Vector4d at = Eigen::Vector4d::Zero();
  Eigen::Vector4d jacobian = Eigen::Vector4d::Zero();
  bool ok = true;
};

/// An energy face (h of eq. 3): the cone of c, whose first entry is raised to the norm of the others if needed (and
/// to |(v_alpha, v_beta)|, kLeastCMargin), and the epigraph's share, whose gap needs the scaling. The epigraph's share
/// of c is minus the cone's, so that the face is stationary in c exactly (the Newton equation's row of c holds only
/// up to rounding) whatever the first entry is.
FaceShares energy_face(const Vec6L& q, const Vec6L& dq, const FaceSetup& fs, double t) {
  FaceShares out;
  // The epigraph term -log(e - R) on (alpha, beta, c, e).
  const EpigraphNorm en = epigraph_norm(q(0), q(1), q(kC), fs.cs, fs.sn);
  const Eigen::Vector4d dq4(dq(0), dq(1), dq(kC), dq(kE));
  const Eigen::Vector4d v =
      log_barrier_share<4>(q(kE) - en.R, Eigen::Vector4d::Unit(3) - en.d, Eigen::Matrix4d(-en.d2), dq4, t);
  Eigen::Vector3d z1 = cone_share(q, dq, t);
  const double rho = std::hypot(z1(1), z1(2));
  z1(0) = std::max({z1(0), rho, kLeastCMargin * std::hypot(v(0), v(1))});
  out.gap = z1.dot(Eigen::Vector3d(q(kC), q(2), q(3)));
  out.epigraph << v(0), v(1), -z1(0), v(3);
  out.at << q(0), q(1), q(kC), q(kE);
  out.jacobian << v(0), v(1), z1(1), z1(2);
  return out;
}

/// The least a of the epigraph's cone r - c >= |(alpha, beta)| for the share v = (v_alpha, v_beta, v_c, v_e): the a
/// that keeps a (1, w / a) in that cone, w = (v_alpha, v_beta) + v_c (cos, sin); +infinity if there is none or it
/// exceeds -v_c (the rotated cone's b = -v_c - a would be negative). It does not depend on v_e.
double epigraph_least_a(const Eigen::Vector4d& v, const FaceSetup& fs) {
  const double vc = v(2);
  const Eigen::Vector2d d(fs.cs, fs.sn);
  const Eigen::Vector2d w = v.head<2>() + vc * d;
  const double wd = w.dot(d), ww = w.squaredNorm();
  double a = 0;  // p b = sqrt(ve^2 - a^2) (-vc - a) decreases in a: the least a that keeps a (1, w / a) in its cone
  if (ww > 0) {
    if (!(wd < 0)) return kInf;
    a = ww / (-2 * wd);
  }
  return a <= -vc ? a : kInf;
}

/// The epigraph's gap for its share v = (v_alpha, v_beta, v_c, v_e) (v_e already scaled) at the values `at` of
/// (alpha, beta, c, e), given its epigraph_least_a; +infinity if no multipliers of its three cones reproduce v.
double epigraph_gap(const Eigen::Vector4d& v, double a, const Eigen::Vector4d& at) {
  const double ve = v(3), vc = v(2);
  if (!(ve > 0) || !(a <= ve)) return kInf;
  const double p = std::sqrt(ve * ve - a * a), b = -vc - a;
  return v.dot(at) - 2 * std::sqrt(p * b);
}

/// A ghost face: the summed share of its three terms (c >= |(gamma, delta)|, m >= 0, n <= bound - c) split with the
/// least gap: z1 = (z10, v_gamma, v_delta), z_m, z6 = (z10 - z_m - v_c, v_alpha - z_m cos, v_beta - z_m sin), the gap
/// growing with delta = z10 - z_m (times the bound); delta = max(rho - z_m, v_c + |(v_alpha, v_beta) - z_m (cos,
/// sin)|), rho = |(v_gamma, v_delta)|, is convex in z_m and least either where the norm is least or where the two
/// meet.
FaceShares ghost_face(const Vec6L& q, const Vec6L& dq, const FaceSetup& fs, double t) {
  FaceShares out;
  const Norm nn = norm_of(q);
  const double c = q(kC), m = q(0) * fs.cs + q(1) * fs.sn - c;
  const Vec6L dm = m_gradient(fs);
  Vec6L v = log_barrier_share<6>(fs.bound - nn.n - c, -nn.d - Vec6L::Unit(kC), -nn.d2, dq, t) +
            log_barrier_share<6>(m, dm, Mat6L::Zero(), dq, t);
  const Eigen::Vector3d z1 = cone_share(q, dq, t);
  v(kC) = 0;  // stationary in c exactly: the three shares of c sum to 0 (the Newton equation's row, up to rounding)
  v(2) += z1(1);
  v(3) += z1(2);
  out.jacobian = v.head<4>();
  const double rho = std::hypot(v(2), v(3));
  const Eigen::Vector2d d(fs.cs, fs.sn), vab(v(0), v(1));
  const double D = vab.dot(d), P = std::abs(vab(0) * d(1) - vab(1) * d(0));
  auto need = [&](double zm) { return std::max(rho - zm, v(kC) + (vab - zm * d).norm()); };
  double zm = std::max(D, 0.0);
  if (rho - zm > v(kC) + std::sqrt(P * P + (zm - D) * (zm - D))) {
    const double K = rho - v(kC);  // where rho - z = v_c + |vab - z d|, beyond the norm's least point
    zm = (K * K - P * P - D * D) / (2 * (K - D));
  }
  const double delta = need(zm);
  const double z10 = delta + zm, z60 = delta - v(kC);
  if (!(zm >= 0) || !(z10 >= rho) || !(z60 >= (vab - zm * d).norm())) {
    out.ok = false;
    return out;
  }
  out.gap = z10 * c + v(2) * q(2) + v(3) * q(3) + zm * m + z60 * (fs.bound - c) + (v(0) - zm * fs.cs) * q(0) +
            (v(1) - zm * fs.sn) * q(1);
  return out;
}

/// Each energy face's v_e, the multiplier of e_j in the epigraph's cone e >= |(r, s)| and (times -1 / sqrt(w_j)) in
/// its mesh's objective cone T_m >= |(sqrt(w_j) e_j)|. Stationarity in e_j holds for any v_e, so v_e is free but for
/// two cones: each objective cone's multiplier (1, -v_e / sqrt(w)) must lie in it, sum_j v_e^2 / w_j <= 1 over the
/// mesh, and each epigraph's needs v_e >= a_j (epigraph_least_a). The Newton direction's v_e are scaled down by one
/// factor per mesh, and those below their a_j raised to it: v_e' = max(s v_e, a_j), with s the largest that keeps the
/// sum at most 1 (s^2 times the free faces' sum plus the raised faces' a_j^2 / w_j; a lower s may raise more faces,
/// hence a few rounds). Far from the central path a few faces whose Newton step leaves their cones (v_e < a_j) would
/// otherwise leave the whole point without a gap.
struct ObjectiveConeShares {
  std::vector<double> v_e;  ///< per face (0 for ghost faces)
  std::vector<double> a;    ///< per face, epigraph_least_a (0 for ghost faces)
  bool feasible = false;    ///< false: some a_j is infinite, or the raised faces alone fill a cone
};

ObjectiveConeShares objective_cone_shares(const Setup& s, const std::vector<FaceShares>& shares) {
  const int nf = s.n_faces;
  ObjectiveConeShares out;
  out.v_e.assign(static_cast<size_t>(nf), 0.0);
  out.a.assign(static_cast<size_t>(nf), 0.0);
  std::vector<double>& a = out.a;
  for (int j = 0; j < nf; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    if (fs.ghost()) continue;
    a[static_cast<size_t>(j)] = epigraph_least_a(shares[static_cast<size_t>(j)].epigraph, fs);
    if (!std::isfinite(a[static_cast<size_t>(j)])) return out;
  }
  std::array<double, 2> scale{1, 1};
  for (int round = 0; round < kObjectiveConeRounds; ++round) {
    std::array<double, 2> norm2{0, 0}, free2{0, 0}, raised2{0, 0};  // the sum; the free faces' unscaled; the raised
    for (int j = 0; j < nf; ++j) {
      const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
      if (fs.ghost()) continue;
      const size_t m = static_cast<size_t>(fs.mesh);
      const double ve = shares[static_cast<size_t>(j)].epigraph(3), aj = a[static_cast<size_t>(j)];
      const double ve_out = std::max(scale[m] * ve, aj);
      out.v_e[static_cast<size_t>(j)] = ve_out;
      norm2[m] += ve_out * ve_out / fs.w;
      if (scale[m] * ve >= aj) {
        free2[m] += ve * ve / fs.w;
      } else {
        raised2[m] += aj * aj / fs.w;
      }
    }
    if (norm2[0] <= 1 && norm2[1] <= 1) {
      out.feasible = true;
      return out;
    }
    for (size_t m = 0; m < 2; ++m) {
      if (norm2[m] <= 1) continue;
      if (!(raised2[m] < 1)) return out;
      // Below the least factor for this round's faces, and below the last factor in any case: the sum's rounding
      // (some 1e-15 relative over 50k faces) must not leave it a hair above 1 round after round.
      scale[m] =
          std::min((1 - kConeMargin) * std::sqrt(1 - raised2[m]) / std::sqrt(free2[m]), (1 - kConeMargin) * scale[m]);
    }
  }
  return out;
}

}  // namespace

double newton_dual_gap(const Setup& s, const NewtonPoint& p) {
  if (s.settings.h_max || s.settings.p_inf) return kInf;
  const int nf = s.n_faces;
  std::vector<FaceShares> shares(static_cast<size_t>(nf));
  int ok = 1;
#pragma omp parallel for schedule(static) reduction(min : ok) if (nf > kParallelFaces)
  for (int j = 0; j < nf; ++j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    const Vec6L q = local(p.point(j)), dq = local(p.direction(j));
    FaceShares& f = shares[static_cast<size_t>(j)];
    f = fs.ghost() ? ghost_face(q, dq, fs, p.t) : energy_face(q, dq, fs, p.t);
    if (!f.ok) ok = 0;
  }
  if (ok == 0) return kInf;
  const ObjectiveConeShares e_shares = objective_cone_shares(s, shares);
  if (!e_shares.feasible) return kInf;
  const double face_gaps = sum_over_faces<double>(nf, [&](int j) {
    const FaceSetup& fs = s.faces[static_cast<size_t>(j)];
    const FaceShares& f = shares[static_cast<size_t>(j)];
    if (fs.ghost()) return f.gap;
    Eigen::Vector4d v = f.epigraph;
    v(3) = e_shares.v_e[static_cast<size_t>(j)];
    // The objective cone's part of s^T z, -e_j v_e, cancels the epigraph's v_e e_j.
    return f.gap + epigraph_gap(v, e_shares.a[static_cast<size_t>(j)], f.at) - f.at(3) * v(3);
  });
  if (!std::isfinite(face_gaps)) return kInf;
  const double gap = face_gaps + p.T[0] + p.T[1];
  // Stationarity in the positions: the residual sum_j S_j^T v_j of the Newton equation (negated).
  std::vector<Eigen::Matrix<double, 6, 1>> corners(static_cast<size_t>(nf));
  for (int j = 0; j < nf; ++j) {
    corners[static_cast<size_t>(j)] =
        s.faces[static_cast<size_t>(j)].S.transpose() * shares[static_cast<size_t>(j)].jacobian;
  }
  Eigen::MatrixXd residual = Eigen::MatrixXd::Zero(s.n_var, 1);
  subtract_corner_rows<1>(s, *p.parts, corners, residual);
  const double margin = residual.cwiseAbs().sum() * 2 * p.position_extent;
  if (!(gap > 0) || !(margin <= 1e-3 * gap)) return kInf;
  return gap + margin;
}

}  // namespace liftmap::subproblem
