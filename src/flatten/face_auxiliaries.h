#pragma once
/// The per-face auxiliary problem of the barrier method for problem (10) with p = 2 (paper §3.3, docs/algorithm.md):
/// at fixed vertex positions, the best auxiliary variables (c, e) of one face.

namespace liftmap {

/// One face's auxiliary problem at fixed positions: minimise over (c, e)
///   quad e^2 / 2 - log(c^2 - lo^2) - log(e - R(c))              (h of eq. 3, R = |(n + c, 1 / (l - c))|)
///   quad e^2 / 2 - log(c^2 - lo^2) - log(e - n - c) - log(e (l - c) - 1)   (h of eq. 2)
///   -log(c^2 - lo^2) - log(l - c) - log(bound - n - c)           (ghost face: constraints only, e unused)
/// c bounds |(gamma, delta)| (so Sigma <= n + c and sigma_tilde >= l - c), e bounds the face energy E_j, and
/// quad e^2 / 2 is the face's share of the objective cone's barrier, linearised in S_m = sum_j w_j e_j^2.
struct FaceAuxiliaryProblem {
  double lo = 0;       ///< |(gamma, delta)| of the face's Jacobian
  double n = 0;        ///< |(alpha, beta)|
  double l = 0;        ///< alpha cos(theta) + beta sin(theta): the rotation's part of sigma_tilde
  double bound = 0;    ///< ghost faces: upper bound of Sigma
  double quad = 0;     ///< > 0 on energy faces: t w_j / T_m
  bool ghost = false;  ///< constraint-only face
  bool h_max = false;  ///< h of eq. 2 instead of eq. 3
};

/// The minimiser of a FaceAuxiliaryProblem.
struct FaceAuxiliaries {
  double c = 0;
  double e = 0;  ///< 0 on ghost faces
};

/// Solves a FaceAuxiliaryProblem exactly, as a problem in one variable: for a fixed c the optimal e has a closed
/// form (eq. 3) or is the root of a monotone function (eq. 2), and the remaining function of the slack
/// u = c - lo is convex with a slope from -infinity at u = 0 to +infinity at the upper end of its interval. The
/// root of the slope is found by Newton's method from the warm start inside a shrinking bracket (ghost faces and
/// eq. 3, whose slope has a closed-form derivative), or, for eq. 2 and if Newton has not converged in 30 steps,
/// bracketed from the warm start and found by TOMS 748 (Boost.Math).
/// \param c_warm a guess of c, used if it lies strictly inside c's interval
/// \return false if c's interval is empty (the positions are infeasible: sigma_tilde <= 0, or a ghost face beyond
/// its bound) or numerically too thin to hold a root.
bool solve_face_auxiliaries(const FaceAuxiliaryProblem& problem, double c_warm, FaceAuxiliaries& out);

}  // namespace liftmap
