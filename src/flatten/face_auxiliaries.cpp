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
