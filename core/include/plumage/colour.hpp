// Colour science shared by every picture and by the renderer: the CIE 1931 2° observer and
// illuminant D65 (CIE 15:2004, 5 nm tables in the data folder), spectrum → CIE XYZ → linear
// sRGB → display sRGB (IEC 61966-2-1).
//
// Spectra are piecewise linear in λ on their own grid, and XYZ is the trapezoid rule on the
// union of that grid and the tables' grid, so the colour of a smooth spectrum barely depends on
// how it was sampled. The paper's reference code instead treats sample i of 400:6:694 as
// constant over the bin [400 + 6i, 406 + 6i] (spec §4.12); SpectralToXyz::bins reproduces that.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace plumage {

struct Xyz {
  double x = 0.0, y = 0.0, z = 0.0;
};

// Linear or encoded sRGB, as the function producing it says. Nominal range [0, 1].
struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};

// Display sRGB, 8 bits per channel: what a PNG holds.
struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

// CIE xy chromaticity.
struct Chromaticity {
  double x = 0.0, y = 0.0;
};
Chromaticity chromaticity(const Xyz& c);

// ---- tables --------------------------------------------------------------------------------

// The observer and D65 on their common grid (380–780 nm at 5 nm as shipped).
struct CieTables {
  std::vector<double> lambda_nm;         // strictly increasing
  std::vector<double> xbar, ybar, zbar;  // colour matching functions
  std::vector<double> d65;               // relative spectral power, 100 at 560 nm
};

// Reads cie1931_2deg_5nm.csv and cie_d65_5nm.csv from `folder`. A missing file, a malformed
// row or differing wavelength grids throw Error naming the file (and line).
CieTables load_cie_tables(const std::filesystem::path& folder);

// The tables from data_directory(), read once on first use; safe to call from any thread.
const CieTables& cie_tables();

// ---- spectrum → XYZ ------------------------------------------------------------------------

enum class SpectrumKind {
  // Reflectance lit by D65. A perfect white reflector (1 everywhere) gives Y = 1.
  reflectance,
  // Emitted radiance in the units of the D65 table (100 at 560 nm), no illuminant applied:
  // the D65 table itself gives the same XYZ as a white reflector, so a renderer that lights
  // scenes with D65 and reports radiance gets the same colours as the reflectance path.
  radiance,
};

// How a spectrum continues beyond the ends of its grid.
enum class Extension {
  // The end values hold over the whole observer range (380–780 nm). A constant spectrum is
  // then exactly neutral whatever its grid (400:6:694 does not turn white into yellow).
  hold_ends,
  // Nothing outside [first, last] of the grid.
  zero,
};

// Precomputed XYZ weights for one wavelength grid: pictures evaluate thousands of spectra on
// the same grid, so the union-grid integration is done once and apply() is three dot products.
class SpectralToXyz {
 public:
  // Spectra sampled at `lambda_nm` (finite, strictly increasing, non-empty), linear in between.
  explicit SpectralToXyz(std::span<const double> lambda_nm,
                         SpectrumKind kind = SpectrumKind::reflectance,
                         Extension extension = Extension::hold_ends,
                         const CieTables& tables = cie_tables());

  // The reference code's convention: sample i is constant on [start + i·width, start +
  // (i+1)·width], nothing outside. bins(400, 6, 50) matches spec §4.12 up to its unknown D65
  // normalisation (ours: white reflector over the full observer range has Y = 1).
  static SpectralToXyz bins(double start_nm, double width_nm, std::size_t count,
                            SpectrumKind kind = SpectrumKind::reflectance,
                            const CieTables& tables = cie_tables());

  std::size_t size() const { return wx_.size(); }

  // XYZ of one spectrum on this grid; throws Error if its length is not size().
  Xyz apply(std::span<const double> spectrum) const;

  // The weights themselves (X = Σ wx[i]·s[i]), for callers that vectorise over many spectra.
  const std::vector<double>& x_weights() const { return wx_; }
  const std::vector<double>& y_weights() const { return wy_; }
  const std::vector<double>& z_weights() const { return wz_; }

 private:
  SpectralToXyz() = default;
  std::vector<double> wx_, wy_, wz_;
};

// One-off conversions (build a SpectralToXyz when converting many spectra on one grid).
Xyz spectrum_to_xyz(std::span<const double> lambda_nm, std::span<const double> reflectance);
Xyz radiance_to_xyz(std::span<const double> lambda_nm, std::span<const double> radiance);

// XYZ of the perfect white reflector under D65 from the tables (Y = 1; CIE 15:2004 publishes
// 0.95047, 1, 1.08883).
Xyz d65_white_point();

// ---- XYZ → sRGB ----------------------------------------------------------------------------

// IEC 61966-2-1 matrices, derived from the sRGB primaries and D65 (x, y) = (0.3127, 0.3290) to
// full precision; the standard prints them rounded to 4 digits.
Rgb xyz_to_linear_srgb(const Xyz& c);
Xyz linear_srgb_to_xyz(const Rgb& c);

// Relative luminance of linear sRGB (the Y row of the matrix).
double srgb_luminance(const Rgb& linear);

// The exact piecewise sRGB transfer function: linear below 0.0031308 (encoded 0.04045),
// 1.055·v^(1/2.4) − 0.055 above. Negative input stays on the linear segment.
double srgb_encode(double linear);
double srgb_decode(double encoded);

// What to do with colours outside [0, 1]³ in linear sRGB (saturated iridescence often is).
enum class GamutMapping {
  // Clamp each channel: cheap, keeps in-gamut colours exactly, shifts hue and luminance of
  // out-of-gamut ones.
  clip,
  // Mix toward the grey of the same luminance just enough to fit: keeps the luminance (when
  // 0 ≤ Y ≤ 1, else Y is clamped first) and the dominant wavelength, loses saturation.
  desaturate,
};

// Linear sRGB into [0, 1]³. Non-finite channels (NaN) become 0 so one bad sample cannot poison
// an image.
Rgb map_to_gamut(const Rgb& linear, GamutMapping mapping = GamutMapping::clip);

// Linear sRGB (or XYZ) → gamut mapping → transfer function → 8 bits, rounded to nearest.
Rgb8 to_srgb8(const Rgb& linear, GamutMapping mapping = GamutMapping::clip);
Rgb8 to_srgb8(const Xyz& c, GamutMapping mapping = GamutMapping::clip);

}  // namespace plumage
