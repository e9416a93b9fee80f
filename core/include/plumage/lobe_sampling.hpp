// Importance sampling of the feather lobe's half vector (paper §7.2; spec geometry-and-brdf §4.10,
// whose proposal this implements without tables).
//
// The lobe's normal distribution (paper Eq. 17, spec §3) is D = D'(h_x; m) · exp(−h_y²/σ²), a
// function of the half vector's x and y components only. We sample those two components on the
// projected unit disk, h_x² + h_y² ≤ 1, and set h_z = sqrt(1 − h_x² − h_y²):
//
//   h_y ~ exp(−h_y²/σ²) truncated to [−1, 1]          inverse CDF: σ·erfinv((2u − 1)·erf(1/σ))
//   h_x | h_y ~ (m² + (1 − m²) h_x²)⁻² on [−a, a],   a = sqrt(1 − h_y²)
//
// The h_x marginal has a closed-form CDF. With b = sqrt(1 − m²) and h_x = (m/b)·tan(s/2),
//   ∫_0^{h_x} (m² + b²t²)⁻² dt = (s + sin s) / (4 m³ b),
// so sampling solves s + sin s = c (monotone) by safeguarded Newton, and near the cut-off
// s → π the complementary form r − sin r with r = π − s keeps full precision for small m.
// Density on the projected disk: p_A(h_x, h_y) = N_σ(h_y) · p(h_x | h_y); per solid angle of h:
// p_h = p_A · h_z (dA = h_z dω). Note: spec §4.10 step 4 divides by h_z instead; the χ² tests
// (tests/test_bsdf_sampling.cpp) confirm the factor h_z.
#pragma once

#include "plumage/conventions.hpp"

namespace plumage {

class HalfVectorSampler {
 public:
  // m: GGX roughness (0, 1]; sigma: D_y spread (> 0).
  HalfVectorSampler(double m, double sigma);

  // (u1, u2) ∈ [0, 1)² → h on the upper unit hemisphere. u1 drives h_y, u2 drives h_x.
  Direction sample(double u1, double u2) const;
  // Density of sample() per unit projected area (h_x, h_y); 0 outside the unit disk.
  double pdf_projected(double hx, double hy) const;
  // Density per solid angle of h (h_z ≥ 0): pdf_projected · h_z.
  double pdf_solid_angle(const Direction& h) const;

  double m() const { return m_; }
  double sigma() const { return sigma_; }

 private:
  double sample_hy(double u) const;
  double sample_hx(double u, double a) const;
  double pdf_hy(double hy) const;
  double pdf_hx(double hx, double a) const;

  double m_, sigma_, b_;
  double erf_norm_;  // erf(1/σ): normalisation of the truncated Gaussian
  bool uniform_x_;   // m ≈ 1: the h_x marginal is uniform
};

// Reflection of ω about the unit vector h: 2(ω·h)h − ω.
inline Direction reflect(const Direction& w, const Direction& h) {
  const double d = 2.0 * (w.x * h.x + w.y * h.y + w.z * h.z);
  return {d * h.x - w.x, d * h.y - w.y, d * h.z - w.z};
}

// Density per solid angle of ω_o when h is drawn from `s` and ω_o = reflect(ω_e, h) (paper §7.2):
// p_h(h*) / (4 |ω_o · h*|), h* = ±(ω_e + ω_o)/|ω_e + ω_o| on the upper hemisphere. Every ω_o on
// the sphere has exactly one such h*, so this is the exact density of what sample() produces,
// below the horizon too (MIS-friendly).
double reflected_pdf(const HalfVectorSampler& s, const Direction& w_e, const Direction& w_o);

}  // namespace plumage
