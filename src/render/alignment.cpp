#include "render/alignment.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "core/errors.h"

namespace liftmap {

Eigen::MatrixXd SimilarityTransform::apply(const Eigen::MatrixXd& P) const {
  return ((scale * P * R.transpose()).rowwise() + t.transpose()).eval();
}

SimilarityTransform align_similarity(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q) {
  if (P.cols() != 3 || Q.cols() != 3 || P.rows() != Q.rows())
    throw InvalidInputError("align_similarity: expected two #L by 3 matrices with the same number of rows");
  if (P.rows() < 2) throw InvalidInputError("align_similarity: at least 2 corresponding points are needed");
  // Eigen::umeyama divides by the source points' variance: reject coincident points before it yields inf or NaN.
  if ((Q.rowwise() - Q.colwise().mean()).squaredNorm() <= 0.0)
    throw InvalidInputError("align_similarity: the source points all coincide");

  // umeyama takes one point per column and returns the 4 by 4 homogeneous matrix [scale R, t; 0, 1].
  const Eigen::Matrix4d T = Eigen::umeyama(Q.transpose(), P.transpose(), true);
  SimilarityTransform out;
  out.scale = T.topLeftCorner<3, 3>().col(0).norm();  // every column of scale R has length scale
  // A zero scale (P's points coincide, or are uncorrelated with Q's) leaves R undetermined: keep the identity.
  if (out.scale > 0.0) out.R = T.topLeftCorner<3, 3>() / out.scale;
  out.t = T.topRightCorner<3, 1>();
  return out;
}

ViewDirection default_view(const Eigen::MatrixXd& V, const Eigen::MatrixXd& landmarks) {
  if (V.rows() == 0 || V.cols() != 3) throw InvalidInputError("default_view: V must be a non-empty #V by 3 matrix");
  if (landmarks.rows() > 0 && landmarks.cols() != 3) throw InvalidInputError("default_view: landmarks must be #L by 3");
  const Eigen::RowVector3d centroid = V.colwise().mean();
  const Eigen::MatrixXd V0 = V.rowwise() - centroid;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(V0.transpose() * V0);  // ascending eigenvalues
  Eigen::Vector3d side = pca.eigenvectors().col(0);
  // Look from the side the landmarks are on: the eye is at -direction, so direction points away from them.
  if (landmarks.rows() > 0 && (landmarks.colwise().mean() - centroid).dot(side.transpose()) < 0) side = -side;
  const Eigen::Vector3d direction0 = -side;

  Eigen::Vector3d up(0.0, 1.0, 0.0);
  if (std::abs(up.dot(direction0)) > 0.9) up = pca.eigenvectors().col(2);
  up = (up - up.dot(direction0) * direction0).normalized();

  const double deg = std::numbers::pi / 180.0;
  const Eigen::Vector3d turned = Eigen::AngleAxisd(30.0 * deg, up) * direction0;
  const Eigen::Vector3d axis = turned.cross(up).normalized();
  ViewDirection view;
  view.direction = (Eigen::AngleAxisd(-15.0 * deg, axis) * turned).normalized();
  view.up = (up - up.dot(view.direction) * view.direction).normalized();
  return view;
}

}  // namespace liftmap
