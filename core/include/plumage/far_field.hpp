// Far fields on the specular cone of a 2.5D scatterer (paper §4.4, Eqs. 7–10).
//
// A barbule is invariant along its axis y, so an incident plane wave ω_i ~ (θ_i, φ_i) scatters
// only into the cone ω_o ~ (−θ_i, φ_o) (conventions.hpp). Far away,
//   E(ρ, y) ≈ e^{iβy} e^{iγ0 ρ} ρ^{−1/2} 𝓔(φ_o),   β = −k0 sin θ_i, γ0 = k0 cos θ_i,
// and 𝓔 (V·m^{-1/2}) is what a FarField stores, per outgoing azimuth and polarization, for a
// unit-amplitude (1 V/m) incident plane wave. Power radiated per unit barbule length per unit
// φ_o is cos θ_i |𝓔|²/(2η0); divided by the incident power Φ_i intercepted by the top surface
// (Eq. 9) it is the reflectance density per radian (Eq. 10), which integrates over φ_o to the
// reflected fraction (Eq. 8 over Eq. 9).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "plumage/conventions.hpp"

namespace plumage {

struct IncidentDirection {
  double theta_rad = 0.0;  // longitudinal angle, out of the cross-section plane
  double phi_rad = 0.0;    // azimuth in the cross-section plane, from the macro normal +z
};

// The two incident polarizations, both unit amplitude, in the frame of conventions.hpp:
//   pol 1: E¹ = (−sin θ sin φ, cos θ, −sin θ cos φ)  (E along the barbule axis at θ = 0)
//          η0 H¹ = (cos φ, 0, −sin φ)
//   pol 2: E² = (−cos φ, 0, sin φ)                    (H along the axis at θ = 0)
//          η0 H² = E¹
// Both satisfy η0 H = k̂ × E with k̂ = −ω_i (propagation toward the surface).
struct PlaneWavePolarization {
  std::array<double, 3> e;
  std::array<double, 3> eta0_h;
};
PlaneWavePolarization incident_polarization(int pol, const IncidentDirection& incident);

// Outgoing azimuths on the specular cone.
enum class DirectionSetKind { pattern, projected, full_circle };

struct DirectionSet {
  DirectionSetKind kind = DirectionSetKind::pattern;
  std::vector<double> phi_o_rad;  // only the directions that lie on the cone
  // For `projected`: index of each direction in the full 1024-sample list of ω_o,x values.
  std::vector<int> sample_index;
};

// The paper's 400 bin centres on (−90°, 90°): φ_o,k = −90° + (k + ½)·180°/count.
DirectionSet pattern_directions(int count = 400);
// `count` samples uniform in ω_o,x ∈ (−1, 1), x_k = −1 + (2k + 1)/count, kept where
// |x_k| ≤ cos θ_i (φ_o = asin(x_k / cos θ_i)); used for noise statistics.
DirectionSet projected_directions(double theta_i_rad, int count = 1024);
// 1° steps around the full circle, for validation bodies.
DirectionSet full_circle_directions(int count = 360);

// 𝓔 for one instance, one wavelength, one incident direction, both polarizations.
struct FarField {
  double lambda_nm = 0.0;
  IncidentDirection incident;
  std::vector<double> phi_o_rad;
  std::array<std::vector<std::array<Complex, 3>>, 2> field;  // [pol][direction] (x, y, z)
  std::array<double, 2> incident_power{0.0, 0.0};            // Φ_i per pol, W per m of axis

  // Reflectance density per radian of φ_o (Eq. 10): cos θ_i |𝓔|² / (2η0 Φ_i).
  double reflectance_density(int pol, std::size_t direction) const;
  // ∫ density dφ_o over the directions, by the midpoint rule on the given (uniform) bins.
  double reflected_fraction(int pol, double bin_width_rad) const;
};

}  // namespace plumage
