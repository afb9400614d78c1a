#include "lift/format_point.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace liftmap {
namespace {

TEST(LiftFormatPoint, SeventeenDigitsRoundTrip) {
  EXPECT_EQ(format_point(Eigen::Vector2d(0.1, -2.0)), "(0.10000000000000001, -2)");
  const Eigen::Vector2d p(1.0 / 3.0, 1e-300);
  const std::string s = format_point(p);
  double x = 0, y = 0;
  ASSERT_EQ(std::sscanf(s.c_str(), "(%lf, %lf)", &x, &y), 2);
  EXPECT_EQ(x, p.x());
  EXPECT_EQ(y, p.y());
}

}  // namespace
}  // namespace liftmap
