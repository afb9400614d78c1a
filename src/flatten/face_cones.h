#pragma once
/// Problem (10) as a second-order-cone program, face by face (primal_dual_solver.h lists the cones): each face's
/// local variables and the cones that constrain them, s = A x_loc + b.

#include <Eigen/Core>
#include <array>

#include "flatten/subproblem_faces.h"

namespace liftmap::subproblem {

/// Local variables of one face: x_loc = (alpha, beta, gamma, delta, c, r, s, e, T). (alpha..delta) = S u are linear
/// in the corner positions u; c, r, s, e are the face's auxiliaries; T is the epigraph variable of its mesh.
/// p = inf: the epigraph of E_j is T itself, e is unused. Unused auxiliaries get a unit curvature and stay 0.
constexpr int kC = 4;
constexpr int kR = 5;
constexpr int kS = 6;
constexpr int kE = 7;
constexpr int kT = 8;
constexpr int kLocal = 9;
constexpr int kAux = 4;       ///< auxiliaries per face (c, r, s, e)
constexpr int kMaxCones = 4;  ///< cones per face
constexpr int kRows = 3 * kMaxCones;
using VecL = Eigen::Matrix<double, kLocal, 1>;

/// One cone of a face: s = A x_loc(var) + b, dimension 1 (s >= 0) or 3 (s0 >= |(s1, s2)|).
struct Cone {
  int dim = 3;
  int n = 0;                 ///< variables it depends on
  std::array<int, 4> var{};  ///< their local indices
  Eigen::Matrix<double, 3, 4> A = Eigen::Matrix<double, 3, 4>::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

/// The cones of one face; cone k's slack and dual occupy rows 3k .. 3k + dim - 1 of the face's kRows.
struct FaceCones {
  std::array<Cone, kMaxCones> cone;
  int n = 0;
};

/// The cones of face fs (their rows depend only on the rotation and the ghost bound): c >= |(gamma, delta)|, then
/// for energy faces top - c >= |(alpha, beta)| and the rotated cone inv m >= 1 (m = alpha cos + beta sin - c),
/// with (top, inv) = (r, s) and e >= |(r, s)| for eq. 3, or both the epigraph variable for eq. 2; for ghost faces
/// bound - c >= |(alpha, beta)| and m >= 0.
void face_cones(const FaceSetup& fs, const Settings& st, FaceCones& fc);

/// s = A x_loc(var) + b of cone k (the first k.dim entries are meaningful). Inline: the solver's per-face loops
/// call it for every cone of every face several times per iteration.
inline Eigen::Vector3d cone_value(const Cone& k, const VecL& x) {
  Eigen::Vector4d xv = Eigen::Vector4d::Zero();
  for (int i = 0; i < k.n; ++i) xv(i) = x(k.var[static_cast<size_t>(i)]);
  return k.A * xv + k.b;
}

}  // namespace liftmap::subproblem
