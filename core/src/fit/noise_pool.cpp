// Noise-function synthesis (spec §4.8): stationary Gaussian functions with a measured
// autocorrelation ρ, by random-phase spectral synthesis through FFTW.
//
// PSD_k = |DFT(ρ)|_k / N. Coefficients c_k = √PSD_k (g_k + i g'_k), g, g' ~ N(0, ½), for
// k = 1 … N/2 − 1, c_{N−k} = conj(c_k); unlike the reference, c_0 = 0 and c_{N/2} = 0, so every
// function sums to exactly zero (before rounding). n(t) = Σ_k c_k e^{2πikt/N} (no 1/N). Each
// function is then shifted by its mean and scaled by its population standard deviation (in
// double precision, then rounded to float: residual mean and variance error ~1e-7), so the pool is zero-mean and unit-variance function by function (the reference's
// functions have variance Σ PSD ≈ 1 only on average). The per-function scaling changes ρ by the
// sampling spread of the variance only (tests/test_fit_noise.cpp measures it).
//
// Random numbers: function k uses RandomStream(seed, k); values are drawn in a fixed order,
// so the pool depends on (seed, ρ, count) only. FFTW runs with estimate plans and scalar codelets
// (fft/real_fft.hpp), so the pool is the same bits on every machine.
#include <cmath>
#include <complex>

#include "fft/real_fft.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "plumage/random.hpp"

namespace plumage {

NoisePool synthesize_noise_pool(const std::vector<double>& acf, int count, std::uint64_t seed) {
  const int n = static_cast<int>(acf.size());
  if (n < 8 || n % 2 != 0) throw Error("noise synthesis: the autocorrelation needs an even length >= 8");
  if (count < 1) throw Error("noise synthesis: count must be >= 1");

  // Power spectrum of ρ (real input → half spectrum).
  const detail::RealFft fft(static_cast<std::size_t>(n));
  std::vector<std::complex<double>> spec;
  std::vector<double> out;
  fft.forward(acf, spec);
  std::vector<double> amplitude(n / 2 + 1);
  for (int k = 0; k <= n / 2; ++k) amplitude[k] = std::sqrt(std::abs(spec[k]) / n);

  NoisePool pool;
  pool.samples = n;
  pool.functions.resize(static_cast<std::size_t>(count) * static_cast<std::size_t>(n));
  for (int f = 0; f < count; ++f) {
    RandomStream rng(seed, "noise-function-" + std::to_string(f));
    spec[0] = 0.0;
    spec[n / 2] = 0.0;
    const double s = std::sqrt(0.5);
    for (int k = 1; k < n / 2; ++k) {
      const double g = rng.normal() * s, g2 = rng.normal() * s;
      spec[k] = amplitude[k] * std::complex<double>(g, g2);
    }
    // c2r computes Σ_k c_k e^{+2πikt/N} over the full Hermitian spectrum, no 1/N.
    fft.inverse(spec, out);
    double mean = 0;
    for (double v : out) mean += v;
    mean /= n;
    double var = 0;
    for (double v : out) var += (v - mean) * (v - mean);
    var /= n;
    const double scale = var > 0 ? 1.0 / std::sqrt(var) : 0.0;
    float* dst = pool.functions.data() + static_cast<std::size_t>(f) * static_cast<std::size_t>(n);
    for (int t = 0; t < n; ++t) dst[t] = static_cast<float>((out[t] - mean) * scale);
  }
  // Lag-one correlation of the pool itself (for variance-preserving interpolation, §4.8 step 3).
  double c1 = 0, c0 = 0;
  for (int f = 0; f < count; ++f) {
    const float* p = pool.functions.data() + static_cast<std::size_t>(f) * static_cast<std::size_t>(n);
    for (int t = 0; t < n; ++t) {
      c0 += double(p[t]) * p[t];
      c1 += double(p[t]) * p[(t + 1) % n];
    }
  }
  pool.lag1 = c0 > 0 ? c1 / c0 : 0.0;
  return pool;
}

}  // namespace plumage
