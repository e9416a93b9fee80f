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

std::vector<double> polarised_density(const FarField& f, int pol) {
  if (pol == 2) return unpolarised_density(f);
  if (pol != 0 && pol != 1) throw std::invalid_argument("polarised_density: pol must be 0, 1 or 2");
  std::vector<double> u(f.phi_o_rad.size());
  for (std::size_t j = 0; j < u.size(); ++j) u[j] = f.reflectance_density(pol, j);
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

double pattern_correlation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("pattern_correlation: patterns on different direction sets");
  const double n = static_cast<double>(a.size());
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= n;
  mb /= n;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa > 0.0) || !(sbb > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return sab / std::sqrt(saa * sbb);
}

double reflected_fraction(const std::vector<double>& density, double bin_rad) {
  double total = 0.0;
  for (double u : density) total += u * bin_rad;
  return total;
}

PatternComparison compare_patterns(const std::vector<double>& a, const std::vector<double>& ref, double bin_rad) {
  PatternComparison m;
  m.correlation = pattern_correlation(a, ref);
  m.rel_l2 = relative_l2(a, ref);
  m.total = reflected_fraction(a, bin_rad);
  m.total_ref = reflected_fraction(ref, bin_rad);
  return m;
}

}  // namespace plumage
