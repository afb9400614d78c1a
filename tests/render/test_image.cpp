#include "render/image.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.h"
#include "render/png_util.h"

namespace liftmap {
namespace {

TEST(RenderImage, FillSetAndBlend) {
  Image image(4, 3, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(image.rgb.size(), 36u);
  EXPECT_EQ(image.pixel(3, 2)[0], 255);
  image.set(1, 1, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(image.pixel(1, 1)[2], 255);
  EXPECT_EQ(image.pixel(1, 1)[0], 0);
  image.set(-1, 7, Eigen::Vector3d(0, 0, 0));  // ignored
  image.blend(0, 0, Eigen::Vector3d(0, 0, 0), 0.5);
  EXPECT_NEAR(image.pixel(0, 0)[0], 128, 1);
}

TEST(RenderImage, DownsampleAveragesBlocks) {
  Image image(4, 2, Eigen::Vector3d::Zero());
  image.set(0, 0, Eigen::Vector3d::Ones());
  image.set(1, 1, Eigen::Vector3d::Ones());
  const Image small = downsample(image, 2);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_NEAR(small.pixel(0, 0)[0], 128, 1);
  EXPECT_EQ(small.pixel(1, 0)[0], 0);
}

TEST(RenderImage, PasteClips) {
  Image dst(3, 3, Eigen::Vector3d::Zero());
  paste(dst, Image(2, 2, Eigen::Vector3d::Ones()), 2, 2);
  EXPECT_EQ(dst.pixel(2, 2)[0], 255);
  EXPECT_EQ(dst.pixel(1, 1)[0], 0);
}

TEST(RenderWritePng, WritesReadableHeader) {
  const std::string path = testing::output_path("test_image.png");
  Image image(37, 21, Eigen::Vector3d(0.2, 0.4, 0.6));
  write_png(path, image);
  const testing::PngHeader h = testing::read_png_header(path);
  EXPECT_TRUE(h.signature_ok);
  EXPECT_TRUE(h.ihdr_ok);
  EXPECT_EQ(h.width, 37u);
  EXPECT_EQ(h.height, 21u);
}

TEST(RenderWritePng, FailuresAreTyped) {
  EXPECT_THROW(write_png("/nonexistent-dir/x.png", Image(2, 2)), IoError);
  EXPECT_THROW(write_png(testing::output_path("empty.png"), Image()), InvalidInputError);
}

TEST(RenderImage, ReadImageReadsBackWhatWritePngWrote) {
  Image image(5, 3, Eigen::Vector3d(0.2, 0.4, 0.6));
  image.set(4, 2, Eigen::Vector3d(1, 0, 0.5));
  const std::string path = testing::output_path("read_back.png");
  write_png(path, image);
  const Image back = read_image(path);
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.rgb, image.rgb) << "PNG is lossless: every byte comes back";
}

TEST(RenderImage, ReadImageNamesTheFile) {
  const std::string missing = testing::output_path("no_such_image.png");
  try {
    read_image(missing);
    FAIL() << "a missing file must throw";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  const std::string text = testing::output_path("not_an_image.png");
  std::ofstream(text) << "not a PNG\n";
  try {
    read_image(text);
    FAIL() << "a text file must throw";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read the image"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace liftmap
