// The error metrics every solver comparison reports (plumage compare, the accuracy ladders, the
// stability and convergence tests): the reflectance density U(φ_o) of Eq. 10 per polarization
// or unpolarised, and how two such patterns on the same directions differ (relative L2 distance,
// Pearson correlation, reflected fractions).
#pragma once

#include <vector>

#include "plumage/far_field.hpp"

namespace plumage {

// U(φ_o) = (U_1 + U_2) / 2 per direction of the far field.
std::vector<double> unpolarised_density(const FarField& f);

// U_pol(φ_o) per direction for pol 0 or 1; pol 2 is the unpolarised mean (unpolarised_density).
std::vector<double> polarised_density(const FarField& f, int pol);

// ‖a − ref‖₂ / ‖ref‖₂ (NaN when ref is zero).
double relative_l2(const std::vector<double>& a, const std::vector<double>& ref);

// relative_l2 of the two far fields' unpolarised densities.
double unpolarised_relative_l2(const FarField& a, const FarField& ref);

// Pearson correlation of two patterns over their directions (NaN when either is constant).
double pattern_correlation(const std::vector<double>& a, const std::vector<double>& b);

// ∫ U dφ_o by the midpoint rule on bins of bin_rad: the reflected fraction (Eq. 8 over Eq. 9).
double reflected_fraction(const std::vector<double>& density, double bin_rad);

// A pattern against a reference pattern on the same bins.
struct PatternComparison {
  double correlation = 0.0;  // pattern_correlation(a, ref)
  double rel_l2 = 0.0;       // relative_l2(a, ref)
  double total = 0.0;        // reflected_fraction(a)
  double total_ref = 0.0;    // reflected_fraction(ref)
};
PatternComparison compare_patterns(const std::vector<double>& a, const std::vector<double>& ref, double bin_rad);

}  // namespace plumage
