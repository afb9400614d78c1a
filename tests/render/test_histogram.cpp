#include "render/histogram.h"

#include <gtest/gtest.h>

#include <random>

#include "core/errors.h"
#include "render/png_util.h"

namespace liftmap {
namespace {

TEST(RenderHistogram, WritesPictureWithBarsAndMean) {
  std::mt19937 rng(7);
  std::lognormal_distribution<double> excess(-2.0, 0.6);
  std::uniform_real_distribution<double> area(0.5, 2.0);
  Eigen::VectorXd values(5000), weights(5000);
  for (int i = 0; i < 5000; ++i) {
    values[i] = 1.0 + excess(rng);
    weights[i] = area(rng);
  }
  HistogramOptions options;
  const std::string path = testing::output_path("histogram.png");
  render_histogram_png(values, weights, path, options);
  const testing::PngHeader header = testing::read_png_header(path);
  EXPECT_TRUE(header.signature_ok);
  EXPECT_TRUE(header.ihdr_ok);
  EXPECT_EQ(header.width, static_cast<std::uint32_t>(options.width));
  EXPECT_EQ(header.height, static_cast<std::uint32_t>(options.height));

  const Image image = render_histogram(values, weights, options);
  const int inked = testing::count_non_background(image, options.background);
  EXPECT_GT(inked, options.width * options.height / 20);
  EXPECT_LT(inked, options.width * options.height / 2);
  int bar = 0, mean = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Eigen::Vector3d c = image.colour(x, y);
      bar += (c - options.bar_colour).norm() < 0.02;
      mean += (c - options.mean_colour).norm() < 0.02;
    }
  EXPECT_GT(bar, 2000);
  EXPECT_GT(mean, 200);
}

TEST(RenderHistogram, HandlesOutliersAndEqualWeights) {
  Eigen::VectorXd values(4);
  values << 1.0, 1.2, 50.0, std::numeric_limits<double>::infinity();
  HistogramOptions options;
  options.x_max = 2.0;
  const Image image = render_histogram(values, Eigen::VectorXd(), options);
  EXPECT_EQ(image.width, options.width);
}

TEST(RenderHistogram, RejectsBadInput) {
  const Eigen::VectorXd values = Eigen::VectorXd::Constant(3, 1.5);
  EXPECT_THROW(render_histogram(values, Eigen::VectorXd::Ones(2)), InvalidInputError);
  EXPECT_THROW(render_histogram(values, -Eigen::VectorXd::Ones(3)), InvalidInputError);
  EXPECT_THROW(render_histogram(values, Eigen::VectorXd::Zero(3)), InvalidInputError);
  EXPECT_THROW(render_histogram(Eigen::VectorXd(), Eigen::VectorXd()), InvalidInputError);
}

}  // namespace
}  // namespace liftmap
