#include "spectral_tables.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/error.hpp"

namespace plumage::pathtracer {

namespace {

// Linear interpolation in a tabulated (increasing) grid, ends held.
double interp(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - xs.begin()) - 1;
  const double t = (x - xs[i]) / (xs[i + 1] - xs[i]);
  return ys[i] + t * (ys[i + 1] - ys[i]);
}

}  // namespace

SpectralTables::SpectralTables(double lambda_min_nm, double lambda_max_nm, const CieTables& cie)
    : lmin_(lambda_min_nm), lmax_(lambda_max_nm) {
  if (!(lmax_ > lmin_) || lmin_ <= 0.0) {
    throw Error("pathtracer: wavelength range [" + std::to_string(lmin_) + ", " + std::to_string(lmax_) +
                "] nm is empty");
  }
  // 0.25 nm: the CIE tables are 5 nm piecewise linear, so this grid reproduces them exactly at
  // their nodes and linearly in between.
  const int n = static_cast<int>(std::ceil((lmax_ - lmin_) / 0.25)) + 1;
  step_ = (lmax_ - lmin_) / (n - 1);
  for (int i = 0; i < n; ++i) {
    const double l = lmin_ + step_ * i;
    x_.push_back(interp(cie.lambda_nm, cie.xbar, l));
    y_.push_back(interp(cie.lambda_nm, cie.ybar, l));
    z_.push_back(interp(cie.lambda_nm, cie.zbar, l));
    d65_.push_back(interp(cie.lambda_nm, cie.d65, l));
  }
  // ∫ D65·cmf over the range (trapezoid on the fine grid) ↔ the white point.
  Xyz w;
  for (int i = 0; i < n; ++i) {
    const double h = (i == 0 || i == n - 1) ? 0.5 * step_ : step_;
    w.x += h * d65_[i] * x_[i];
    w.y += h * d65_[i] * y_[i];
    w.z += h * d65_[i] * z_[i];
  }
  const Xyz white = d65_white_point();
  scale_ = {white.x / w.x, white.y / w.y, white.z / w.z};
}

double SpectralTables::lerp(const std::vector<double>& t, double lambda) const {
  const double f = (lambda - lmin_) / step_;
  if (f <= 0.0) return t.front();
  const std::size_t i = static_cast<std::size_t>(f);
  if (i + 1 >= t.size()) return t.back();
  const double a = f - static_cast<double>(i);
  return t[i] + a * (t[i + 1] - t[i]);
}

Spectrum4 SpectralTables::wavelengths(double u) const {
  Spectrum4 l;
  const double r = range();
  for (int j = 0; j < kWavelengths; ++j) {
    double v = u + static_cast<double>(j) / kWavelengths;
    if (v >= 1.0) v -= 1.0;
    l[static_cast<std::size_t>(j)] = lmin_ + r * v;
  }
  return l;
}

Xyz SpectralTables::to_xyz(const Spectrum4& lambda, const Spectrum4& radiance) const {
  Xyz s;
  for (int j = 0; j < kWavelengths; ++j) {
    const Xyz c = cmf(lambda[static_cast<std::size_t>(j)]);
    const double l = radiance[static_cast<std::size_t>(j)];
    s.x += l * c.x;
    s.y += l * c.y;
    s.z += l * c.z;
  }
  const double k = range() / kWavelengths;  // (1/4) Σ … / pdf, pdf = 1/range
  return {s.x * k * scale_.x, s.y * k * scale_.y, s.z * k * scale_.z};
}

}  // namespace plumage::pathtracer
