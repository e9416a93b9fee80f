// Closed-form integrals of a linear (tent) basis against a plane-wave phase over one segment:
//   A(u) = ∫₀¹ (1 − t) e^{iut} dt,   B(u) = ∫₀¹ t e^{iut} dt,
// so that the integral over a segment of length h of a linearly interpolated amplitude times
// e^{i(ψ_a + u·l/h)} is h·e^{iψ_a}·(A(u)·X_a + B(u)·X_b). This replaces a per-segment Gauss rule
// (and its extra complex exponentials) by exact integrals of the tent interpolant. Four
// segments at a time (simd_math.hpp vectors).
#pragma once

#include "plumage/simd_math.hpp"

namespace plumage::detail {

// u: phase increments; z = e^{iu} (re, im), which the caller has from the endpoint phases.
inline void tent_weights(simd::v4d u, simd::v4d z_re, simd::v4d z_im, simd::v4d& a_re,
                         simd::v4d& a_im, simd::v4d& b_re, simd::v4d& b_im) {
  // Small |u|: Taylor series to u⁵ (truncation < 0.05⁶/8! ≈ 4e-13 relative).
  const simd::v4d u2 = u * u;
  const simd::v4d ta_re = 0.5 - u2 * (1.0 / 24.0) + u2 * u2 * (1.0 / 720.0);
  const simd::v4d ta_im = u * (1.0 / 6.0 - u2 * (1.0 / 120.0) + u2 * u2 * (1.0 / 5040.0));
  const simd::v4d tb_re = 0.5 - u2 * (1.0 / 8.0) + u2 * u2 * (1.0 / 144.0);
  const simd::v4d tb_im = u * (1.0 / 3.0 - u2 * (1.0 / 30.0) + u2 * u2 * (1.0 / 840.0));
  // Otherwise the closed forms E0 = (z − 1)/(iu), B = z/(iu) + (z − 1)/u², A = E0 − B
  // (rounding ≲ 1e-16/u² < 5e-14 for |u| ≥ 0.05).
  const simd::v4d small = simd::v4d{0.05, 0.05, 0.05, 0.05};
  const auto use_taylor = (u < small) & (u > -small);
  const simd::v4d safe_u = use_taylor ? simd::v4d{1.0, 1.0, 1.0, 1.0} : u;
  const simd::v4d inv = 1.0 / safe_u, inv2 = inv * inv;
  const simd::v4d e0_re = z_im * inv, e0_im = -(z_re - 1.0) * inv;
  const simd::v4d cb_re = z_im * inv + (z_re - 1.0) * inv2;
  const simd::v4d cb_im = -z_re * inv + z_im * inv2;
  b_re = use_taylor ? tb_re : cb_re;
  b_im = use_taylor ? tb_im : cb_im;
  a_re = use_taylor ? ta_re : e0_re - cb_re;
  a_im = use_taylor ? ta_im : e0_im - cb_im;
}

}  // namespace plumage::detail
