#include "lift/exact_predicates.h"

#include <gtest/gtest.h>

#include <cmath>

namespace liftmap {
namespace {

using Eigen::Vector2d;

// Exact reference for points whose coordinates are multiples of 2^-53 below 2^5: scaled to integers the
// determinant fits in 128 bits.
__extension__ typedef __int128 Int128;

int reference_orient(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  auto n = [](double x) { return static_cast<Int128>(std::ldexp(x, 53)); };
  const Int128 d = (n(b.x()) - n(a.x())) * (n(c.y()) - n(a.y())) - (n(b.y()) - n(a.y())) * (n(c.x()) - n(a.x()));
  return d > 0 ? 1 : (d < 0 ? -1 : 0);
}

TEST(LiftExactPredicates, OrientSigns) {
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(orient2d({0, 0}, {1, 1}, {3, 3}), 0);
  EXPECT_EQ(orient2d({1, 1}, {1, 1}, {2, 5}), 0);
}

// The classic near-degenerate configuration (Kettner et al., "Classroom examples of robustness problems"):
// naive floating point gets signs wrong and inconsistent; the exact predicate must match the integer reference
// and be consistent under permutation.
TEST(LiftExactPredicates, NearCollinearMatchesExactReference) {
  const Vector2d q(12, 12);
  const Vector2d r(24, 24);
  int zeros = 0;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      const Vector2d p(0.5 + std::ldexp(i, -53), 0.5 + std::ldexp(j, -53));
      const int o = orient2d(p, q, r);
      ASSERT_EQ(o, reference_orient(p, q, r)) << i << " " << j;
      ASSERT_EQ(orient2d(q, r, p), o);
      ASSERT_EQ(orient2d(r, p, q), o);
      ASSERT_EQ(orient2d(q, p, r), -o);
      zeros += o == 0;
    }
  }
  EXPECT_EQ(zeros, 64);  // exactly the diagonal i == j is collinear
}

TEST(LiftExactPredicates, CompareXyOrdersCollinearPoints) {
  EXPECT_EQ(compare_xy({0, 0}, {0, 0}), 0);
  EXPECT_EQ(compare_xy({0, 1}, {0, 2}), -1);
  EXPECT_EQ(compare_xy({1, -5}, {0, 7}), 1);
  // Along a line of negative slope, x order is the order along the line.
  EXPECT_EQ(compare_xy({0, 3}, {1, 2}), -1);
}

TEST(LiftExactPredicates, LocateInTriangle) {
  const Vector2d a(0, 0), b(4, 0), c(0, 4);
  using K = TriangleLocation::Kind;
  EXPECT_EQ(locate_in_triangle(a, b, c, {1, 1}).kind, K::kInside);
  EXPECT_EQ(locate_in_triangle(a, b, c, {5, 5}).kind, K::kOutside);
  EXPECT_EQ(locate_in_triangle(a, b, c, {-1, 1}).kind, K::kOutside);
  auto on = [&](Vector2d p, K kind, int index) {
    const TriangleLocation loc = locate_in_triangle(a, b, c, p);
    EXPECT_EQ(loc.kind, kind) << p.transpose();
    EXPECT_EQ(loc.index, index) << p.transpose();
  };
  on({2, 0}, K::kOnEdge, 0);
  on({2, 2}, K::kOnEdge, 1);
  on({0, 2}, K::kOnEdge, 2);
  on({0, 0}, K::kAtVertex, 0);
  on({4, 0}, K::kAtVertex, 1);
  on({0, 4}, K::kAtVertex, 2);
  // On the line of an edge but beyond the triangle.
  on({6, 0}, K::kOutside, -1);
}

}  // namespace
}  // namespace liftmap
