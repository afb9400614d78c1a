#pragma once
/// A certified duality gap of the barrier method's iterate, read off its Newton direction (docs/algorithm.md, "A dual
/// point from the Newton direction"). The barrier method's own bound, (nu + lambda sqrt(nu) / (1 - lambda)) / t, needs
/// a Newton decrement lambda below 1; this one holds at any lambda for which the dual point below is feasible, so a
/// centring that has already reached the objective's optimum need not be polished further to prove it.

#include <Eigen/Core>
#include <array>
#include <functional>

#include "flatten/subproblem_faces.h"

namespace liftmap::subproblem {

/// One face's variables in the barrier method (barrier_solver.cpp): its Jacobian coordinates
/// (alpha, beta, gamma, delta) = S u and its auxiliaries c, e; or their Newton step.
struct FaceValues {
  Eigen::Vector4d a = Eigen::Vector4d::Zero();
  double c = 0;
  double e = 0;
};

/// The barrier method's iterate and Newton direction at barrier parameter t, for p = 2 and h of eq. 3: the objective
/// T_0 + T_1 with T_m >= |(sqrt(w_j) e_j)_j|, each face's cone c >= |(gamma, delta)| and epigraph e >= |(n + c, 1 / m)|
/// (n = |(alpha, beta)|, m = alpha cos + beta sin - c), ghost faces' m >= 0 and n <= bound - c.
struct NewtonPoint {
  double t = 0;
  std::array<double, 2> T{0, 0};             ///< the epigraph variables T_m
  std::function<FaceValues(int)> point;      ///< face j's variables
  std::function<FaceValues(int)> direction;  ///< their Newton step
  double position_extent = 0;                ///< max |x_k| over the unknown coordinates (see newton_dual_gap)
  const FacePartition* parts = nullptr;      ///< the faces' partition for sums into the unknowns (must be set)
};

/// The gap s^T z of the conic form of problem (10) (three second-order cones per energy face: e >= |(r, s)|,
/// r - c >= |(alpha, beta)|, s m >= 1) between the iterate and a dual point z built from the Newton direction dx:
/// each barrier term F_i contributes the share v_i = -(grad F_i + hess F_i dx) / t of the objective's gradient
/// (sum_i v_i = grad f0 is the Newton equation), and each share is written as cone multipliers in closed form:
/// - c >= |(gamma, delta)|: z = -(grad F + hess F ds) / t, F = -log(s^T J s), its first entry raised to the norm of the
///   others if it falls short, and to |(v_alpha, v_beta)| of the epigraph's share (below that, no multipliers of the
///   epigraph's cones reproduce the share); the epigraph's share of c is minus that entry (the face stationary in c
///   exactly, whatever the entry);
/// - the epigraph, share v on (alpha, beta, c, e): z = (v_e, -a, -p) on e >= |(r, s)|, a (1, w / a) on
///   r - c >= |(alpha, beta)| and the rotated cone's (p, b) with b = -v_c - a, w = (v_alpha, v_beta) + v_c (cos, sin),
///   a = |w|^2 / (-2 w . (cos, sin)) the least that keeps the second in its cone, p = sqrt(v_e^2 - a^2); its gap is
///   v . q - 2 sqrt(p b);
/// - ghost faces: the three terms' summed share, split between the cones with the least gap (a convex problem in one
///   variable, solved in closed form);
/// - the objective cones: z = (1, -v_e / sqrt(w)) (exact in T_m and e_j by construction for any v_e), with every
///   face's v_e of a mesh scaled down together if |(v_e / sqrt(w))| exceeds 1, and a face's v_e below its epigraph's
///   least a raised to it (v_e' = max(s v_e, a), s the largest factor that keeps the norm at most 1): far from the
///   central path a few faces' Newton steps leave their epigraph cones, which would otherwise void the whole point.
/// Stationarity in c, e and T holds by construction; in the positions it holds up to the Newton system's residual
/// r = sum_j S_j^T v_j, which is checked: the gap is returned with |r|_1 * 2 position_extent added (the dual
/// objective's change for an optimum within twice the iterate's extent), +infinity if that exceeds 1e-3 of the gap.
/// \return +infinity if some multiplier leaves its cone (far from the central path), for h of eq. 2 or p = inf
/// (not built), or if the residual is too large (a modified Newton system: isotropic curvature, clamped blocks,
/// shifted diagonals).
double newton_dual_gap(const Setup& s, const NewtonPoint& p);

}  // namespace liftmap::subproblem
