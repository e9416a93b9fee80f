#include <algorithm>

#include "plumage/scene.hpp"

namespace plumage {

double TabulatedSpectrum::at(double lambda) const {
  if (value.empty()) return 0.0;
  if (value.size() == 1 || lambda <= lambda_nm.front()) return value.front();
  if (lambda >= lambda_nm.back()) return value.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(lambda_nm.begin(), lambda_nm.end(), lambda) - lambda_nm.begin());
  const std::size_t lo = hi - 1;
  const double t = (lambda - lambda_nm[lo]) / (lambda_nm[hi] - lambda_nm[lo]);
  return value[lo] + t * (value[hi] - value[lo]);
}

}  // namespace plumage
