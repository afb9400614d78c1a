#include "render/text.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "render/png_util.h"

namespace liftmap {
namespace {

// Black text on white: a pixel is ink if it is darker than mid-grey.
bool ink(const Image& image, int x, int y) { return image.pixel(x, y)[0] < 128; }

Image drawn(int width, int height, int x, int y, const std::string& text, int scale) {
  Image image(width, height, Eigen::Vector3d::Ones());
  draw_text(image, x, y, text, Eigen::Vector3d::Zero(), scale);
  return image;
}

TEST(RenderText, WidthIsTheSumOfAdvancesLessTheLastGap) {
  EXPECT_EQ(text_width("", 2), 0);
  EXPECT_EQ(text_width("0", 1), 4);                     // digits: 4 of ink in an advance of 6
  EXPECT_EQ(text_width("00", 2), 2 * 10);               // 6 + 6 - 2
  EXPECT_LT(text_width("ii", 1), text_width("mm", 1));  // proportional
  const std::string label = "mean 0.527";
  EXPECT_EQ(text_width(label, 3), 3 * text_width(label, 1));
  EXPECT_EQ(text_width("a\nb", 1), text_width("a?b", 1));
}

TEST(RenderText, InkFillsItsBoxAndStaysInIt) {
  const std::string all = "0123456789.:-%()/= abcxyz ABCXYZ gjpqy";
  const int s = 2, w = text_width(all, s), h = kTextHeight * s;
  const Image image = drawn(w + 20, h + 20, 10, 10, all, s);
  int inked = 0, x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (ink(image, x, y)) {
        ++inked;
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  EXPECT_GT(inked, 500);
  // '0' starts at the left edge, 'y' ends at the right edge, capitals reach the top and descenders the bottom.
  EXPECT_EQ(x0, 10);
  EXPECT_EQ(x1, 10 + w - 1);
  EXPECT_EQ(y0, 10);
  EXPECT_EQ(y1, 10 + h - 1);
  // Nothing but descenders below the baseline.
  const Image caps = drawn(w + 20, h + 20, 10, 10, "0123456789 ABCXYZ abcxz", s);
  for (int y = 10 + kTextAscent * s; y < caps.height; ++y)
    for (int x = 0; x < caps.width; ++x) EXPECT_FALSE(ink(caps, x, y)) << x << ", " << y;
}

TEST(RenderText, EveryGlyphButTheSpaceDrawsSomething) {
  for (char c = 33; c < 127; ++c)
    EXPECT_GT(testing::count_non_background(drawn(20, 30, 2, 2, std::string(1, c), 1), Eigen::Vector3d::Ones()), 0)
        << "glyph '" << c << "'";
  for (const std::string text : {"", " ", "   "})
    EXPECT_EQ(testing::count_non_background(drawn(40, 30, 2, 2, text, 2), Eigen::Vector3d::Ones()), 0)
        << "'" << text << "'";
}

TEST(RenderText, NonPrintableCharactersAreQuestionMarks) {
  const std::string odd = "a\nb\x01\x7f\xe9";
  EXPECT_EQ(drawn(80, 30, 2, 2, odd, 2).rgb, drawn(80, 30, 2, 2, "a?b???", 2).rgb);
}

TEST(RenderText, EachFontPixelIsAScaleByScaleBlock) {
  const std::string text = "Ag%";
  const Image one = drawn(40, 20, 0, 0, text, 1), three = drawn(120, 60, 0, 0, text, 3);
  for (int y = 0; y < three.height; ++y)
    for (int x = 0; x < three.width; ++x) ASSERT_EQ(ink(three, x, y), ink(one, x / 3, y / 3)) << x << ", " << y;
}

TEST(RenderText, ClippedAtTheImageEdges) {
  // Text over each edge of a small image draws exactly the part of it that a large image shows there.
  const std::string text = "Clip gjpqy 100%";
  const int s = 2, w = 40, h = 14, pad = 400;
  for (const auto& [x, y] : {std::pair{-15, -6}, std::pair{20, 5}, std::pair{-300, 0}, std::pair{5, -20},
                             std::pair{50, 0}, std::pair{0, 30}}) {
    const Image small = drawn(w, h, x, y, text, s), large = drawn(w + 2 * pad, h + 2 * pad, x + pad, y + pad, text, s);
    for (int yy = 0; yy < h; ++yy)
      for (int xx = 0; xx < w; ++xx)
        ASSERT_EQ(ink(small, xx, yy), ink(large, xx + pad, yy + pad)) << "text at " << x << ", " << y;
  }
}

}  // namespace
}  // namespace liftmap
