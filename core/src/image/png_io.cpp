// PNG files through libpng's simplified API: it reports errors through a message in png_image
// instead of longjmp, so no setjmp is needed around C++ objects.
#include <png.h>

#include <cstring>
#include <ostream>
#include <string>

#include "plumage/atomic_file.hpp"
#include "plumage/error.hpp"
#include "plumage/image.hpp"

namespace plumage {

namespace fs = std::filesystem;

static_assert(sizeof(Rgb8) == 3, "Rgb8 must be packed: PNG rows are copied as bytes");

void write_png(const Image& image, const fs::path& path) {
  if (image.width() <= 0 || image.height() <= 0)
    throw Error(path.string() + ": cannot write an empty image as PNG");
  std::vector<png_byte> rgb(image.pixels().size() * 3);
  std::memcpy(rgb.data(), image.pixels().data(), rgb.size());

  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width());
  png.height = static_cast<png_uint_32>(image.height());
  png.format = PNG_FORMAT_RGB;  // 8-bit sRGB: libpng writes the sRGB chunk
  // Encode in memory first, so the file step below is a plain atomic write of finished bytes.
  png_alloc_size_t size = 0;
  std::vector<png_byte> encoded;
  bool ok = png_image_write_get_memory_size(png, size, 0, rgb.data(), 0, nullptr) != 0;
  if (ok) {
    encoded.resize(size);
    ok = png_image_write_to_memory(&png, encoded.data(), &size, 0, rgb.data(), 0, nullptr) != 0;
  }
  if (!ok) {
    const std::string message = png.message;
    png_image_free(&png);
    throw Error(path.string() + ": PNG encoding failed: " + message);
  }
  try {
    write_file_atomically(
        path,
        [&](std::ostream& out) {
          out.write(reinterpret_cast<const char*>(encoded.data()), static_cast<std::streamsize>(size));
        },
        /*binary=*/true);
  } catch (const OutputPathError&) {
    throw;  // bad input, not a failed write: keeps its type (exit status 2)
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot write PNG (" + e.what() + ")");
  }
}

Image read_png(const fs::path& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw Error(path.string() + ": cannot read PNG: " + png.message);
  png.format = PNG_FORMAT_RGB;
  if (png.width > 1u << 15 || png.height > 1u << 15) {
    png_image_free(&png);
    throw Error(path.string() + ": PNG larger than 32768 pixels on a side");
  }
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  std::vector<png_byte> rgb(PNG_IMAGE_SIZE(png), 0);  // zeros: alpha composites onto black
  const png_color black{0, 0, 0};
  if (!png_image_finish_read(&png, &black, rgb.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw Error(path.string() + ": cannot read PNG: " + message);
  }
  std::memcpy(image.pixels().data(), rgb.data(), rgb.size());
  return image;
}

}  // namespace plumage
