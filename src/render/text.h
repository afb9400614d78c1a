#pragma once
/// Text for the labels and axes of the figures: the glyphs of stb_easy_font (printable ASCII, proportional, made of
/// axis-aligned strokes on a grid of font pixels), each font pixel drawn as a scale by scale block.

#include <Eigen/Core>
#include <string>

#include "render/image.h"

namespace liftmap {

/// Rows of font pixels in a line of text: 7 above the baseline (capitals, digits) plus 2 below (the descenders of
/// g, j, p, q, y and the comma).
inline constexpr int kTextAscent = 7;
inline constexpr int kTextHeight = 9;

/// Width in image pixels of `text` drawn at `scale`: from the left edge of its first glyph to the right edge of
/// its last one (the sum of the glyph advances less the 2-pixel gap after the last glyph); 0 for an empty string.
/// Characters outside printable ASCII count as '?'.
/// \pre scale >= 1
int text_width(const std::string& text, int scale = 2);

/// Draws `text` in `colour` in the box of text_width(text, scale) by kTextHeight * scale image pixels whose top-left
/// corner is (x, y); characters outside printable ASCII (line breaks included) are drawn as '?'. Pixels outside the
/// image are clipped.
/// \pre scale >= 1
void draw_text(Image& image, int x, int y, const std::string& text, const Eigen::Vector3d& colour, int scale = 2);

}  // namespace liftmap
