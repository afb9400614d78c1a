#include "render/text.h"

#include <cmath>
#include <vector>

// Static functions and tables only: nothing of stb_easy_font is visible outside this file.
#include <stb_easy_font.h>

namespace liftmap {
namespace {

/// `text` with every character outside printable ASCII replaced by '?': stb_easy_font indexes its glyph table with
/// the character code unchecked, and would break the line at '\n'.
std::string printable(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

}  // namespace

int text_width(const std::string& text, int scale) {
  if (text.empty()) return 0;
  std::string s = printable(text);
  // Every glyph's advance is its ink plus 2 font pixels of spacing.
  return (stb_easy_font_width(s.data()) - 2) * scale;
}

void draw_text(Image& image, int x, int y, const std::string& text, const Eigen::Vector3d& colour, int scale) {
  if (text.empty()) return;
  std::string s = printable(text);
  // stb_easy_font writes 4 vertices of 16 bytes (x, y, z as floats, then RGBA) per quad and silently drops the quads
  // that do not fit: a buffer with room for one more quad after the last one written held them all.
  constexpr int kFloatsPerVertex = 4, kQuadBytes = 4 * kFloatsPerVertex * static_cast<int>(sizeof(float));
  std::vector<float> vertices(8 * 4 * kFloatsPerVertex * s.size());  // 8 quads a glyph; a few glyphs have more
  int quads = 0;
  for (;;) {
    const int bytes = static_cast<int>(vertices.size() * sizeof(float));
    quads = stb_easy_font_print(0.0F, 0.0F, s.data(), nullptr, vertices.data(), bytes);
    if ((quads + 1) * kQuadBytes <= bytes) break;
    vertices.resize(2 * vertices.size());
  }
  // Drawn at the origin, every quad has integer corners in font pixels: vertex 0 top-left, vertex 2 bottom-right.
  auto to_image = [scale](float font_pixel, int origin) {
    return origin + scale * static_cast<int>(std::lround(font_pixel));
  };
  for (int q = 0; q < quads; ++q) {
    const float* v = vertices.data() + 4 * kFloatsPerVertex * q;
    const float* w = v + 2 * kFloatsPerVertex;
    fill_rect(image, to_image(v[0], x), to_image(v[1], y), to_image(w[0], x), to_image(w[1], y), colour);
  }
}

}  // namespace liftmap
