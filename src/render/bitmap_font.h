#pragma once
/// A small bitmap font (5 by 7 pixel glyphs with 2 rows of descenders, printable ASCII) for the labels and axes of
/// the figures, drawn without any font library.

#include <Eigen/Core>
#include <string>

#include "render/image.h"

namespace liftmap {

/// Glyph cell size in font pixels: 5 columns plus 1 of spacing, 7 rows above the baseline plus 2 below.
inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphAdvance = 6;
inline constexpr int kGlyphHeight = 9;
inline constexpr int kGlyphAscent = 7;

/// Width in image pixels of `text` drawn at `scale` (each font pixel is a scale by scale block).
int text_width(const std::string& text, int scale = 2);

/// Draws `text` with the top-left corner of its first glyph cell at (x, y); characters outside printable ASCII
/// are drawn as '?'. Pixels outside the image are clipped.
void draw_text(Image& image, int x, int y, const std::string& text, const Eigen::Vector3d& colour, int scale = 2);

}  // namespace liftmap
