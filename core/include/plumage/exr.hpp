// OpenEXR output of rendered images (issue 8): linear sRGB as float R, G, B plus optional
// spectral radiance channels, written atomically like write_png (image.hpp).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "plumage/image.hpp"

namespace plumage {

// Equal spectral bins over [lambda_min_nm, lambda_max_nm]; values [y][x][bin] (RenderResult).
struct SpectralChannels {
  int bins = 0;
  double lambda_min_nm = 400.0, lambda_max_nm = 700.0;
  std::vector<float> values;
};

// Channel name of bin b: "S<bb>.<lo>-<hi>nm" (zero-padded index so that OpenEXR's alphabetical
// channel order is the wavelength order; the dot makes "S<bb>" a layer in EXR viewers).
std::string spectral_channel_name(const SpectralChannels& s, int bin);

// Float (32-bit) R, G, B and, when `spectral` has bins > 0, one float channel per bin. Encoded in
// memory (ZIP compression), then a temporary file beside `path` renamed over it; missing parent
// folders are created. Throws Error naming `path` for an empty image, a spectral buffer of the
// wrong size, or any I/O failure (no file is left behind then). `attributes` become string
// attributes of the header (e.g. "plumage:warnings").
void write_exr(const LinearImage& rgb, const std::filesystem::path& path,
               const SpectralChannels* spectral = nullptr,
               const std::map<std::string, std::string>& attributes = {});

// Reads the R, G, B channels of an EXR (any pixel type) into linear sRGB; for tests and tools.
LinearImage read_exr_rgb(const std::filesystem::path& path);

// The string attributes of an EXR header (others are skipped); for tests and tools.
std::map<std::string, std::string> read_exr_string_attributes(const std::filesystem::path& path);

}  // namespace plumage
