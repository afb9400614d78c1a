#include "core/total_area.h"

#include <Eigen/Geometry>

namespace liftmap {

double total_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const auto row3 = [&](int i) -> Eigen::Vector3d { return V.row(i).transpose(); };
  double a = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    a += 0.5 * (row3(F(f, 1)) - row3(F(f, 0))).cross(row3(F(f, 2)) - row3(F(f, 0))).norm();
  }
  return a;
}

}  // namespace liftmap
