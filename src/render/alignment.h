#pragma once
/// Matching viewpoints for two meshes: a similarity transform that brings B's landmarks onto A's, and a default
/// view of A that shows its landmarks, so that both meshes are drawn with one camera direction.

#include <Eigen/Core>

namespace liftmap {

/// x -> scale * R * x + t, with R a proper rotation (det +1).
struct SimilarityTransform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  double scale = 1.0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  /// The transform applied to every row of P (#P by 3); returns #P by 3.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& P) const;
};

/// Least-squares similarity transform taking the points Q onto the points P: minimises
/// sum_i |scale R Q_i + t - P_i|^2 over rotations R (det +1, never a reflection), scale >= 0 and t
/// (Umeyama 1991, computed by Eigen::umeyama: SVD of the cross-covariance with the sign of the last singular
/// vector fixed).
/// With fewer than 3 non-collinear points the rotation about their common line is not determined; the result is
/// then one of the minimisers. When the points of P all coincide (more generally, when the cross-covariance
/// vanishes) the minimiser has scale 0, and R is returned as the identity.
/// \param P #L by 3 target points (e.g. landmarks on A)
/// \param Q #L by 3 source points (e.g. the corresponding landmarks on B), #L >= 2
/// \throw InvalidInputError for mismatched shapes, fewer than 2 points or all points of Q coincident
SimilarityTransform align_similarity(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q);

/// A viewing direction (from the eye toward the mesh) and an image up direction, orthonormal.
struct ViewDirection {
  Eigen::Vector3d direction{0.0, 0.0, -1.0};
  Eigen::Vector3d up{0.0, 1.0, 0.0};
};

/// A 3/4 view of a mesh that shows its landmarks: the eye looks along the axis of least spread of the vertices
/// (the side of an animal, the front of a face), from the side where the landmarks lie, turned by 30 degrees
/// about the up axis and raised by 15 degrees. Up is the world +y made orthogonal to the view, or the axis of
/// largest spread when +y is nearly the viewing direction.
/// \param V #V by 3 vertex positions
/// \param landmarks #L by 3 landmark positions (may be empty)
/// \throw InvalidInputError for an empty V or wrong shapes
ViewDirection default_view(const Eigen::MatrixXd& V, const Eigen::MatrixXd& landmarks);

}  // namespace liftmap
