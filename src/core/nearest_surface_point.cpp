#include "core/nearest_surface_point.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

namespace liftmap {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Eigen::MatrixXd& V, int v) { return {V(v, 0), V(v, 1), V(v, 2)}; }

}  // namespace

struct SurfaceLocator::Tree {
  std::vector<Triangle> triangles;
  liftmap::Tree tree;
};

SurfaceLocator::SurfaceLocator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F)
    : V_(V), F_(F), tree_(std::make_unique<Tree>()) {
  tree_->triangles.reserve(static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    tree_->triangles.emplace_back(point(V, F(f, 0)), point(V, F(f, 1)), point(V, F(f, 2)));
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.accelerate_distance_queries();
}

SurfaceLocator::~SurfaceLocator() = default;

NearestSurfacePoint SurfaceLocator::nearest(const Eigen::Vector3d& x) const {
  const auto hit = tree_->tree.closest_point_and_primitive(Kernel::Point_3(x.x(), x.y(), x.z()));
  NearestSurfacePoint out;
  out.face = static_cast<int>(hit.second - tree_->triangles.cbegin());
  // The face's own nearest point, so that a point on a side or a corner has exact zeros.
  const auto corner = [&](int k) { return Eigen::Vector3d(V_.row(F_(out.face, k)).transpose()); };
  out.bary = nearest_in_triangle(x, corner(0), corner(1), corner(2));
  const Eigen::Vector3d p = out.bary[0] * corner(0) + out.bary[1] * corner(1) + out.bary[2] * corner(2);
  out.distance = (p - x).norm();
  return out;
}

std::array<double, 3> nearest_in_triangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = x - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = x - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = x - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

}  // namespace liftmap
