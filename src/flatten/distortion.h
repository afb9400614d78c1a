#pragma once
/// Isometric distortion of flattenings (paper §3.3, eqs. (1)-(3) and (8); docs/algorithm.md, "The convexified
/// distortion").

#include <Eigen/Core>

namespace liftmap {

/// h in eq. (1): how the two stretches r = Sigma and s = 1/sigma combine into a per-face distortion.
enum class DistortionCombiner {
  kMax,   ///< h(r, s) = max(r, s), eq. (2): the dilation
  kNorm,  ///< h(r, s) = sqrt(r^2 + s^2), eq. (3): the paper's default
};

/// Per-face singular values from the 2-vector form: Sigma = |(alpha,beta)| + |(gamma,delta)|,
/// sigma = | |(alpha,beta)| - |(gamma,delta)| |.
/// \param P #F by 4 rows (alpha, beta, gamma, delta), see similarity_parts()
/// \return #F by 2 rows (Sigma, sigma)
Eigen::MatrixXd singular_values(const Eigen::MatrixXd& P);

/// The convexified smallest singular value sigma_tilde = alpha cos(theta) + beta sin(theta) - |(gamma,delta)|
/// of eq. (7b) (docs/algorithm.md); concave in the Jacobian, <= sigma, equal to sigma when theta is the polar rotation.
/// \param P #F by 4 (alpha, beta, gamma, delta)
/// \param theta #F rotation angles
/// \return #F values; the face is feasible for problem (10) iff its value is > 0
Eigen::VectorXd convexified_sigma(const Eigen::MatrixXd& P, const Eigen::VectorXd& theta);

/// Rotation angles of the polar decompositions, theta_j = atan2(beta_j, alpha_j) (Algorithm 2).
/// \param P #F by 4 (alpha, beta, gamma, delta)
Eigen::VectorXd polar_rotations(const Eigen::MatrixXd& P);

/// Per-face distortion E_j = h(Sigma_j, 1/sigma_j) of eq. (1); +infinity for a flipped or degenerate face.
/// \param P #F by 4 (alpha, beta, gamma, delta)
Eigen::VectorXd face_distortion(const Eigen::MatrixXd& P, DistortionCombiner h);

/// The energy (8): (sum_j E_j^p |t_j|)^(1/p), and max_j E_j for p = infinity.
/// \param E #F per-face distortions
/// \param area #F face areas
/// \param p 2 or std::numeric_limits<double>::infinity() (any p >= 1 is accepted)
double distortion_energy(const Eigen::VectorXd& E, const Eigen::VectorXd& area, double p);

/// The reported distortion of §4.2: per face max(Sigma, 1/sigma) (eq. (1) with h from eq. (2)).
inline Eigen::VectorXd true_distortion(const Eigen::MatrixXd& P) {
  return face_distortion(P, DistortionCombiner::kMax);
}

}  // namespace liftmap
