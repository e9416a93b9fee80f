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
// so the pool depends on (seed, ρ, count) only. FFTW (FFTW_ESTIMATE) runs on the one process
// that assembles the material, so single, sharded and MPI runs on one machine agree bit for bit.
#include <fftw3.h>

#include <cmath>
#include <complex>
#include <mutex>

#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "plumage/random.hpp"

namespace plumage {

namespace {
std::mutex& fftw_planner_mutex() {  // FFTW's planner is not thread-safe
  static std::mutex m;
  return m;
}
}  // namespace

NoisePool synthesize_noise_pool(const std::vector<double>& acf, int count, std::uint64_t seed) {
  const int n = static_cast<int>(acf.size());
  if (n < 8 || n % 2 != 0) throw Error("noise synthesis: the autocorrelation needs an even length >= 8");
  if (count < 1) throw Error("noise synthesis: count must be >= 1");

  // Power spectrum of ρ (real input → half spectrum).
  std::vector<double> in(acf);
  std::vector<std::complex<double>> spec(n / 2 + 1);
  std::vector<double> out(n);
  fftw_plan forward, backward;
  {
    std::lock_guard lock(fftw_planner_mutex());
    forward = fftw_plan_dft_r2c_1d(n, in.data(), reinterpret_cast<fftw_complex*>(spec.data()), FFTW_ESTIMATE);
    backward = fftw_plan_dft_c2r_1d(n, reinterpret_cast<fftw_complex*>(spec.data()), out.data(), FFTW_ESTIMATE);
  }
  fftw_execute(forward);
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
    fftw_execute_dft_c2r(backward, reinterpret_cast<fftw_complex*>(spec.data()), out.data());
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
  {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(forward);
    fftw_destroy_plan(backward);
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
