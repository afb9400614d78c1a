#include "render/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

// The implementation with internal linkage: a host program that uses stb_image_write itself keeps its own.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
// The same for the reader, limited to the two formats textures come in.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#include <stb_image.h>

#include "core/errors.h"
#include "io/output_file.h"

namespace liftmap {

std::uint8_t to_byte(double channel) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(channel, 0.0, 1.0) * 255.0));
}

Image::Image(int w, int h, const Eigen::Vector3d& background)
    : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3) {
  const std::uint8_t r = to_byte(background.x()), g = to_byte(background.y()), b = to_byte(background.z());
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = r;
    rgb[i + 1] = g;
    rgb[i + 2] = b;
  }
}

Eigen::Vector3d Image::colour(int x, int y) const {
  const std::uint8_t* p = pixel(x, y);
  return Eigen::Vector3d(p[0], p[1], p[2]) / 255.0;
}

void Image::set(int x, int y, const Eigen::Vector3d& c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = pixel(x, y);
  for (int k = 0; k < 3; ++k) p[k] = to_byte(c[k]);
}

void Image::blend(int x, int y, const Eigen::Vector3d& c, double alpha) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  alpha = std::clamp(alpha, 0.0, 1.0);
  set(x, y, (1.0 - alpha) * colour(x, y) + alpha * c);
}

void fill_rect(Image& image, int x0, int y0, int x1, int y1, const Eigen::Vector3d& c) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, image.width);
  y1 = std::min(y1, image.height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) image.set(x, y, c);
}

void paste(Image& dst, const Image& src, int x, int y) {
  for (int sy = 0; sy < src.height; ++sy) {
    const int dy = y + sy;
    if (dy < 0 || dy >= dst.height) continue;
    for (int sx = 0; sx < src.width; ++sx) {
      const int dx = x + sx;
      if (dx < 0 || dx >= dst.width) continue;
      std::copy_n(src.pixel(sx, sy), 3, dst.pixel(dx, dy));
    }
  }
}

Image downsample(const Image& image, int factor) {
  if (factor <= 1) return image;
  Image out(image.width / factor, image.height / factor);
  const int n = factor * factor;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) {
          const std::uint8_t* p = image.pixel(x * factor + i, y * factor + j);
          for (int k = 0; k < 3; ++k) sum[k] += p[k];
        }
      std::uint8_t* q = out.pixel(x, y);
      for (int k = 0; k < 3; ++k) q[k] = static_cast<std::uint8_t>((sum[k] + n / 2) / n);
    }
  return out;
}

void write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw InvalidInputError("write_png: empty or inconsistent image for " + path);
  OutputFile file(path);
  const auto write = [](void* context, void* data, int size) {
    std::fwrite(data, 1, static_cast<size_t>(size), static_cast<std::FILE*>(context));
  };
  if (stbi_write_png_to_func(write, file.get(), image.width, image.height, 3, image.rgb.data(), image.width * 3) == 0)
    throw IoError(path + ": cannot write PNG");
  file.close();
}

Image read_image(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw IoError(path + ": no such image file");
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw IoError(path + ": cannot open image file");
  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load_from_file(file.get(), &width, &height, &channels, 3),
                                                       &stbi_image_free);
  if (!data) throw IoError(path + ": cannot read the image (" + stbi_failure_reason() + "; PNG or JPEG expected)");
  Image image;
  image.width = width;
  image.height = height;
  image.rgb.assign(data.get(), data.get() + static_cast<std::size_t>(width) * height * 3);
  return image;
}

}  // namespace liftmap
