#include "render/colour_maps.h"

#include <gtest/gtest.h>

namespace liftmap {
namespace {

TEST(RenderColourMaps, CheckerAlternatesAndStaysInRange) {
  const CheckerTexture texture = make_checker_texture((Eigen::MatrixXd(2, 3) << 0, 0, 0, 1, 1, 1).finished(), 10);
  const double cell = 0.1;
  const Eigen::Vector3d a = texture(Eigen::Vector3d(0.45, 0.55, 0.55));
  const Eigen::Vector3d b = texture(Eigen::Vector3d(0.45 + cell, 0.55, 0.55));
  // Neighbouring cubes differ by the checker contrast, far more than the smooth hue changes over one cube.
  EXPECT_GT(std::abs(a.sum() - b.sum()), 0.2);
  const Eigen::MatrixXd C = evaluate_texture(texture, Eigen::MatrixXd::Random(200, 3) * 2.0);
  EXPECT_GE(C.minCoeff(), 0.0);
  EXPECT_LE(C.maxCoeff(), 1.0);
}

TEST(RenderColourMaps, SequentialIsOrderedByLightness) {
  auto luminance = [](const Eigen::Vector3d& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
  double previous = -1;
  for (int i = 0; i <= 50; ++i) {
    const double l = luminance(sequential_colour(i / 50.0));
    EXPECT_GT(l, previous);
    previous = l;
  }
  EXPECT_EQ(sequential_colour(-3.0), sequential_colour(0.0));
  EXPECT_EQ(sequential_colour(7.0), sequential_colour(1.0));
  const Eigen::MatrixXd C = sequential_colours(Eigen::Vector3d(1.0, 2.0, 3.0), 1.0, 3.0);
  EXPECT_EQ(C.row(0).transpose(), sequential_colour(0.0));
  EXPECT_EQ(C.row(2).transpose(), sequential_colour(1.0));
}

TEST(RenderColourMaps, LandmarkColoursAreDistinct) {
  const Eigen::MatrixXd C = landmark_colours(20);
  ASSERT_EQ(C.rows(), 20);
  for (int i = 0; i < 20; ++i)
    for (int j = i + 1; j < 20; ++j) EXPECT_GT((C.row(i) - C.row(j)).norm(), 0.05) << i << " " << j;
}

}  // namespace
}  // namespace liftmap
