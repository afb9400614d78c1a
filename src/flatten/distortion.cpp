#include "flatten/distortion.h"

#include <cmath>
#include <limits>

namespace liftmap {

Eigen::MatrixXd singular_values(const Eigen::MatrixXd& P) {
  Eigen::MatrixXd S(P.rows(), 2);
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    const double b = std::hypot(P(f, 0), P(f, 1));
    const double c = std::hypot(P(f, 2), P(f, 3));
    S(f, 0) = b + c;
    S(f, 1) = std::abs(b - c);
  }
  return S;
}

Eigen::VectorXd convexified_sigma(const Eigen::MatrixXd& P, const Eigen::VectorXd& theta) {
  Eigen::VectorXd s(P.rows());
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    s(f) = P(f, 0) * std::cos(theta(f)) + P(f, 1) * std::sin(theta(f)) - std::hypot(P(f, 2), P(f, 3));
  }
  return s;
}

Eigen::VectorXd polar_rotations(const Eigen::MatrixXd& P) {
  Eigen::VectorXd theta(P.rows());
  for (Eigen::Index f = 0; f < P.rows(); ++f) theta(f) = std::atan2(P(f, 1), P(f, 0));
  return theta;
}

Eigen::VectorXd face_distortion(const Eigen::MatrixXd& P, DistortionCombiner h) {
  Eigen::VectorXd E(P.rows());
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    const double b = std::hypot(P(f, 0), P(f, 1));
    const double c = std::hypot(P(f, 2), P(f, 3));
    if (!(b > c)) {  // det A = b^2 - c^2 <= 0: flipped or degenerate
      E(f) = std::numeric_limits<double>::infinity();
      continue;
    }
    const double r = b + c;
    const double s = 1.0 / (b - c);
    E(f) = h == DistortionCombiner::kMax ? std::max(r, s) : std::hypot(r, s);
  }
  return E;
}

double distortion_energy(const Eigen::VectorXd& E, const Eigen::VectorXd& area, double p) {
  if (std::isinf(p)) return E.size() > 0 ? E.maxCoeff() : 0.0;
  double sum = 0;
  for (Eigen::Index f = 0; f < E.size(); ++f) sum += std::pow(E(f), p) * area(f);
  return std::pow(sum, 1.0 / p);
}

}  // namespace liftmap
