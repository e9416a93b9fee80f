// The error metric every solver comparison reports (plumage compare, the accuracy ladder, the
// stability and convergence tests): the unpolarised reflectance density U(φ_o) of Eq. 10 and the
// relative L2 distance of two such patterns on the same directions.
#pragma once

#include <vector>

#include "plumage/far_field.hpp"

namespace plumage {

// U(φ_o) = (U_1 + U_2) / 2 per direction of the far field.
std::vector<double> unpolarised_density(const FarField& f);

// ‖a − ref‖₂ / ‖ref‖₂ (NaN when ref is zero).
double relative_l2(const std::vector<double>& a, const std::vector<double>& ref);

// relative_l2 of the two far fields' unpolarised densities.
double unpolarised_relative_l2(const FarField& a, const FarField& ref);

}  // namespace plumage
