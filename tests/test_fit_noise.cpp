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

namespace {
// The plain definitions of spec §4.6 steps 4–5 and §4.8 step 2, with the index (t + lag) mod N,
// as the reference for the blocked sums of correlation.cpp.
std::vector<double> plain_summed_autocovariance(std::vector<std::vector<double>> c, std::size_t lags) {
  for (auto& col : c) {
    double mean = 0;
    for (double v : col) mean += v;
    mean /= static_cast<double>(col.size());
    for (double& v : col) v -= mean;
  }
  std::vector<double> s(lags, 0.0);
  const std::size_t n = c.front().size();
  for (std::size_t lag = 0; lag < lags; ++lag)
    for (const auto& col : c)
      for (std::size_t t = 0; t < n; ++t) s[lag] += col[t] * col[(t + lag) % n];
  return s;
}

double plain_correlation_length(const std::vector<std::vector<double>>& c, double spacing) {
  const std::size_t n = c.front().size();
  const auto s = plain_summed_autocovariance(c, n / 2);
  double prev = 1.0;
  for (std::size_t lag = 1; lag < n / 2; ++lag) {
    const double rho = s[lag] / s[0];
    if (rho < std::exp(-1.0)) return (static_cast<double>(lag - 1) + (prev - std::exp(-1.0)) / (prev - rho)) * spacing;
    prev = rho;
  }
  return static_cast<double>(n / 2 - 1) * spacing;
}
}  // namespace

TEST_CASE("correlation length and autocorrelation equal the plain circular sums", "[fit][fit-noise]") {
  // Lengths crossing e⁻¹ in the first block of 32 lags, in a later one (a = 0.99: ~100 lags) and
  // never (a = 0.9999 on 64 samples); column lengths odd, even, shorter than a block.
  struct Case { double a; int columns, n; };
  for (const Case& k : {Case{0.5, 7, 1024}, Case{0.95, 20, 1000}, Case{0.99, 10, 1025}, Case{0.9999, 5, 64},
                        Case{0.7, 3, 6}, Case{0.8, 4, 37}}) {
    const auto cols = ar1_columns(k.a, k.columns, k.n, 17);
    INFO("a = " << k.a << ", n = " << k.n);
    const double expected = plain_correlation_length(cols, 0.5);
    CHECK(correlation_length(cols, 0.5) == Approx(expected).epsilon(1e-12));
    if (k.n % 2 == 0) {
      const auto acf = mean_autocorrelation(cols);
      const auto s = plain_summed_autocovariance(cols, static_cast<std::size_t>(k.n / 2));
      for (int lag = 0; lag < k.n / 2; ++lag) CHECK(acf[lag] == Approx(s[lag] / s[0]).margin(1e-13));
    }
  }
}
