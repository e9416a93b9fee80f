#include "plumage/pattern_metrics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace plumage {

std::vector<double> unpolarised_density(const FarField& f) {
  std::vector<double> u(f.phi_o_rad.size());
  for (std::size_t j = 0; j < u.size(); ++j) u[j] = 0.5 * (f.reflectance_density(0, j) + f.reflectance_density(1, j));
  return u;
}

double relative_l2(const std::vector<double>& a, const std::vector<double>& ref) {
  if (a.size() != ref.size()) throw std::invalid_argument("relative_l2: patterns on different direction sets");
  double num = 0.0, den = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    num += (a[j] - ref[j]) * (a[j] - ref[j]);
    den += ref[j] * ref[j];
  }
  return den > 0.0 ? std::sqrt(num / den) : std::numeric_limits<double>::quiet_NaN();
}

double unpolarised_relative_l2(const FarField& a, const FarField& ref) {
  return relative_l2(unpolarised_density(a), unpolarised_density(ref));
}

}  // namespace plumage
