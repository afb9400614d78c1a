#pragma once
// Reading back what write_png wrote: the PNG signature and the IHDR width and height (big-endian).

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "render/image.h"

namespace liftmap::testing {

struct PngHeader {
  bool signature_ok = false;
  bool ihdr_ok = false;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

inline PngHeader read_png_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  PngHeader h;
  if (bytes.size() < 24) return h;
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  h.signature_ok = std::equal(signature, signature + 8, bytes.begin());
  h.ihdr_ok = bytes[12] == 'I' && bytes[13] == 'H' && bytes[14] == 'D' && bytes[15] == 'R';
  auto be32 = [&](std::size_t i) {
    return (std::uint32_t(bytes[i]) << 24) | (std::uint32_t(bytes[i + 1]) << 16) | (std::uint32_t(bytes[i + 2]) << 8) |
           std::uint32_t(bytes[i + 3]);
  };
  h.width = be32(16);
  h.height = be32(20);
  return h;
}

/// Number of pixels that differ from `background` by more than `tolerance` in some channel (0..255).
inline int count_non_background(const Image& image, const Eigen::Vector3d& background, int tolerance = 3) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      for (int k = 0; k < 3; ++k)
        if (std::abs(int(p[k]) - int(to_byte(background[k]))) > tolerance) {
          ++n;
          break;
        }
    }
  return n;
}

/// Where test pictures go: $LIFTMAP_RENDER_OUT if set (to look at them), else the test temporary folder.
inline std::string output_path(const std::string& name) {
  const char* dir = std::getenv("LIFTMAP_RENDER_OUT");
  return (dir ? std::string(dir) : ::testing::TempDir()) + "/" + name;
}

}  // namespace liftmap::testing
