// Pixel storage for Image and LinearImage, and the linear → display conversion.
#include "plumage/image.hpp"

#include <algorithm>
#include <string>

#include "plumage/error.hpp"

namespace plumage {

namespace {

std::size_t checked_area(int width, int height) {
  if (width < 0 || height < 0)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is negative");
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

std::size_t checked_index(int x, int y, int width, int height) {
  if (x < 0 || y < 0 || x >= width || y >= height)
    throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") outside a " +
                std::to_string(width) + "x" + std::to_string(height) + " image");
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
}

}  // namespace

Image::Image(int width, int height, Rgb8 fill)
    : width_(width), height_(height), pixels_(checked_area(width, height), fill) {}

Rgb8& Image::at(int x, int y) { return pixels_[checked_index(x, y, width_, height_)]; }
const Rgb8& Image::at(int x, int y) const { return pixels_[checked_index(x, y, width_, height_)]; }

void Image::fill_rect(int x, int y, int w, int h, Rgb8 colour) {
  // 64-bit ends so that huge w or h cannot overflow before clipping.
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = static_cast<int>(std::min<long long>(static_cast<long long>(x) + w, width_));
  const int y1 = static_cast<int>(std::min<long long>(static_cast<long long>(y) + h, height_));
  for (int row = y0; row < y1; ++row)
    for (int col = x0; col < x1; ++col)
      pixels_[static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(col)] = colour;
}

LinearImage::LinearImage(int width, int height, RgbF fill)
    : width_(width), height_(height), pixels_(checked_area(width, height), fill) {}

RgbF& LinearImage::at(int x, int y) { return pixels_[checked_index(x, y, width_, height_)]; }
const RgbF& LinearImage::at(int x, int y) const {
  return pixels_[checked_index(x, y, width_, height_)];
}

Image to_display(const LinearImage& linear, GamutMapping mapping) {
  Image out(linear.width(), linear.height());
  const auto in = linear.pixels();
  auto px = out.pixels();
  for (std::size_t i = 0; i < in.size(); ++i)
    px[i] = to_srgb8(Rgb{in[i].r, in[i].g, in[i].b}, mapping);
  return out;
}

}  // namespace plumage
