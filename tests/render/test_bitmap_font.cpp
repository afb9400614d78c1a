#include "render/bitmap_font.h"

#include <gtest/gtest.h>

#include "render/png_util.h"

namespace liftmap {
namespace {

TEST(RenderBitmapFont, WidthScalesWithLength) {
  EXPECT_EQ(text_width("", 2), 0);
  EXPECT_EQ(text_width("A", 1), kGlyphWidth);
  EXPECT_EQ(text_width("AB", 2), 2 * (kGlyphAdvance + kGlyphWidth));
}

TEST(RenderBitmapFont, GlyphsStayInTheirCell) {
  const std::string all = "0123456789.:-%()/= abcxyz ABCXYZ gjpqy";
  Image image(text_width(all, 2) + 20, kGlyphHeight * 2 + 20, Eigen::Vector3d::Ones());
  draw_text(image, 10, 10, all, Eigen::Vector3d::Zero(), 2);
  int inked = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (image.pixel(x, y)[0] > 128) continue;
      ++inked;
      EXPECT_GE(x, 10);
      EXPECT_LT(x, 10 + text_width(all, 2));
      EXPECT_GE(y, 10);
      EXPECT_LT(y, 10 + kGlyphHeight * 2);
    }
  EXPECT_GT(inked, 100);
  // Every printable glyph but the space draws something.
  for (char c = 33; c < 127; ++c) {
    Image one(20, 30, Eigen::Vector3d::Ones());
    draw_text(one, 2, 2, std::string(1, c), Eigen::Vector3d::Zero(), 1);
    EXPECT_GT(testing::count_non_background(one, Eigen::Vector3d::Ones()), 0) << "glyph '" << c << "'";
  }
}

}  // namespace
}  // namespace liftmap
