// The per-face auxiliary problem of the barrier method: the one-variable solution must be the minimiser of the
// two-variable problem as the header states it, written out here independently.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "flatten/face_auxiliaries.h"

namespace liftmap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The objective of FaceAuxiliaryProblem in (c, e), +infinity outside its domain.
double objective(const FaceAuxiliaryProblem& p, double c, double e) {
  const double g1 = c * c - p.lo * p.lo, m = p.l - c;
  if (!(c > 0) || !(g1 > 0) || !(m > 0)) return kInf;
  if (p.ghost) {
    const double g6 = p.bound - p.n - c;
    return g6 > 0 ? -std::log(g1) - std::log(m) - std::log(g6) : kInf;
  }
  const double v = 0.5 * p.quad * e * e - std::log(g1);
  if (p.h_max) {
    const double g2 = e - p.n - c, g3 = e * m - 1;
    return g2 > 0 && g3 > 0 ? v - std::log(g2) - std::log(g3) : kInf;
  }
  const double g4 = e - std::hypot(p.n + c, 1 / m);
  return g4 > 0 ? v - std::log(g4) : kInf;
}

std::string describe(const FaceAuxiliaryProblem& p) {
  return "lo " + std::to_string(p.lo) + " n " + std::to_string(p.n) + " l - lo " + std::to_string(p.l - p.lo) +
         " quad " + std::to_string(p.quad) + (p.ghost ? " ghost" : "") + (p.h_max ? " h_max" : " h_norm");
}

/// Random problems over the scales the solver meets: sigma_tilde gaps from 1e-6 to 1, |(gamma, delta)| from 0 to 5,
/// quad = t w_j / T_m from the first centrings to the last.
std::vector<FaceAuxiliaryProblem> random_problems(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<FaceAuxiliaryProblem> problems;
  for (int i = 0; i < count; ++i) {
    FaceAuxiliaryProblem p;
    p.lo = i % 7 == 0 ? 0.0 : 5 * unit(rng);
    p.n = 0.1 + 10 * unit(rng);
    p.l = p.lo + std::pow(10.0, -6 + 6 * unit(rng));
    // quad E^2 from 1e-2 to 1e9 (E the face energy): the optimal epigraph slack of e is ~ E / (quad E^2), and
    // beyond 1e9 it falls below the precision of e * (l - c) - 1 in the objective written out here.
    const double energy = p.h_max ? std::max(p.n + p.lo, 1 / (p.l - p.lo)) : std::hypot(p.n + p.lo, 1 / (p.l - p.lo));
    p.quad = std::pow(10.0, -2 + 11 * unit(rng)) / (energy * energy);
    p.h_max = i % 2 == 1;
    p.ghost = i % 5 == 4;
    if (p.ghost) p.bound = p.n + p.lo + (p.l - p.lo) * (0.2 + 2 * unit(rng));
    problems.push_back(p);
  }
  return problems;
}

TEST(FaceAuxiliaries, MinimiseTheTwoVariableProblem) {
  int checked = 0;
  for (const FaceAuxiliaryProblem& p : random_problems(400)) {
    FaceAuxiliaries aux;
    ASSERT_TRUE(solve_face_auxiliaries(p, p.lo + 0.5 * (p.l - p.lo), aux)) << describe(p);
    const double f = objective(p, aux.c, aux.e);
    ASSERT_TRUE(std::isfinite(f)) << describe(p);
    // No point nearby is lower: perturb c by fractions of its slack and e by fractions of its own slack, in
    // 8 directions and at 3 scales. The tolerance is rounding in the objective's terms.
    const double slack_c = std::min(aux.c - p.lo, p.l - aux.c);
    const double slack_e = p.ghost ? 1.0
                                   : aux.e - (p.h_max ? std::max(p.n + aux.c, 1 / (p.l - aux.c))
                                                      : std::hypot(p.n + aux.c, 1 / (p.l - aux.c)));
    const double tol = 1e-9 * (1 + std::abs(f));
    for (double scale : {1e-1, 1e-3, 1e-5}) {
      for (int k = 0; k < 8; ++k) {
        const double angle = k * M_PI / 4;
        const double dc = scale * slack_c * std::cos(angle);
        const double de = p.ghost ? 0.0 : scale * slack_e * std::sin(angle);
        EXPECT_GE(objective(p, aux.c + dc, aux.e + de), f - tol)
            << describe(p) << " at c " << aux.c << " e " << aux.e << ", perturbed by " << dc << ", " << de;
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

TEST(FaceAuxiliaries, WarmStartDoesNotChangeTheMinimiser) {
  for (const FaceAuxiliaryProblem& p : random_problems(200)) {
    const double hi = p.ghost ? std::min(p.l, p.bound - p.n) : p.l;
    FaceAuxiliaries a, b, outside;
    ASSERT_TRUE(solve_face_auxiliaries(p, p.lo + 1e-9 * (hi - p.lo), a)) << describe(p);
    ASSERT_TRUE(solve_face_auxiliaries(p, hi - 1e-9 * (hi - p.lo), b)) << describe(p);
    ASSERT_TRUE(solve_face_auxiliaries(p, -1.0, outside)) << describe(p);
    // The slack c - lo is what the solver determines; compare it relative to itself.
    const double u = a.c - p.lo;
    EXPECT_NEAR(b.c - p.lo, u, 1e-8 * u) << describe(p);
    EXPECT_NEAR(outside.c - p.lo, u, 1e-8 * u) << describe(p);
    EXPECT_NEAR(b.e, a.e, 1e-10 * a.e) << describe(p);
  }
}

TEST(FaceAuxiliaries, RejectsInfeasiblePositions) {
  FaceAuxiliaryProblem p;
  p.lo = 1;
  p.n = 2;
  p.l = 0.5;  // sigma_tilde = l - lo < 0: no c exists
  p.quad = 1;
  FaceAuxiliaries aux;
  EXPECT_FALSE(solve_face_auxiliaries(p, 0.7, aux));
  p.l = 1.5;
  p.ghost = true;
  p.bound = 2.5;  // Sigma = n + c > n + lo = 3 > bound
  EXPECT_FALSE(solve_face_auxiliaries(p, 1.2, aux));
  p.bound = 3.4;
  EXPECT_TRUE(solve_face_auxiliaries(p, 1.2, aux));
  EXPECT_GT(aux.c, 1);
  EXPECT_LT(aux.c, 1.4);
}

}  // namespace
}  // namespace liftmap
