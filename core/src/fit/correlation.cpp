// Autocorrelation of the noise data and the correlation length l (spec §4.6 steps 4–5, §4.8
// step 2). Direct sums, no FFT: the per-unit length stops at the first lag below e⁻¹ (rock-dove
// production, 550 nm: 8–31 lags, mean 22, over 200 columns of 1024 samples), and the direct sums
// make every record identical on every machine.
//
// The sums run as 32 lags at once: for each t one product x_t · x_{t+lag} per lag, in 8 vectors
// of 4 lags. Each lag's sum still takes its products in the order of the plain definition
// (columns in order, t = 0 … N − 1 with index (t + lag) mod N), so each equals it bit for bit; the
// 8 independent accumulators, not the adds of one sum, now bound the loop (4 MAC per cycle
// instead of 1 with the former 4 scalar sums; 32 lags cover every unit above in one pass).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "plumage/simd_math.hpp"
#include "noise_columns.hpp"

namespace plumage {

namespace detail {

void centre(NoiseColumns& c) {
  for (std::size_t k = 0; k < c.count; ++k) {
    double* x = c.column(k);
    double mean = 0;
    for (std::size_t t = 0; t < c.n; ++t) mean += x[t];
    mean /= static_cast<double>(c.n);
    for (std::size_t t = 0; t < c.n; ++t) x[t] -= mean;
    for (std::size_t t = c.n; t < c.stride; ++t) x[t] = x[(t - c.n) % c.n];
  }
}

namespace {

// Σ over columns of the circular autocovariance at lags lag0 … lag0 + 31 (the common divisor
// N − 1 cancels in the normalisation by lag 0); lags ≥ N give 0.
std::array<double, kLagBlock> summed_autocovariance32(const NoiseColumns& c, std::size_t lag0) {
  using simd::v4d;
  const std::size_t n = c.n;
  std::vector<double> shifted(lag0 > 0 ? c.stride : 0);
  v4d s[8] = {};
  for (std::size_t k = 0; k < c.count; ++k) {
    const double* x = c.column(k);
    // y[t + q] = x[(t + lag0 + q) mod N] for t < N, q < 32: the column itself at lag0 = 0, else
    // a shifted copy.
    const double* y = x;
    if (lag0 > 0) {
      for (std::size_t t = 0; t < c.stride; ++t) shifted[t] = x[(t + lag0) % n];
      y = shifted.data();
    }
    for (std::size_t t = 0; t < n; ++t) {
      const v4d xt = simd::splat(x[t]);
      for (std::size_t j = 0; j < 8; ++j) {
        v4d yj;
        __builtin_memcpy(&yj, y + t + 4 * j, sizeof yj);
        s[j] += xt * yj;
      }
    }
  }
  std::array<double, kLagBlock> out{};
  for (std::size_t q = 0; q < kLagBlock; ++q) out[q] = lag0 + q < n ? s[q / 4][q % 4] : 0.0;
  return out;
}

}  // namespace

double correlation_length(const NoiseColumns& c, double spacing) {
  if (c.empty() || c.n < 4) throw Error("correlation: need columns of at least 4 samples");
  const std::size_t n = c.n;
  std::array<double, kLagBlock> block = summed_autocovariance32(c, 0);
  const double c0 = block[0];
  if (!(c0 > 0)) return 0.0;
  const double target = std::exp(-1.0);
  double prev = 1.0;
  for (std::size_t lag = 1; lag < n / 2; ++lag) {
    if (lag % kLagBlock == 0) block = summed_autocovariance32(c, lag);
    const double rho = block[lag % kLagBlock] / c0;
    if (rho < target) {
      // Linear interpolation between lag − 1 (ρ = prev ≥ e⁻¹) and lag.
      const double frac = (prev - target) / (prev - rho);
      return (static_cast<double>(lag - 1) + frac) * spacing;
    }
    prev = rho;
  }
  return static_cast<double>(n / 2 - 1) * spacing;
}

std::vector<double> mean_autocorrelation(const NoiseColumns& c) {
  if (c.empty() || c.n < 4) throw Error("correlation: need columns of at least 4 samples");
  const std::size_t n = c.n, half = n / 2;
  std::vector<double> acf(n, 0.0);
  for (std::size_t lag0 = 0; lag0 < half; lag0 += kLagBlock) {
    const auto block = summed_autocovariance32(c, lag0);
    for (std::size_t q = 0; q < kLagBlock && lag0 + q < half; ++q) acf[lag0 + q] = block[q];
  }
  const double c0 = acf[0];
  if (!(c0 > 0)) throw Error("autocorrelation: the noise data are constant");
  for (std::size_t lag = 0; lag < half; ++lag) acf[lag] /= c0;
  // Mirror: lags N/2 + 1 … N − 1 are lags N/2 − 1 … 1.
  for (std::size_t lag = half + 1; lag < n; ++lag) acf[lag] = acf[n - lag];
  // Lag N/2: mean of its neighbours (lags N/2 − 1 and N/2 + 1, equal after mirroring).
  acf[half] = 0.5 * (acf[half - 1] + acf[(half + 1) % n]);
  return acf;
}

}  // namespace detail

namespace {
detail::NoiseColumns centred(const std::vector<std::vector<double>>& columns) {
  if (columns.empty() || columns.front().size() < 4) throw Error("correlation: need columns of at least 4 samples");
  detail::NoiseColumns c(columns.size(), columns.front().size());
  for (std::size_t k = 0; k < c.count; ++k) {
    if (columns[k].size() != c.n) throw Error("correlation: columns differ in length");
    std::copy(columns[k].begin(), columns[k].end(), c.column(k));
  }
  detail::centre(c);
  return c;
}
}  // namespace

double correlation_length(const std::vector<std::vector<double>>& columns, double spacing) {
  return detail::correlation_length(centred(columns), spacing);
}

std::vector<double> mean_autocorrelation(const std::vector<std::vector<double>>& columns) {
  return detail::mean_autocorrelation(centred(columns));
}

}  // namespace plumage
