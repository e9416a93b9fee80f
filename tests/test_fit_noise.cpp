// Correlation length (spec §4.6) and the noise pool (§4.8): synthetic data with known
// autocorrelation.
#include <catch2/catch.hpp>

#include <cmath>

#include "plumage/fitter.hpp"
#include "plumage/random.hpp"

using namespace plumage;

namespace {
// Circular AR(1)-like columns: x_t = a x_{t−1} + √(1 − a²) e_t (burn-in so the start is
// stationary); ACF ρ(k) = a^k, so ρ drops to e⁻¹ at k = −1/ln a.
std::vector<std::vector<double>> ar1_columns(double a, int columns, int n, std::uint64_t seed) {
  std::vector<std::vector<double>> c(columns, std::vector<double>(n));
  for (int k = 0; k < columns; ++k) {
    RandomStream rng(seed, "ar1-" + std::to_string(k));
    double x = rng.normal();
    for (int t = 0; t < 200; ++t) x = a * x + std::sqrt(1 - a * a) * rng.normal();
    for (int t = 0; t < n; ++t) c[k][t] = x = a * x + std::sqrt(1 - a * a) * rng.normal();
  }
  return c;
}
}  // namespace

// Circular moving average of L white samples: exactly stationary on the circle, with the
// triangular ACF ρ(k) = 1 − k/L (k ≤ L), so linear interpolation between lags is exact.
std::vector<std::vector<double>> moving_average_columns(int L, int columns, int n, std::uint64_t seed) {
  std::vector<std::vector<double>> c(columns, std::vector<double>(n, 0.0));
  for (int k = 0; k < columns; ++k) {
    RandomStream rng(seed, "ma-" + std::to_string(k));
    std::vector<double> e(n);
    for (double& v : e) v = rng.normal();
    for (int t = 0; t < n; ++t)
      for (int j = 0; j < L; ++j) c[k][t] += e[(t + j) % n] / std::sqrt(double(L));
  }
  return c;
}

TEST_CASE("correlation length of a noise with known autocorrelation", "[fit][fit-noise]") {
  const int n = 1024;
  const double spacing = 2.0 / n;
  for (int L : {8, 16, 32}) {
    const auto cols = moving_average_columns(L, 200, n, 11);
    // Removing each column's mean lowers the expected autocovariance by Var(mean) = L/N (Σρ/N),
    // so the estimator's ρ̂ = (ρ − L/N)/(1 − L/N) crosses e⁻¹ where
    // ρ = e⁻¹(1 − L/N) + L/N, i.e. at lag L(1 − ρ).
    const double rho = std::exp(-1.0) * (1.0 - double(L) / n) + double(L) / n;
    const double expected = L * (1.0 - rho) * spacing;
    // Sampling error of ρ̂ near the crossing: std ≈ √(Σ_k ρ(k)² / (N · columns)) = √(2L/3 / (N · 200));
    // divided by the slope 1/L and the length L(1 − ρ): relative std 0.8 % (L = 8) … 1.6 % (L = 32).
    const double rel_std = std::sqrt(2.0 * L / 3.0 / (n * 200.0)) / (1.0 - rho);
    INFO("L = " << L << ", 3 sigma = " << 3 * rel_std);
    CHECK(correlation_length(cols, spacing) == Approx(expected).epsilon(3 * rel_std));
  }
  // White noise: ρ(1) ≈ 0, so l < one lag.
  CHECK(correlation_length(ar1_columns(0.0, 50, 512, 3), 1.0) < 1.0);
}

TEST_CASE("mean autocorrelation: normalised, mirrored, matches the generating process", "[fit][fit-noise]") {
  const double a = 0.9;
  const auto acf = mean_autocorrelation(ar1_columns(a, 200, 1024, 5));
  REQUIRE(acf.size() == 1024);
  CHECK(acf[0] == Approx(1.0).margin(1e-15));
  for (int k = 1; k < 512; ++k) CHECK(acf[k] == acf[1024 - k]);
  for (int k = 1; k <= 10; ++k) CHECK(acf[k] == Approx(std::pow(a, k)).margin(0.03));
}

TEST_CASE("noise pool: zero mean, unit variance, target autocorrelation, deterministic", "[fit][fit-noise]") {
  // Target: Gaussian ACF with a 6-sample width, circular over 1024 samples.
  const int n = 1024;
  std::vector<double> acf(n);
  for (int k = 0; k < n; ++k) {
    const double d = std::min(k, n - k);
    acf[k] = std::exp(-d * d / (2 * 6.0 * 6.0));
  }
  const NoisePool pool = synthesize_noise_pool(acf, 512, 1234);
  REQUIRE(pool.count() == 512);
  REQUIRE(pool.samples == n);
  std::vector<double> measured(21, 0.0);
  double worst_mean = 0, worst_var = 0;
  for (std::size_t f = 0; f < pool.count(); ++f) {
    const float* p = pool.function(f);
    double mean = 0, var = 0;
    for (int t = 0; t < n; ++t) mean += p[t];
    mean /= n;
    for (int t = 0; t < n; ++t) var += (p[t] - mean) * (p[t] - mean);
    var /= n;
    worst_mean = std::max(worst_mean, std::abs(mean));
    worst_var = std::max(worst_var, std::abs(var - 1.0));
    for (int k = 0; k <= 20; ++k) {
      double s = 0;
      for (int t = 0; t < n; ++t) s += double(p[t]) * p[(t + k) % n];
      measured[k] += s / n / static_cast<double>(pool.count());
    }
  }
  CHECK(worst_mean < 1e-6);  // float rounding of exactly zero-mean functions
  CHECK(worst_var < 1e-5);
  // Zero mean costs the DC share of the spectrum, PSD_0 = Σρ/N (1.5 % here): a zero-mean
  // periodic function's ACF sums to zero, so the pool reproduces ρ' = (ρ − PSD_0)/(1 − PSD_0).
  double psd0 = 0;
  for (double v : acf) psd0 += v;
  psd0 /= n;
  for (int k = 0; k <= 20; ++k) {
    INFO("lag " << k);
    CHECK(measured[k] == Approx((acf[k] - psd0) / (1 - psd0)).margin(0.01));
  }
  CHECK(pool.lag1 == Approx((acf[1] - psd0) / (1 - psd0)).margin(0.01));
  const NoisePool again = synthesize_noise_pool(acf, 512, 1234);
  CHECK(again.functions == pool.functions);
  CHECK(synthesize_noise_pool(acf, 4, 1235).functions != std::vector<float>(pool.functions.begin(), pool.functions.begin() + 4 * n));
}
