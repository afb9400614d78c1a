#pragma once
/// An 8-bit RGB raster, its PNG output and image input: what every picture of liftmap is drawn into, and textures.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace liftmap {

/// An 8-bit RGB image, row-major, top row first, 3 bytes per pixel.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes

  Image() = default;
  /// A width by height image filled with `background` (RGB in [0,1]).
  Image(int width, int height, const Eigen::Vector3d& background = Eigen::Vector3d::Ones());

  /// Pointer to the 3 bytes of pixel (x, y); x in [0, width), y in [0, height) (not checked).
  std::uint8_t* pixel(int x, int y) { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
  const std::uint8_t* pixel(int x, int y) const { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
  /// Pixel (x, y) as RGB in [0,1].
  Eigen::Vector3d colour(int x, int y) const;
  /// Sets pixel (x, y) to `c` (RGB, clamped to [0,1]); pixels outside the image are ignored.
  void set(int x, int y, const Eigen::Vector3d& c);
  /// Blends `c` over pixel (x, y) with opacity `alpha` in [0,1]; pixels outside the image are ignored.
  void blend(int x, int y, const Eigen::Vector3d& c, double alpha);
};

/// 8-bit value of a colour channel in [0,1] (clamped, rounded).
std::uint8_t to_byte(double channel);

/// Fills the rectangle [x0, x1) x [y0, y1) (clipped to the image) with `c`.
void fill_rect(Image& image, int x0, int y0, int x1, int y1, const Eigen::Vector3d& c);

/// Copies `src` into `dst` with its top-left corner at (x, y), clipped to `dst`.
void paste(Image& dst, const Image& src, int x, int y);

/// Averages each factor by factor block of pixels: the downsampling step of supersampled rendering.
/// \pre factor >= 1, and the image size is a multiple of factor.
Image downsample(const Image& image, int factor);

/// Writes `image` as an 8-bit RGB PNG.
/// \throw InvalidInputError for an empty image; IoError naming the file if it cannot be written.
void write_png(const std::string& path, const Image& image);

/// Reads a PNG or JPEG image (8 or 16 bits per channel, grey, grey + alpha, RGB or RGBA) as 8-bit RGB: alpha is
/// dropped, grey is copied to the three channels, 16-bit channels are rounded to 8 bits.
/// \throw IoError naming the file if it is missing, unreadable or not a PNG or JPEG image stb_image can decode.
Image read_image(const std::string& path);

}  // namespace liftmap
