// Autocorrelation of the noise data and the correlation length l (spec §4.6 steps 4–5, §4.8
// step 2). Direct sums, no FFT: the per-unit length stops at the first lag below e⁻¹ (typically
// ten lags), and the direct sums make every record identical on every machine.
#include <array>
#include <cmath>

#include "plumage/error.hpp"
#include "plumage/fitter.hpp"

namespace plumage {

namespace {

std::vector<std::vector<double>> centred(const std::vector<std::vector<double>>& columns) {
  if (columns.empty() || columns.front().size() < 4) throw Error("correlation: need columns of at least 4 samples");
  std::vector<std::vector<double>> c = columns;
  for (auto& col : c) {
    if (col.size() != columns.front().size()) throw Error("correlation: columns differ in length");
    double mean = 0;
    for (double v : col) mean += v;
    mean /= static_cast<double>(col.size());
    for (double& v : col) v -= mean;
  }
  return c;
}

// Σ over columns of the circular autocovariance at `lag` (the common divisor N − 1 cancels in
// the normalisation by lag 0).
double summed_autocovariance(const std::vector<std::vector<double>>& c, std::size_t lag) {
  double s = 0;
  const std::size_t n = c.front().size();
  for (const auto& col : c) {
    // The same products in the same order as t = 0 … n − 1 with index (t + lag) mod n, without
    // the integer division per product.
    const double* x = col.data();
    for (std::size_t t = 0; t < n - lag; ++t) s += x[t] * x[t + lag];
    for (std::size_t t = n - lag; t < n; ++t) s += x[t] * x[t + lag - n];
  }
  return s;
}

// summed_autocovariance at lags lag0 … lag0 + 3 in one pass over the columns: four independent
// sums (the single sum's add latency, not the loads, bounded the one-lag loop), each taking its
// products in the order summed_autocovariance does, so each equals it bit for bit.
std::array<double, 4> summed_autocovariance4(const std::vector<std::vector<double>>& c, std::size_t lag0) {
  std::array<double, 4> s{0.0, 0.0, 0.0, 0.0};
  const std::size_t n = c.front().size();
  if (lag0 + 3 >= n) {
    for (std::size_t q = 0; q < 4; ++q) s[q] = lag0 + q < n ? summed_autocovariance(c, lag0 + q) : 0.0;
    return s;
  }
  const std::size_t common = n - (lag0 + 3);  // t below it: t + lag < n for all four lags
  for (const auto& col : c) {
    const double* x = col.data();
    double s0 = s[0], s1 = s[1], s2 = s[2], s3 = s[3];
    for (std::size_t t = 0; t < common; ++t) {
      const double xt = x[t];
      s0 += xt * x[t + lag0];
      s1 += xt * x[t + lag0 + 1];
      s2 += xt * x[t + lag0 + 2];
      s3 += xt * x[t + lag0 + 3];
    }
    s[0] = s0, s[1] = s1, s[2] = s2, s[3] = s3;
    for (std::size_t q = 0; q < 4; ++q) {
      const std::size_t lag = lag0 + q;
      double sq = s[q];
      for (std::size_t t = common; t < n - lag; ++t) sq += x[t] * x[t + lag];
      for (std::size_t t = n - lag; t < n; ++t) sq += x[t] * x[t + lag - n];
      s[q] = sq;
    }
  }
  return s;
}

}  // namespace

double correlation_length(const std::vector<std::vector<double>>& columns, double spacing) {
  const auto c = centred(columns);
  const std::size_t n = c.front().size();
  const double c0 = summed_autocovariance(c, 0);
  if (!(c0 > 0)) return 0.0;
  const double target = std::exp(-1.0);
  double prev = 1.0;
  std::array<double, 4> block{};
  for (std::size_t lag = 1; lag < n / 2; ++lag) {
    if ((lag - 1) % 4 == 0) block = summed_autocovariance4(c, lag);
    const double rho = block[(lag - 1) % 4] / c0;
    if (rho < target) {
      // Linear interpolation between lag − 1 (ρ = prev ≥ e⁻¹) and lag.
      const double frac = (prev - target) / (prev - rho);
      return (static_cast<double>(lag - 1) + frac) * spacing;
    }
    prev = rho;
  }
  return static_cast<double>(n / 2 - 1) * spacing;
}

std::vector<double> mean_autocorrelation(const std::vector<std::vector<double>>& columns) {
  const auto c = centred(columns);
  const std::size_t n = c.front().size(), half = n / 2;
  std::vector<double> acf(n, 0.0);
  for (std::size_t lag = 0; lag < half; ++lag) acf[lag] = summed_autocovariance(c, lag);
  const double c0 = acf[0];
  if (!(c0 > 0)) throw Error("autocorrelation: the noise data are constant");
  for (std::size_t lag = 0; lag < half; ++lag) acf[lag] /= c0;
  // Mirror: lags N/2 + 1 … N − 1 are lags N/2 − 1 … 1.
  for (std::size_t lag = half + 1; lag < n; ++lag) acf[lag] = acf[n - lag];
  // Lag N/2: mean of its neighbours (lags N/2 − 1 and N/2 + 1, equal after mirroring).
  acf[half] = 0.5 * (acf[half - 1] + acf[(half + 1) % n]);
  return acf;
}

}  // namespace plumage
