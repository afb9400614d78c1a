#pragma once
/// Exact 2D predicates for the path-lifting walk (paper §3.2, Algorithm 1). Every in/out/on decision of the
/// walk goes through these, so degenerate configurations (a path through a vertex, along an edge, ending on an
/// edge) are decided consistently. Coordinates are taken as exact doubles; the arithmetic is CGAL's filtered
/// exact kernel, hidden in the .cpp.

#include <Eigen/Core>

namespace liftmap {

/// Sign of the signed area of the triangle (a, b, c), computed exactly.
/// \return +1 if (a, b, c) is counter-clockwise (c lies left of the directed line a -> b), -1 if clockwise,
///         0 if the three points are collinear (including coincident points).
/// \pre finite coordinates.
int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// Lexicographic comparison of (x, y): -1 if a < b, 0 if a == b, +1 if a > b. Exact.
/// Restricted to a line, this order is the order along one of the line's two directions, so it orders
/// collinear points exactly (used to tell "ahead" from "behind" along a walk).
int compare_xy(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// Where a point lies with respect to a closed triangle, decided exactly.
struct TriangleLocation {
  enum class Kind { kOutside, kInside, kOnEdge, kAtVertex };
  Kind kind = Kind::kOutside;
  /// kOnEdge: the edge from corner `index` to corner `index + 1 (mod 3)`; kAtVertex: the corner; else -1.
  int index = -1;
};

/// Locates `p` in the triangle with corners `c0, c1, c2`.
/// \pre the triangle is non-degenerate and counter-clockwise (`orient2d(c0, c1, c2) > 0`).
TriangleLocation locate_in_triangle(const Eigen::Vector2d& c0, const Eigen::Vector2d& c1, const Eigen::Vector2d& c2,
                                    const Eigen::Vector2d& p);

}  // namespace liftmap
