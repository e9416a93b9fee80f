// Direction sets, incident polarizations and FarField normalisation (paper Eqs. 8–10).
#include "plumage/far_field.hpp"

#include <cmath>

namespace plumage {

PlaneWavePolarization incident_polarization(int pol, const IncidentDirection& incident) {
  const double st = std::sin(incident.theta_rad), ct = std::cos(incident.theta_rad);
  const double sp = std::sin(incident.phi_rad), cp = std::cos(incident.phi_rad);
  const std::array<double, 3> e1{-st * sp, ct, -st * cp};
  const std::array<double, 3> e2{-cp, 0.0, sp};
  if (pol == 0) return {e1, {cp, 0.0, -sp}};  // η0 H¹ = −E²
  return {e2, e1};                            // η0 H² = E¹
}

DirectionSet pattern_directions(int count) {
  DirectionSet set;
  set.kind = DirectionSetKind::pattern;
  for (int k = 0; k < count; ++k) {
    set.phi_o_rad.push_back(-0.5 * kPi + (k + 0.5) * kPi / count);
    set.sample_index.push_back(k);
  }
  return set;
}

DirectionSet projected_directions(double theta_i_rad, int count) {
  DirectionSet set;
  set.kind = DirectionSetKind::projected;
  const double c = std::cos(theta_i_rad);
  for (int k = 0; k < count; ++k) {
    const double x = -1.0 + (2.0 * k + 1.0) / count;
    if (std::abs(x) > c) continue;
    set.phi_o_rad.push_back(std::asin(x / c));
    set.sample_index.push_back(k);
  }
  return set;
}

DirectionSet full_circle_directions(int count) {
  DirectionSet set;
  set.kind = DirectionSetKind::full_circle;
  for (int k = 0; k < count; ++k) {
    set.phi_o_rad.push_back(-kPi + 2.0 * kPi * k / count);
    set.sample_index.push_back(k);
  }
  return set;
}

double FarField::reflectance_density(int pol, std::size_t direction) const {
  const auto& f = field[pol][direction];
  const double intensity = std::norm(f[0]) + std::norm(f[1]) + std::norm(f[2]);
  if (!(incident_power[pol] > 0.0)) return 0.0;
  return std::cos(incident.theta_rad) * intensity / (2.0 * kEta0_ohm * incident_power[pol]);
}

double FarField::reflected_fraction(int pol, double bin_width_rad) const {
  double sum = 0.0;
  for (std::size_t j = 0; j < phi_o_rad.size(); ++j) sum += reflectance_density(pol, j);
  return sum * bin_width_rad;
}

}  // namespace plumage
