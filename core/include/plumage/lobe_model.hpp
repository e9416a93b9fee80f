// The lobe model shared by fitting and rendering (paper §5, Eqs. 11–13; spec geometry-and-brdf
// §3). Frame of conventions.hpp: x across the barbule, y along its axis, z the macro normal;
// ω = (cos θ sin φ, sin θ, cos θ cos φ), ω_i toward the light.
//
//   ω_i' = (cos θ_i sin φ_c, sin θ_i, cos θ_i cos φ_c)   incident direction, azimuth replaced by φ_c
//   h    = (ω_i' + ω_o)/|ω_i' + ω_o|
//   D    = m² / (π (m² + (1 − m²) h_x²)²)                 GGX with h_z² → 1 − h_x² (exact when h_y = 0)
//   D_y  = exp(−h_y²/σ²)                                  spread out of the specular cone
//   G1   = 2 / (1 + sqrt(1 + m²(1 − ω_z²)/ω_z²))          Smith GGX
//   L    = F · D · D_y · G1(ω_i') · G1(ω_o) / (4 ω_i'_z)   = f_r(ω_i, ω_o) · ω_o,z
//
// L is the *cosine-weighted* BRDF: it integrates over the hemisphere (dω) to the directional
// albedo. The BRDF itself is f_r = L / ω_o,z.
#pragma once

#include <cmath>

#include "plumage/conventions.hpp"

namespace plumage {

// σ, the spread of D_y out of the specular cone, of every fitted lobe (spec §4.3): declared once
// here; a characterisation may set another (its `sigma` parameter), stored in the material.
inline constexpr double kLobeSigma = 0.04;

struct Lobe {
  double m = 0.1;          // GGX roughness, [0.001, 1]
  double phi_c_rad = 0.0;  // effective incident azimuth φ_c
  double sigma = kLobeSigma;  // spread of D_y across the cone
  double scale = 1.0;      // F
};

namespace lobe {

inline double ggx_d(double hx, double m) {
  const double m2 = m * m;
  const double q = m2 + (1.0 - m2) * hx * hx;
  return m2 / (kPi * q * q);
}

inline double smith_g1(double cos_z, double m) {
  if (cos_z <= 0.0) return 0.0;
  const double c2 = cos_z * cos_z;
  return 2.0 / (1.0 + std::sqrt(1.0 + m * m * (1.0 - c2) / c2));
}

// ω_i' of a lobe for the incident longitudinal angle θ_i.
inline Direction effective_incident(double theta_i_rad, double phi_c_rad) {
  return direction_from_angles(theta_i_rad, phi_c_rad);
}

}  // namespace lobe

// L(ω_o) for one lobe and θ_i at many ω_o: ω_i' and G1(ω_i') computed once (the integrals and
// cone sums of the fitter evaluate ~10⁴ directions per lobe). Same operations as a one-off
// evaluation, hence the same numbers.
class LobeEvaluator {
 public:
  LobeEvaluator(const Lobe& l, double theta_i_rad)
      : l_(l), wi_(lobe::effective_incident(theta_i_rad, l.phi_c_rad)),
        g1i_(wi_.z > 0.0 ? lobe::smith_g1(wi_.z, l.m) : 0.0) {}

  // L(ω_o) (cosine-weighted); 0 below the horizon.
  double operator()(const Direction& wo) const {
    if (wo.z <= 0.0) return 0.0;
    if (wi_.z <= 0.0) return 0.0;
    double hx = wi_.x + wo.x, hy = wi_.y + wo.y, hz = wi_.z + wo.z;
    const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
    if (!(len > 0.0)) return 0.0;
    hx /= len, hy /= len, hz /= len;
    const double dy = std::exp(-(hy * hy) / (l_.sigma * l_.sigma));
    return l_.scale * lobe::ggx_d(hx, l_.m) * dy * g1i_ * lobe::smith_g1(wo.z, l_.m) / (4.0 * wi_.z);
  }

 private:
  Lobe l_;
  Direction wi_;
  double g1i_;
};

// L(ω_o) (cosine-weighted); 0 below the horizon.
inline double lobe_value(const Lobe& l, double theta_i_rad, const Direction& wo) {
  return LobeEvaluator(l, theta_i_rad)(wo);
}

}  // namespace plumage
