#pragma once
/// The point of a triangle mesh nearest to a point of R^3 (a landmark given by its coordinates).

#include <Eigen/Core>
#include <array>
#include <memory>

namespace liftmap {

/// A point of a mesh given as a face and barycentric coordinates, and its distance to the point it was found for.
struct NearestSurfacePoint {
  int face = -1;                        ///< row of F
  std::array<double, 3> bary{0, 0, 0};  ///< weights of F.row(face), summing to 1; exact zeros for the corners of
                                        ///< the face that the nearest point does not need (on an edge or a vertex)
  double distance = 0;                  ///< from the point asked for
};

/// Finds nearest surface points of one mesh; the search structure (an AABB tree) is built once, by the
/// constructor, and answers any number of queries.
class SurfaceLocator {
 public:
  /// \param V #V by 3 positions; F #F by 3 faces. Both are copied.
  /// \pre F has at least one face; its indices are rows of V
  SurfaceLocator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
  ~SurfaceLocator();
  SurfaceLocator(const SurfaceLocator&) = delete;
  SurfaceLocator& operator=(const SurfaceLocator&) = delete;

  /// The point of the mesh nearest to `x` (any of them if several are equally near).
  /// \pre x is finite
  [[nodiscard]] NearestSurfacePoint nearest(const Eigen::Vector3d& x) const;

 private:
  struct Tree;
  Eigen::MatrixXd V_;
  Eigen::MatrixXi F_;
  std::unique_ptr<Tree> tree_;
};

/// The barycentric coordinates of the point of triangle (a, b, c) nearest to x: exact zeros when the nearest point
/// is on a side or at a corner (Ericson, Real-Time Collision Detection, §5.1.5).
std::array<double, 3> nearest_in_triangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

}  // namespace liftmap
