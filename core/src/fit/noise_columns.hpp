// The noise data of a work unit as one flat array (spec §4.6 steps 1–3), and the correlation
// sums over it (correlation.cpp). fit_unit writes the columns straight into it; the public
// correlation_length / mean_autocorrelation (fitter.hpp) copy their vector-of-columns input in.
#pragma once

#include <cstddef>
#include <vector>

namespace plumage::detail {

// Lags summed per pass of the correlation sums (8 vectors of 4).
inline constexpr std::size_t kLagBlock = 32;

// `count` columns of `n` samples, each followed by kLagBlock more: after centre(), sample
// t < n + kLagBlock of a column is x[t mod n], so lags ℓ < kLagBlock read x[t + ℓ] without a wrap.
struct NoiseColumns {
  std::size_t n = 0, stride = 0, count = 0;
  std::vector<double> x;

  NoiseColumns() = default;
  NoiseColumns(std::size_t columns, std::size_t samples)
      : n(samples), stride(samples + kLagBlock), count(columns), x(columns * stride) {}
  double* column(std::size_t k) { return x.data() + k * stride; }
  const double* column(std::size_t k) const { return x.data() + k * stride; }
  bool empty() const { return count == 0; }
};

// Removes each column's mean (Σ x / n in sample order, then x − mean) and fills the wrap copy.
void centre(NoiseColumns& columns);
// correlation_length and mean_autocorrelation of fitter.hpp on centred columns.
double correlation_length(const NoiseColumns& centred, double spacing);
std::vector<double> mean_autocorrelation(const NoiseColumns& centred);

}  // namespace plumage::detail
