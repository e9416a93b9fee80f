// Spectrum → XYZ weights for a fixed wavelength grid.
//
// X = ∫ s(λ) x̄(λ) D65(λ) dλ / ∫ ȳ(λ) D65(λ) dλ (D65 dropped for radiance). The tabulated
// products x̄·D65 are taken as piecewise linear on the 5 nm grid, the spectrum as piecewise
// linear on its own grid, and the integral is the trapezoid rule on the union of both grids.
// Because that is linear in the samples s[i], it collapses to one weight per sample.
#include <algorithm>
#include <cmath>
#include <string>

#include "plumage/colour.hpp"
#include "plumage/error.hpp"

namespace plumage {

namespace {

// The three integrands (x̄·D65, ȳ·D65, z̄·D65, or the bare x̄, ȳ, z̄) on the table grid and
// the normaliser that gives the perfect white reflector Y = 1.
struct Integrands {
  const std::vector<double>& t;
  std::vector<double> w[3];
  double norm = 0.0;

  Integrands(const CieTables& tables, SpectrumKind kind) : t(tables.lambda_nm) {
    const std::vector<double>* cmf[3] = {&tables.xbar, &tables.ybar, &tables.zbar};
    for (int c = 0; c < 3; ++c) {
      w[c] = *cmf[c];
      if (kind == SpectrumKind::reflectance)
        for (std::size_t j = 0; j < t.size(); ++j) w[c][j] *= tables.d65[j];
    }
    for (std::size_t j = 0; j + 1 < t.size(); ++j)
      norm += 0.5 * (t[j + 1] - t[j]) * (tables.ybar[j] * tables.d65[j] + tables.ybar[j + 1] * tables.d65[j + 1]);
  }

  // The integrands at u, linear between table points, zero outside the table.
  void at(double u, double out[3]) const {
    out[0] = out[1] = out[2] = 0.0;
    if (u < t.front() || u > t.back()) return;
    std::size_t j = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), u) - t.begin());
    if (j >= t.size()) j = t.size() - 1;  // u == t.back()
    const double f = (u - t[j - 1]) / (t[j] - t[j - 1]);
    for (int c = 0; c < 3; ++c) out[c] = (1.0 - f) * w[c][j - 1] + f * w[c][j];
  }
};

void check_grid(std::span<const double> lambda) {
  if (lambda.empty()) throw Error("spectrum to XYZ: empty wavelength grid");
  for (std::size_t i = 0; i < lambda.size(); ++i) {
    if (!std::isfinite(lambda[i]))
      throw Error("spectrum to XYZ: wavelength " + std::to_string(i) + " is not finite");
    if (i > 0 && !(lambda[i] > lambda[i - 1]))
      throw Error("spectrum to XYZ: wavelengths must increase strictly (sample " +
                  std::to_string(i) + ": " + std::to_string(lambda[i]) + " nm after " +
                  std::to_string(lambda[i - 1]) + " nm)");
  }
}

// The sorted union of `extra` points and the table points strictly inside [a, b], with a, b.
std::vector<double> union_grid(const std::vector<double>& table, std::span<const double> extra,
                               double a, double b) {
  std::vector<double> u{a, b};
  for (double v : table)
    if (v > a && v < b) u.push_back(v);
  for (double v : extra)
    if (v > a && v < b) u.push_back(v);
  std::sort(u.begin(), u.end());
  u.erase(std::unique(u.begin(), u.end()), u.end());
  return u;
}

}  // namespace

SpectralToXyz::SpectralToXyz(std::span<const double> lambda, SpectrumKind kind, Extension extension,
                             const CieTables& tables) {
  check_grid(lambda);
  const Integrands in(tables, kind);
  const std::size_t n = lambda.size();
  wx_.assign(n, 0.0);
  wy_.assign(n, 0.0);
  wz_.assign(n, 0.0);
  double a = in.t.front(), b = in.t.back();
  if (extension == Extension::zero) {
    a = std::max(a, lambda.front());
    b = std::min(b, lambda.back());
  }
  if (!(a < b)) return;  // no overlap with the observer: the spectrum is invisible
  const std::vector<double> u = union_grid(in.t, lambda, a, b);
  for (std::size_t k = 0; k < u.size(); ++k) {
    // Trapezoid weight of node k on the (non-uniform) union grid.
    const double h = 0.5 * ((k + 1 < u.size() ? u[k + 1] : u[k]) - (k > 0 ? u[k - 1] : u[k]));
    double w[3];
    in.at(u[k], w);
    for (int c = 0; c < 3; ++c) w[c] *= h / in.norm;
    // The spectrum at u[k] as a combination of at most two samples (end values held outside).
    std::size_t i0 = 0, i1 = 0;
    double f = 0.0;
    if (u[k] >= lambda.back()) {
      i0 = i1 = n - 1;
    } else if (u[k] > lambda.front()) {
      i1 = static_cast<std::size_t>(std::upper_bound(lambda.begin(), lambda.end(), u[k]) - lambda.begin());
      i0 = i1 - 1;
      f = (u[k] - lambda[i0]) / (lambda[i1] - lambda[i0]);
    }
    wx_[i0] += (1.0 - f) * w[0];
    wy_[i0] += (1.0 - f) * w[1];
    wz_[i0] += (1.0 - f) * w[2];
    wx_[i1] += f * w[0];
    wy_[i1] += f * w[1];
    wz_[i1] += f * w[2];
  }
}

SpectralToXyz SpectralToXyz::bins(double start_nm, double width_nm, std::size_t count,
                                  SpectrumKind kind, const CieTables& tables) {
  if (!std::isfinite(start_nm) || !(width_nm > 0.0) || !std::isfinite(width_nm) || count == 0)
    throw Error("spectrum to XYZ: bins need a finite start, a positive width and a count > 0");
  const Integrands in(tables, kind);
  SpectralToXyz s;
  for (std::size_t i = 0; i < count; ++i) {
    // ∫ over the bin of the piecewise-linear integrands: the trapezoid rule on the bin ends
    // plus the table points inside is exact.
    const double lo = start_nm + static_cast<double>(i) * width_nm;
    const double hi = lo + width_nm;
    const std::vector<double> u = union_grid(in.t, {}, lo, hi);
    double sum[3] = {0.0, 0.0, 0.0};
    for (std::size_t k = 0; k + 1 < u.size(); ++k) {
      double w0[3], w1[3];
      in.at(u[k], w0);
      in.at(u[k + 1], w1);
      for (int c = 0; c < 3; ++c) sum[c] += 0.5 * (u[k + 1] - u[k]) * (w0[c] + w1[c]);
    }
    s.wx_.push_back(sum[0] / in.norm);
    s.wy_.push_back(sum[1] / in.norm);
    s.wz_.push_back(sum[2] / in.norm);
  }
  return s;
}

Xyz SpectralToXyz::apply(std::span<const double> spectrum) const {
  if (spectrum.size() != wx_.size())
    throw Error("spectrum to XYZ: spectrum has " + std::to_string(spectrum.size()) +
                " samples, the wavelength grid " + std::to_string(wx_.size()));
  Xyz c;
  for (std::size_t i = 0; i < spectrum.size(); ++i) {
    c.x += wx_[i] * spectrum[i];
    c.y += wy_[i] * spectrum[i];
    c.z += wz_[i] * spectrum[i];
  }
  return c;
}

Xyz spectrum_to_xyz(std::span<const double> lambda_nm, std::span<const double> reflectance) {
  return SpectralToXyz(lambda_nm, SpectrumKind::reflectance).apply(reflectance);
}

Xyz radiance_to_xyz(std::span<const double> lambda_nm, std::span<const double> radiance) {
  return SpectralToXyz(lambda_nm, SpectrumKind::radiance).apply(radiance);
}

Xyz d65_white_point() {
  static const Xyz white = [] {
    const double lambda[1] = {560.0};  // one sample, end values held: constant 1 everywhere
    const double one[1] = {1.0};
    return spectrum_to_xyz(lambda, one);
  }();
  return white;
}

Chromaticity chromaticity(const Xyz& c) {
  const double sum = c.x + c.y + c.z;
  if (sum == 0.0) return {};
  return {c.x / sum, c.y / sum};
}

}  // namespace plumage
