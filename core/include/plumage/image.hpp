// Raster images: 8-bit display sRGB (what PNG previews hold) and float linear sRGB (what a
// renderer or a plot accumulates before tone decisions). Pixel (0, 0) is the top-left corner;
// rows are stored top to bottom.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

#include "plumage/colour.hpp"

namespace plumage {

class Image {
 public:
  Image() = default;
  // Throws Error for negative sizes.
  Image(int width, int height, Rgb8 fill = {});

  int width() const { return width_; }
  int height() const { return height_; }

  // Bounds-checked (throws Error naming the pixel and the size).
  Rgb8& at(int x, int y);
  const Rgb8& at(int x, int y) const;

  std::span<const Rgb8> pixels() const { return pixels_; }
  std::span<Rgb8> pixels() { return pixels_; }

  // Fills [x, x + w) × [y, y + h), clipped to the image (so plots need not clip themselves).
  void fill_rect(int x, int y, int w, int h, Rgb8 colour);

 private:
  int width_ = 0, height_ = 0;
  std::vector<Rgb8> pixels_;
};

struct RgbF {
  float r = 0.0f, g = 0.0f, b = 0.0f;
};

class LinearImage {
 public:
  LinearImage() = default;
  LinearImage(int width, int height, RgbF fill = {});

  int width() const { return width_; }
  int height() const { return height_; }
  RgbF& at(int x, int y);
  const RgbF& at(int x, int y) const;
  std::span<const RgbF> pixels() const { return pixels_; }
  std::span<RgbF> pixels() { return pixels_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<RgbF> pixels_;
};

// Gamut mapping, sRGB transfer function and 8-bit rounding per pixel (see colour.hpp).
Image to_display(const LinearImage& linear, GamutMapping mapping = GamutMapping::clip);

// 8-bit RGB PNG (sRGB chunk set), written atomically: a temporary file beside `path`, renamed
// over it only when complete; missing parent folders are created. Throws Error naming `path`
// if the image is empty or anything fails, and then leaves no file behind.
void write_png(const Image& image, const std::filesystem::path& path);

// Any PNG libpng reads, converted to 8-bit sRGB (grey expanded, alpha composited on black).
// Throws Error naming `path`.
Image read_png(const std::filesystem::path& path);

}  // namespace plumage
