#include "lift/exact_predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cassert>

namespace liftmap {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

Point to_cgal(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }
}  // namespace

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return static_cast<int>(CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c)));
}

int compare_xy(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  if (a.x() != b.x()) return a.x() < b.x() ? -1 : 1;
  if (a.y() != b.y()) return a.y() < b.y() ? -1 : 1;
  return 0;
}

TriangleLocation locate_in_triangle(const Eigen::Vector2d& c0, const Eigen::Vector2d& c1, const Eigen::Vector2d& c2,
                                    const Eigen::Vector2d& p) {
  assert(orient2d(c0, c1, c2) > 0);
  const int o[3] = {orient2d(c0, c1, p), orient2d(c1, c2, p), orient2d(c2, c0, p)};
  if (o[0] < 0 || o[1] < 0 || o[2] < 0) return {TriangleLocation::Kind::kOutside, -1};
  const int zeros = (o[0] == 0) + (o[1] == 0) + (o[2] == 0);
  if (zeros == 0) return {TriangleLocation::Kind::kInside, -1};
  if (zeros == 1) {
    for (int k = 0; k < 3; ++k) {
      if (o[k] == 0) return {TriangleLocation::Kind::kOnEdge, k};
    }
  }
  // Two edges through p: p is their common corner (edge k-1 and edge k meet at corner k).
  for (int k = 0; k < 3; ++k) {
    if (o[k] == 0 && o[(k + 2) % 3] == 0) return {TriangleLocation::Kind::kAtVertex, k};
  }
  assert(false && "a non-degenerate triangle has no point on all three edge lines");
  return {TriangleLocation::Kind::kOutside, -1};
}

}  // namespace liftmap
