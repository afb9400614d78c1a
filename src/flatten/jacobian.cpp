#include "flatten/jacobian.h"

#include <Eigen/Geometry>
#include <string>

#include "core/errors.h"

namespace liftmap {

JacobianOperator jacobian_operator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  JacobianOperator op;
  op.G.resize(F.rows(), 6);
  op.area.resize(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0));
    const Eigen::Vector3d e1 = V.row(F(f, 1)).transpose() - p0;
    const Eigen::Vector3d e2 = V.row(F(f, 2)).transpose() - p0;
    const double area2 = e1.cross(e2).norm();
    const double l1 = e1.norm();
    if (!(area2 > 0) || !(l1 > 0)) {
      throw InvalidInputError("jacobian_operator: face " + std::to_string(f) + " is degenerate");
    }
    // Local frame: x along e1, y in the plane, orthogonal. Corners: (0,0), (l1,0), (x2,y2).
    const Eigen::Vector3d ex = e1 / l1;
    const double x2 = e2.dot(ex);
    const double y2 = area2 / l1;
    // [u1-u0, u2-u0] = A [x1-x0, x2-x0] => A = E M^{-1}, M = [[l1, x2], [0, y2]].
    // A = du1 m1^T + du2 m2^T with m1, m2 the rows of M^{-1} = [[1/l1, -x2/(l1 y2)], [0, 1/y2]]: those rows are
    // the gradients of hat functions 1 and 2; hat 0 takes minus their sum.
    const Eigen::Vector2d g1(1.0 / l1, -x2 / (l1 * y2));
    const Eigen::Vector2d g2(0.0, 1.0 / y2);
    const Eigen::Vector2d g0 = -g1 - g2;
    op.G.row(f) << g0.x(), g0.y(), g1.x(), g1.y(), g2.x(), g2.y();
    op.area(f) = 0.5 * area2;
  }
  return op;
}

Eigen::Matrix<double, 4, 6> similarity_map(const Eigen::Matrix<double, 1, 6>& g) {
  Eigen::Matrix<double, 4, 6> S;
  for (int k = 0; k < 3; ++k) {
    const double gx = 0.5 * g(2 * k);
    const double gy = 0.5 * g(2 * k + 1);
    // Columns: u_k (x image), v_k (y image). a11 = u.gx, a12 = u.gy, a21 = v.gx, a22 = v.gy.
    S.col(2 * k) << gx, -gy, gx, gy;
    S.col(2 * k + 1) << gy, gx, -gy, gx;
  }
  return S;
}

Eigen::MatrixXd similarity_parts(const JacobianOperator& op, const Eigen::MatrixXi& F, const Eigen::MatrixXd& U) {
  Eigen::MatrixXd P(F.rows(), 4);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Matrix<double, 6, 1> u;
    for (int k = 0; k < 3; ++k) u.segment<2>(2 * k) = U.row(F(f, k)).transpose();
    P.row(f) = (similarity_map(op.G.row(f)) * u).transpose();
  }
  return P;
}

}  // namespace liftmap
