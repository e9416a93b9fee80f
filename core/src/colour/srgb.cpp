// XYZ ↔ linear sRGB, the sRGB transfer function, gamut mapping and 8-bit encoding
// (IEC 61966-2-1).
#include <algorithm>
#include <cmath>

#include "plumage/colour.hpp"

namespace plumage {

namespace {

// From the primaries R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06) and white (0.3127, 0.3290).
// The standard prints these rounded (0.4124 0.3576 0.1805 …, 3.2406 −1.5372 −0.4986 …); full
// precision keeps the two directions inverse to each other.
constexpr double kRgbToXyz[3][3] = {{0.4123907993, 0.3575843394, 0.1804807884},
                                    {0.2126390059, 0.7151686788, 0.0721923154},
                                    {0.0193308187, 0.1191947798, 0.9505321522}};
constexpr double kXyzToRgb[3][3] = {{3.2409699419, -1.5373831776, -0.4986107603},
                                    {-0.9692436363, 1.8759675015, 0.0415550574},
                                    {0.0556300797, -0.2039769589, 1.0569715142}};

std::uint8_t quantise(double encoded) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(encoded, 0.0, 1.0) * 255.0));
}

}  // namespace

Rgb xyz_to_linear_srgb(const Xyz& c) {
  const auto& m = kXyzToRgb;
  return {m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
          m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
          m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z};
}

Xyz linear_srgb_to_xyz(const Rgb& c) {
  const auto& m = kRgbToXyz;
  return {m[0][0] * c.r + m[0][1] * c.g + m[0][2] * c.b,
          m[1][0] * c.r + m[1][1] * c.g + m[1][2] * c.b,
          m[2][0] * c.r + m[2][1] * c.g + m[2][2] * c.b};
}

double srgb_luminance(const Rgb& c) {
  return kRgbToXyz[1][0] * c.r + kRgbToXyz[1][1] * c.g + kRgbToXyz[1][2] * c.b;
}

double srgb_encode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Rgb map_to_gamut(const Rgb& linear, GamutMapping mapping) {
  double c[3] = {linear.r, linear.g, linear.b};
  for (double& v : c) v = std::isnan(v) ? 0.0 : std::clamp(v, -1e300, 1e300);  // inf·0 below
  if (mapping == GamutMapping::desaturate) {
    // Move along the straight line to the grey (Y, Y, Y): in linear RGB that line is also
    // straight in chromaticity and ends at the white point, so the dominant wavelength stays.
    const double y = std::clamp(srgb_luminance({c[0], c[1], c[2]}), 0.0, 1.0);
    double t = 1.0;  // fraction of the original chroma kept
    for (double v : c) {
      if (v < 0.0) t = std::min(t, y / (y - v));
      if (v > 1.0) t = std::min(t, (1.0 - y) / (v - y));
    }
    for (double& v : c) v = y + t * (v - y);
  }
  // The clip itself for GamutMapping::clip; only rounding residue for desaturate.
  for (double& v : c) v = std::clamp(v, 0.0, 1.0);
  return {c[0], c[1], c[2]};
}

Rgb8 to_srgb8(const Rgb& linear, GamutMapping mapping) {
  const Rgb c = map_to_gamut(linear, mapping);
  return {quantise(srgb_encode(c.r)), quantise(srgb_encode(c.g)), quantise(srgb_encode(c.b))};
}

Rgb8 to_srgb8(const Xyz& c, GamutMapping mapping) {
  return to_srgb8(xyz_to_linear_srgb(c), mapping);
}

}  // namespace plumage
