// Physical conventions shared by every solver in plumage. Declared once, here.
//
// Time convention: fields are Re{ F(r) e^{-iωt} } (the physics convention). A passive, absorbing
// medium therefore has a refractive index n = n' + iκ with κ ≥ 0, a plane wave e^{+i k·r}
// travels along k, and a wave decaying into a medium has Im k_z ≥ 0. The paper writes melanin as
// 1.648 + 23700/λ² + j·0.56·e^{-λ/270} with e^{-jωt}; that is the same sign of the imaginary part.
// Solvers that are easier to derive in the engineering convention (e^{+jωt}) must convert at
// their boundary (i → −j, H^(1) → H^(2)) and report in this one.
//
// Frame (paper Fig. 6): barbule axis y, macro-surface normal z, cross section in the xz-plane.
//   ω(θ, φ) = (cos θ sin φ, sin θ, cos θ cos φ),
// θ the longitudinal angle out of the xz-plane, φ the azimuth in it measured from +z toward +x.
// ω_i points toward the light. The specular cone of ω_i ~ (θ_i, φ_i) is ω_o ~ (−θ_i, φ_o).
//
// Units: lengths in nanometres unless a name says otherwise (`_um`); λ is the vacuum wavelength
// in nm; angles in radians unless a name ends in `_deg`.
#pragma once

#include <cmath>
#include <complex>
#include <numbers>

namespace plumage {

using Complex = std::complex<double>;

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kSpeedOfLight_m_per_s = 299'792'458.0;
inline constexpr double kMu0_H_per_m = 4e-7 * std::numbers::pi;
// Impedance of free space η0 = μ0·c0.
inline constexpr double kEta0_ohm = kMu0_H_per_m * kSpeedOfLight_m_per_s;

inline constexpr double deg_to_rad(double deg) { return deg * (kPi / 180.0); }
inline constexpr double rad_to_deg(double rad) { return rad * (180.0 / kPi); }

// Vacuum wavenumber k0 = 2π/λ in rad per nm.
inline constexpr double wavenumber_per_nm(double lambda_nm) { return 2.0 * kPi / lambda_nm; }

struct Direction {
  double x = 0, y = 0, z = 1;
};

// ω(θ, φ) of the frame above.
inline Direction direction_from_angles(double theta_rad, double phi_rad) {
  return {std::cos(theta_rad) * std::sin(phi_rad), std::sin(theta_rad),
          std::cos(theta_rad) * std::cos(phi_rad)};
}

}  // namespace plumage
