#pragma once
/// Algebra of the second-order cone K = {x = (x0, x1) : x0 >= |x1|} (dimension N >= 2) for the primal-dual method
/// (primal_dual_solver.h): its determinant, interior test, Jordan product and division, the Nesterov-Todd scaling
/// and the step to the cone's boundary. Notation as in Vandenberghe, "The CVXOPT linear and quadratic cone program
/// solvers" (2010), §4: J = diag(1, -I), det x = x^T J x = x0^2 - |x1|^2, x o y = (x^T y, x0 y1 + y0 x1).
/// Every function works for a fixed dimension N or for Eigen::Dynamic.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace liftmap::soc {

template <int N>
using Vec = Eigen::Matrix<double, N, 1>;

/// det x = x0^2 - |x1|^2, computed as (x0 - |x1|)(x0 + |x1|) (no cancellation of the squares near the boundary).
template <class V>
double det(const Eigen::MatrixBase<V>& x) {
  const double r = x.tail(x.size() - 1).norm();
  return (x(0) - r) * (x(0) + r);
}

/// x in the interior of K (for a vector of size 1: x0 > 0, the half-line).
template <class V>
bool interior(const Eigen::MatrixBase<V>& x) {
  if (x.size() == 1) return x(0) > 0;
  return x(0) > 0 && x(0) > x.tail(x.size() - 1).norm();
}

/// x^-1 = J x / det x, the inverse in the Jordan algebra (x o x^-1 = e = (1, 0)); 1 / x0 for size 1.
/// \pre x in the interior of K
inline Eigen::VectorXd inverse(const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() == 1) return Eigen::VectorXd::Constant(1, 1 / x(0));
  Eigen::VectorXd y = x / det(x);
  y.tail(x.size() - 1) *= -1;
  return y;
}

/// x o y = (x^T y, x0 y1 + y0 x1).
template <int N>
Vec<N> jordan_product(const Vec<N>& x, const Vec<N>& y) {
  const Eigen::Index n = x.size() - 1;
  Vec<N> p(x.size());
  p(0) = x.dot(y);
  p.tail(n) = x(0) * y.tail(n) + y(0) * x.tail(n);
  return p;
}

/// u with lambda o u = d: u0 = (lambda0 d0 - lambda1^T d1) / det lambda, u1 = (d1 - u0 lambda1) / lambda0.
/// \pre lambda in the interior of K
template <int N>
Vec<N> jordan_divide(const Vec<N>& lambda, const Vec<N>& d) {
  const Eigen::Index n = lambda.size() - 1;
  const double dl = det(lambda);
  Vec<N> u(lambda.size());
  u(0) = (lambda(0) * d(0) - lambda.tail(n).dot(d.tail(n))) / dl;
  u.tail(n) = (d.tail(n) - u(0) * lambda.tail(n)) / lambda(0);
  return u;
}

/// Nesterov-Todd scaling W = beta (2 v v^T - J) of a pair (s, z) of the cone's interior: W z = W^-1 s = lambda.
/// wbar is the normalised scaling point (det wbar = 1), v = (wbar + e) / sqrt(2 (wbar0 + 1)) its square root in the
/// Jordan algebra, beta = (det s / det z)^(1/4), and W^-2 = (2 J wbar (J wbar)^T - J) / beta^2 (Vandenberghe §4.2).
template <int N>
struct Scaling {
  Vec<N> v, wbar;
  double beta = 1;
};

/// The Nesterov-Todd scaling of (s, z): wbar = (s/sqrt(det s) + J z/sqrt(det z)) / (2 gamma),
/// gamma = sqrt((1 + sbar^T zbar) / 2).
/// \pre s and z in the interior of K
template <int N>
Scaling<N> nesterov_todd(const Vec<N>& s, const Vec<N>& z) {
  const double sn = std::sqrt(det(s)), zn = std::sqrt(det(z));
  const Vec<N> sb = s / sn;
  Vec<N> zb = z / zn;
  const double gamma = std::sqrt((1 + sb.dot(zb)) / 2);
  zb.tail(zb.size() - 1) *= -1;  // J zbar
  Scaling<N> w;
  w.wbar = (sb + zb) / (2 * gamma);
  w.v = w.wbar;
  w.v(0) += 1;
  w.v /= std::sqrt(2 * (w.wbar(0) + 1));
  w.beta = std::sqrt(sn / zn);
  return w;
}

/// W x = beta (2 (v^T x) v - J x).
template <int N>
Vec<N> apply_w(const Scaling<N>& w, const Vec<N>& x) {
  Vec<N> y = 2 * w.v.dot(x) * w.v;
  y(0) -= x(0);
  y.tail(y.size() - 1) += x.tail(x.size() - 1);
  return w.beta * y;
}

/// W^-1 x = (2 ((J v)^T x) J v - J x) / beta.
template <int N>
Vec<N> apply_w_inverse(const Scaling<N>& w, const Vec<N>& x) {
  const double jvx = w.v(0) * x(0) - w.v.tail(w.v.size() - 1).dot(x.tail(x.size() - 1));
  Vec<N> y(x.size());
  y(0) = 2 * jvx * w.v(0) - x(0);
  y.tail(y.size() - 1) = -2 * jvx * w.v.tail(w.v.size() - 1) + x.tail(x.size() - 1);
  return y / w.beta;
}

/// The largest a >= 0 with x + a d in the closed cone: the first positive root of
/// det(x + a d) = det x + 2 a (x^T J d) + a^2 det d; +infinity if the whole ray stays inside.
/// \pre x in the interior of K
template <int N>
double max_step(const Vec<N>& x, const Vec<N>& d) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Eigen::Index n = x.size() - 1;
  const double c = det(x);
  const double b = x(0) * d(0) - x.tail(n).dot(d.tail(n));
  const double a = det(d);
  if (a == 0) return b < 0 ? -c / (2 * b) : kInf;
  const double disc = b * b - a * c;
  if (disc < 0) return kInf;  // det stays positive: the ray stays in the cone's interior
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double t = kInf;
  for (const double r : {q / a, q != 0 ? c / q : kInf}) {
    if (r > 0) t = std::min(t, r);
  }
  return t;
}

/// The same for the half-line x >= 0: -x / d if d < 0, else +infinity.
inline double max_step_linear(double x, double d) { return d < 0 ? -x / d : std::numeric_limits<double>::infinity(); }

}  // namespace liftmap::soc
