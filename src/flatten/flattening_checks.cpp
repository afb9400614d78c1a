#include "flatten/flattening_checks.h"

#include <cmath>

namespace liftmap {

Eigen::VectorXd signed_double_areas(const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  Eigen::VectorXd a(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d e1 = U.row(F(f, 1)) - U.row(F(f, 0));
    const Eigen::Vector2d e2 = U.row(F(f, 2)) - U.row(F(f, 0));
    a(f) = e1.x() * e2.y() - e1.y() * e2.x();
  }
  return a;
}

Eigen::VectorXd angle_sums(const Mesh& mesh, const Eigen::MatrixXd& U) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto fv = mesh.face_vertices(FaceId(f));
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d p = U.row(fv[c].idx);
      const Eigen::Vector2d a = U.row(fv[(c + 1) % 3].idx).transpose() - p;
      const Eigen::Vector2d b = U.row(fv[(c + 2) % 3].idx).transpose() - p;
      sums(fv[c].idx) += std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
    }
  }
  return sums;
}

}  // namespace liftmap
