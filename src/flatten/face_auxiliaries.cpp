#include "flatten/face_auxiliaries.h"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>

namespace liftmap {

namespace {

/// The optimal e for the slack u, and its epigraph slacks: e - R (eq. 3, in `first`), or e - (n + c) and
/// e - 1 / (l - c) (eq. 2).
struct Epigraph {
  double e = 0, first = 0, second = 0;
};

Epigraph optimal_e(const FaceAuxiliaryProblem& p, double u) {
  if (p.ghost) return {};
  const double c = p.lo + u, m = (p.l - p.lo) - u;
  if (!p.h_max) {
    // quad e (e - R) = 1, written without cancellation: e - R = 2 / (quad (R + sqrt(R^2 + 4 / quad))).
    const double r = p.n + c, s = 1 / m;
    const double R = std::sqrt(r * r + s * s);
    const double slack = 2 / (p.quad * (R + std::sqrt(R * R + 4 / p.quad)));
    return {R + slack, slack, 0};
  }
  // The root of the increasing, concave f(v) = quad (M + v) - 1 / (v + M - a) - 1 / (v + M - b), e = M + v,
  // a = n + c, b = 1 / m, M = max(a, b). Newton steps from a point left of the root stay left of it; the start
  // is the root without the term that vanishes at M.
  const double a = p.n + c, b = 1 / m, big = std::max(a, b);
  const double ka = big - a, kb = big - b;  // one of them is 0
  const double q = p.quad;
  double v = 2 / (q * big + std::sqrt(q * q * big * big + 4 * q));
  for (int it = 0; it < 60; ++it) {
    const double fa = 1 / (v + ka), fb = 1 / (v + kb);
    const double dv = -(q * (big + v) - fa - fb) / (q + fa * fa + fb * fb);
    v += dv;
    if (!(std::abs(dv) > 1e-15 * v)) break;
  }
  return {big + v, v + ka, v + kb};
}

/// The derivative in u of min_e of the objective (envelope theorem: the partial derivative in c at the optimal e).
double slope(const FaceAuxiliaryProblem& p, double u) {
  const double c = p.lo + u, g1 = u * (2 * p.lo + u), m = (p.l - p.lo) - u;
  const double d = -2 * c / g1;
  if (p.ghost) return d + 1 / m + 1 / ((p.bound - p.n - p.lo) - u);
  const Epigraph ep = optimal_e(p, u);
  if (p.h_max) return d + 1 / ep.first + ep.e / (m * ep.second);  // e m - 1 = m (e - b)
  const double r = p.n + c, s = 1 / m;
  const double R = std::sqrt(r * r + s * s);
  return d + (r + s * s * s) / (R * ep.first);  // (dR/dc) / (e - R)
}

/// The slope and its derivative in u, for ghost faces and h of eq. 3 (not eq. 2: false). With R = |(r, s)|,
/// r = n + c, s = 1 / m, and the epigraph slack E = e - R at the optimal e (quad e E = 1, so dE/dc = -R' E / (e + E)):
///   slope = -2 c / g1 + R' / E,
///   slope' = 2 (c^2 + lo^2) / g1^2 + R'' / E + R'^2 / (E (e + E)),  R'' = (1 + 3 s^4 - R'^2) / R > 0;
/// for ghost faces slope = -2 c / g1 + 1 / m + 1 / (B - u) and slope' = 2 (c^2 + lo^2) / g1^2 + 1 / m^2 +
/// 1 / (B - u)^2. Every term of slope' is positive: no cancellation.
bool slope_and_derivative(const FaceAuxiliaryProblem& p, double u, double& value, double& derivative) {
  if (p.h_max) return false;
  const double c = p.lo + u, g1 = u * (2 * p.lo + u), m = (p.l - p.lo) - u;
  const double d = -2 * c / g1, dd = 2 * (c * c + p.lo * p.lo) / (g1 * g1);
  if (p.ghost) {
    const double b = (p.bound - p.n - p.lo) - u;
    value = d + 1 / m + 1 / b;
    derivative = dd + 1 / (m * m) + 1 / (b * b);
    return true;
  }
  const Epigraph ep = optimal_e(p, u);
  const double r = p.n + c, s = 1 / m;
  const double R = std::sqrt(r * r + s * s);
  const double rp = (r + s * s * s) / R;
  const double rpp = (1 + 3 * s * s * s * s - rp * rp) / R;
  value = d + rp / ep.first;
  derivative = dd + rpp / ep.first + rp * rp / (ep.first * ep.e);
  return true;
}

/// Relative step at which newton_root stops. Its convergence is quadratic, so the step before the last leaves an
/// error of ~kNewtonTolerance^2; where it is not (bracket steps), the bracket is this tight, like TOMS 748's 40 bits.
/// Looser is not enough: at 1e-10 the barrier method no longer certified a 1e-8 gap on a camel/cow patch
/// (flatten_barrier.SolvesFirstSubproblemToOptimality, p = 2, h of eq. 3).
constexpr double kNewtonTolerance = 1e-12;

/// Newton's method on the slope from the warm start u, kept inside the bracket (below, above) of the root, which
/// it narrows with every evaluation; false if it has not converged after 30 steps (under 1% of the solves on camel-cow,
/// which then go to TOMS 748). Bracketing plus TOMS 748 took 7.2 slope evaluations per solve there.
bool newton_root(const FaceAuxiliaryProblem& p, double w, double& u) {
  double below = 0, above = w;
  for (int it = 0; it < 30; ++it) {
    double s = 0, ds = 0;
    if (!slope_and_derivative(p, u, s, ds) || !std::isfinite(s) || !(ds > 0)) return false;
    if (s == 0) return true;
    (s < 0 ? below : above) = u;
    double next = u - s / ds;
    // Outside the bracket: its middle once both ends are points of opposite sign, else a quarter of the way from
    // the interval's open end (geometric: the optimal slack may be orders of magnitude below the interval).
    if (!(next > below && next < above)) {
      if (below > 0 && above < w) {
        next = 0.5 * (below + above);
      } else if (below > 0) {
        next = w - 0.25 * (w - below);
      } else {
        next = 0.25 * above;
      }
    }
    // Converged once the step is tiny relative to the distance to either end of the interval: near an end, where
    // the slope has a pole, a step relative to u alone is small long before the root (a start at 1e-9 of the
    // interval from its upper end was taken for the root).
    if (std::abs(next - u) <= kNewtonTolerance * std::min(u, w - u)) {
      u = next;
      return true;
    }
    u = next;
  }
  return false;
}

}  // namespace

bool solve_face_auxiliaries(const FaceAuxiliaryProblem& problem, double c_warm, FaceAuxiliaries& out) {
  const FaceAuxiliaryProblem& p = problem;
  const double hi = p.ghost ? std::min(p.l, p.bound - p.n) : p.l;
  const double w = hi - p.lo;  // u = c - lo lies in (0, w)
  if (!(w > 0)) return false;
  // Bracket the root of the increasing slope within a factor of 4 of u (near 0) or of w - u (near w): from the warm
  // start, move geometrically towards the end where the slope changes sign (the optimal slack can be 1e-10 of
  // the interval, and TOMS 748 needs many more steps on wider brackets: from [1e-9 w, 0.6 w] it ran out of
  // iterations far from a root at 3e-7 w).
  double u = c_warm - p.lo;
  if (!(u > 0 && u < w)) u = 1e-3 * w;
  {
    double root = u;
    if (newton_root(p, w, root) && root > 0 && root < w) {
      out.c = p.lo + root;
      out.e = optimal_e(p, root).e;
      return true;
    }
  }
  double below = 0, above = w, s_below = 0, s_above = 0;
  double s = slope(p, u);
  // The first move is a small one (1%): in the line search and after each accepted step, the warm start is the
  // face's optimum at a nearby point, and a tight bracket leaves TOMS 748 few iterations.
  double ratio = 1.01;
  for (int k = 0; k < 200 && s != 0; ++k, ratio = 4) {
    if (std::isnan(s)) return false;
    if (s < 0) {
      below = u;
      s_below = s;
      if (above < w) break;
      u = u < w / ratio ? ratio * u : w - (w - u) / ratio;
    } else {
      above = u;
      s_above = s;
      if (below > 0) break;
      u = w - u < w / ratio ? w - ratio * (w - u) : u / ratio;
    }
    if (!(u > 0 && u < w)) break;
    s = slope(p, u);
  }
  if (s != 0) {
    // No sign change inside the interval, or an infinite slope at a bracket end: the positions are numerically at
    // the boundary of their domain.
    if (!(below > 0 && above < w) || !std::isfinite(s_below) || !std::isfinite(s_above)) return false;
    boost::uintmax_t max_iter = 100;
    const auto root =
        boost::math::tools::toms748_solve([&p](double x) { return slope(p, x); }, below, above, s_below, s_above,
                                          boost::math::tools::eps_tolerance<double>(40), max_iter);
    u = 0.5 * (root.first + root.second);
  }
  out.c = p.lo + u;
  out.e = optimal_e(p, u).e;
  return true;
}

}  // namespace liftmap
