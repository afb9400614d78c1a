#include "render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors.h"

namespace liftmap {
namespace {

struct ViewFrame {
  Eigen::Vector3d right, up, forward;
};

ViewFrame view_frame(const Camera& camera) {
  ViewFrame frame;
  frame.forward = (camera.target - camera.eye).normalized();
  frame.right = frame.forward.cross(camera.up).normalized();
  frame.up = frame.right.cross(frame.forward);
  return frame;
}

double tan_half_fov(const Camera& camera) { return std::tan(0.5 * camera.fov_y_degrees * std::numbers::pi / 180.0); }

}  // namespace

ProjectedPoint project(const Camera& camera, double aspect, const Eigen::Vector3d& p) {
  const ViewFrame frame = view_frame(camera);
  const Eigen::Vector3d d = p - camera.eye;
  const double x = frame.right.dot(d), y = frame.up.dot(d), z = frame.forward.dot(d);
  ProjectedPoint out;
  out.depth = z;
  const double h = camera.projection == Projection::kPerspective ? z * tan_half_fov(camera) : camera.half_height;
  out.ndc = Eigen::Vector2d(x / (h * aspect), y / h);
  return out;
}

double half_height_at_depth(const Camera& camera, double depth) {
  return camera.projection == Projection::kPerspective ? depth * tan_half_fov(camera) : camera.half_height;
}

Sphere bounding_sphere(const Eigen::MatrixXd& V) {
  if (V.rows() == 0 || V.cols() != 3) throw InvalidInputError("bounding_sphere: expected a non-empty #V by 3 matrix");
  Sphere s;
  s.center = 0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()).transpose();
  s.radius = (V.rowwise() - s.center.transpose()).rowwise().norm().maxCoeff();
  return s;
}

Camera fit_camera(const Eigen::MatrixXd& V, const Eigen::Vector3d& direction, const Eigen::Vector3d& up, double aspect,
                  Projection projection, double fill) {
  const Sphere sphere = bounding_sphere(V);
  if (direction.norm() == 0.0) throw InvalidInputError("fit_camera: zero viewing direction");
  const Eigen::Vector3d dir = direction.normalized();
  if (up.cross(dir).norm() < 1e-9 * up.norm()) throw InvalidInputError("fit_camera: up is parallel to the direction");
  const double radius = std::max(sphere.radius, 1e-12);

  Camera camera;
  camera.projection = projection;
  camera.up = up;
  camera.target = sphere.center;
  // A narrow field of view keeps perspective foreshortening mild, as in a figure; the eye stays outside the sphere.
  const double distance = projection == Projection::kPerspective
                              ? radius / std::sin(0.5 * camera.fov_y_degrees * std::numbers::pi / 180.0)
                              : 3.0 * radius;
  camera.eye = camera.target - distance * dir;
  camera.half_height = radius;

  // Centre the projected bounding box and scale it to `fill`; perspective needs a few rounds since moving the
  // window changes the projection slightly.
  for (int round = 0; round < 4; ++round) {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d hi = -lo;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
      const Eigen::Vector2d q = project(camera, aspect, V.row(i).transpose()).ndc;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const Eigen::Vector2d mid = 0.5 * (lo + hi);
    const double scale = std::max(0.5 * (hi.x() - lo.x()), 0.5 * (hi.y() - lo.y())) / fill;
    const ViewFrame frame = view_frame(camera);
    const double depth = (camera.target - camera.eye).norm();
    const double h = half_height_at_depth(camera, depth);
    const Eigen::Vector3d shift = frame.right * (mid.x() * h * aspect) + frame.up * (mid.y() * h);
    camera.target += shift;
    camera.eye += shift;
    if (projection == Projection::kPerspective) {
      const double t = tan_half_fov(camera) * scale;
      camera.fov_y_degrees = 2.0 * std::atan(t) * 180.0 / std::numbers::pi;
    } else {
      camera.half_height *= scale;
    }
  }
  return camera;
}

}  // namespace liftmap
