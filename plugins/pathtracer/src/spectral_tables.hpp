// Hero wavelengths and the tables the path tracer evaluates at them: CIE 1931 colour matching
// functions and the D65 emission shape, resampled once on a fine uniform grid over
// [lambda_min, lambda_max] so that a lookup is one linear interpolation (no search per sample).
#pragma once

#include <array>
#include <vector>

#include "plumage/colour.hpp"
#include "plumage/scene.hpp"

namespace plumage::pathtracer {

inline constexpr int kWavelengths = 4;  // per path (Wilkie et al. 2014)
using Spectrum4 = std::array<double, kWavelengths>;

class SpectralTables {
 public:
  SpectralTables(double lambda_min_nm, double lambda_max_nm, const CieTables& cie = cie_tables());

  double lambda_min() const { return lmin_; }
  double lambda_max() const { return lmax_; }
  double range() const { return lmax_ - lmin_; }

  // Hero λ uniform in [min, max) from u ∈ [0, 1); the others rotated by range/4 (Wilkie et al.
  // 2014, §3): every λ_j is then marginally uniform, pdf 1/range.
  Spectrum4 wavelengths(double u) const;

  // D65 in the units of its table (100 at 560 nm).
  double d65(double lambda_nm) const { return lerp(d65_, lambda_nm); }
  Xyz cmf(double lambda_nm) const { return {lerp(x_, lambda_nm), lerp(y_, lambda_nm), lerp(z_, lambda_nm)}; }

  // XYZ of one path's radiance at its four wavelengths: (1/4) Σ_j L_j cmf(λ_j) / pdf(λ_j), times
  // the normalisation that gives D65 radiance × 1 the XYZ of the white reflector (Y = 1,
  // colour.hpp SpectrumKind::radiance) — per channel over [min, max], so that D65 stays exactly
  // white although the observer's tails outside the range are not sampled.
  Xyz to_xyz(const Spectrum4& lambda, const Spectrum4& radiance) const;

 private:
  double lerp(const std::vector<double>& t, double lambda) const;
  double lmin_, lmax_, step_;
  std::vector<double> x_, y_, z_, d65_;
  Xyz scale_;  // per-channel normalisation of to_xyz
};

}  // namespace plumage::pathtracer
