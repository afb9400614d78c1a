#pragma once
/// Cameras for the headless renderer: look-at pose, orthographic or perspective projection, and framing a mesh.

#include <Eigen/Core>

namespace liftmap {

enum class Projection { kOrthographic, kPerspective };

/// A look-at camera. The image's vertical axis is `up` made orthogonal to the viewing direction.
struct Camera {
  Eigen::Vector3d eye{0.0, 0.0, 3.0};     ///< camera position
  Eigen::Vector3d target{0.0, 0.0, 0.0};  ///< point at the centre of the image
  Eigen::Vector3d up{0.0, 1.0, 0.0};      ///< approximate up direction, not parallel to target - eye
  Projection projection = Projection::kPerspective;
  double fov_y_degrees = 25.0;  ///< vertical field of view (perspective)
  double half_height = 1.0;     ///< half the visible height, in world units (orthographic)
};

/// Where a point lands in the image of a camera.
struct ProjectedPoint {
  Eigen::Vector2d ndc;  ///< normalised device coordinates: x right, y up, the image is [-1,1]^2
  double depth = 0;     ///< distance in front of the eye along the viewing direction (> 0 is visible)
};

/// Projects a point through `camera` into an image of aspect ratio `aspect` (width / height).
/// Points with depth <= 0 (behind the eye) get meaningless ndc under perspective projection.
ProjectedPoint project(const Camera& camera, double aspect, const Eigen::Vector3d& p);

/// World-space size of one unit of ndc y at a given depth (half the visible height at that depth).
double half_height_at_depth(const Camera& camera, double depth);

/// A sphere: centre and radius.
struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;
};

/// A sphere containing all rows of V: the centre of the bounding box and the largest distance to it.
/// \param V #V by 3 points, #V >= 1
/// \throw InvalidInputError if V is empty or not #V by 3
Sphere bounding_sphere(const Eigen::MatrixXd& V);

/// A camera looking along `direction` that frames all points of V: the eye is outside V's bounding sphere, and
/// the projected points fill `fill` of the image's width or height (whichever is tighter), centred.
/// \param V #V by 3 points to frame, #V >= 1
/// \param direction viewing direction (from the eye toward the mesh), non-zero
/// \param up approximate up direction of the image, not parallel to `direction`
/// \param aspect image width / height
/// \param fill fraction of the image the framed points span, in (0, 1]
/// \throw InvalidInputError for empty V, zero direction or up parallel to direction
Camera fit_camera(const Eigen::MatrixXd& V, const Eigen::Vector3d& direction, const Eigen::Vector3d& up, double aspect,
                  Projection projection = Projection::kPerspective, double fill = 0.9);

}  // namespace liftmap
