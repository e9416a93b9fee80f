// Continuation of the specular Jones reflection from the simulated region (k_z/k0 ≥ kz_min) to
// the grazing limit k_z → 0, where the FDTD runs are expensive (zero group velocity at the air
// cut-off) and least accurate.
//
// Physics. Write κ = k_z/k0 = cos θ cos φ (direction cosine of ω_i on the outward normal). For
// any passive structure the reflection at fixed (k_x, k_y, ω) follows from a surface
// impedance of the structure that is analytic through the air light line; only the air side
// is singular there, through κ. For a layered medium (spec wave-simulation.md §2.4, Fresnel
// form) r_s = (κ − κ_2)/(κ + κ_2), r_p = (ε κ − κ_2)/(ε κ + κ_2) in the sign convention of
// our table (both → −1 at grazing, spec §3.2), i.e. r = (κ Z − 1)/(κ Z + 1) with Z = 1/κ_2 or
// ε/κ_2, smooth in the in-plane wavevector. The matrix form used here is the Cayley pair
//     J = (κ Z − I)(κ Z + I)⁻¹   ⇔   Z = (I + J)(I − J)⁻¹ / κ,
// which gives J = −I exactly at κ = 0 and r + 1 ∝ κ near it. Along a radial line of the
// in-plane wavevector k_∥ = k0 ρ (u_x, u_y), ρ = sqrt(1 − κ²), at fixed ω, the (s, p) basis
// keeps ŝ ⟂ u (the s direction does not turn), and Z depends on k_∥ = k0 sqrt(1 − κ²), i.e.
// smoothly on κ². So Z is sampled at anchor points on the entry's radial line inside the
// simulated region and continued as a polynomial in κ² (the measured errors are in NOTES.md §7
// and docs/validation.md §4).
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "plumage/local_reflection.hpp"

namespace plumage::fdtd_table {

struct GrazingAnchor {
  double kappa;       // k_z/k0 of the anchor
  JonesReflection J;  // Jones matrix there (its own (s, p) basis)
};

// κ of the anchors used for entries below kz_min: kz_min + 0.01 + m·0.05, m = 0 … count−1
// (0.26, 0.31 in production). An anchor without k-grid support falls back (table_build.cpp).
std::vector<double> anchor_kappas(double kz_min, int count = 2);

// (θ, φ) of the point with k_z/k0 = kappa on the radial k_∥ line through (θ, φ) (φ ≥ 0).
std::pair<double, double> radial_point(double theta_rad, double phi_rad, double kappa);

// Surface impedance of a Jones matrix at κ = k_z/k0 > 0: Z = (I + J)(I − J)⁻¹/κ, stored in a
// JonesReflection (ss, sp, ps, pp = Z's elements), and its inverse J = (κZ − I)(κZ + I)⁻¹.
// Z is smooth in (k_x, k_y) through the light line where J has a square-root branch point
// (κ = sqrt(1 − |k_∥|²/k0²)), so the k-grid interpolation works on Z (table_build.cpp).
JonesReflection impedance_of(const JonesReflection& J, double kappa);
JonesReflection jones_of(const JonesReflection& Z, double kappa);

// Jones matrix at κ from anchors (≥ 1; Z fitted as a polynomial in κ² of degree count − 1 through
// the anchors, exact interpolation). Returns exactly diag(−1, −1) at κ = 0.
JonesReflection continue_to_grazing(std::span<const GrazingAnchor> anchors, double kappa);

}  // namespace plumage::fdtd_table
