// Closed-form integrals of a linear (tent) basis against a plane-wave phase over one segment:
//   A(u) = ∫₀¹ (1 − t) e^{iut} dt,   B(u) = ∫₀¹ t e^{iut} dt,
// so that the integral over a segment of length h of a linearly interpolated amplitude times
// e^{i(ψ_a + u·l/h)} is h·e^{iψ_a}·(A(u)·X_a + B(u)·X_b). This replaces a per-segment Gauss rule
// (and its extra complex exponentials) by exact integrals of the tent interpolant.
//
// Evaluated as power series split into even and odd parts, polynomials in u² of degree 7
// (terms to u¹⁵): truncation below 1/17! ≈ 3e-15 relative for |u| ≤ kTaylorRange = 1, no
// division and no branch, four segments at a time (30 nm segments give |u| ≤ 0.95 down to
// λ = 400 nm). Callers take the closed form beyond it.
#pragma once

#include <complex>

#include "plumage/simd_math.hpp"

namespace plumage::detail {

inline constexpr double kTaylorRange = 1.0;

// Coefficients of A_re, A_im/u, B_re, B_im/u in powers of u² (from A = Σ (iu)^n/(n+2)!,
// B = Σ (n+1)(iu)^n/(n+2)!).
inline constexpr double k_ar[8] = {0.5, -0.041666666666666664, 0.0013888888888888889, -2.4801587301587302e-05, 2.7557319223985888e-07, -2.08767569878681e-09, 1.1470745597729725e-11, -4.7794773323873853e-14};
inline constexpr double k_ai[8] = {0.16666666666666666, -0.0083333333333333332, 0.00019841269841269841, -2.7557319223985893e-06, 2.505210838544172e-08, -1.6059043836821613e-10, 7.6471637318198164e-13, -2.8114572543455206e-15};
inline constexpr double k_br[8] = {0.5, -0.125, 0.0069444444444444441, -0.00017361111111111112, 2.4801587301587302e-06, -2.296443268665491e-08, 1.4911969277048643e-10, -7.1692159985810778e-13};
inline constexpr double k_bi[8] = {0.33333333333333331, -0.033333333333333333, 0.0011904761904761906, -2.2045855379188714e-05, 2.5052108385441718e-07, -1.9270852604185937e-09, 1.0706029224547743e-11, -4.498331606952833e-14};

inline simd::v4d horner(const double (&c)[8], simd::v4d x) {
  simd::v4d p = simd::splat(c[7]);
  for (int m = 6; m >= 0; --m) p = p * x + c[m];
  return p;
}

inline void tent_weights_series(simd::v4d u, simd::v4d& a_re, simd::v4d& a_im, simd::v4d& b_re,
                                simd::v4d& b_im) {
  const simd::v4d u2 = u * u;
  a_re = horner(k_ar, u2);
  a_im = u * horner(k_ai, u2);
  b_re = horner(k_br, u2);
  b_im = u * horner(k_bi, u2);
}

// B alone: A follows from it by the mirror identity A(u) = e^{iu}·conj(B(u)) (substitute
// t → 1 − t; u real), which FactoredTentKernel uses to evaluate one series instead of two.
inline void tent_weight_b_series(simd::v4d u, simd::v4d& b_re, simd::v4d& b_im) {
  const simd::v4d u2 = u * u;
  b_re = horner(k_br, u2);
  b_im = u * horner(k_bi, u2);
}

// Closed form for any u (used where |u| > kTaylorRange): E0 = (z − 1)/(iu),
// B = z/(iu) + (z − 1)/u², A = E0 − B with z = e^{iu}.
inline void tent_weights_closed(double u, std::complex<double>& a, std::complex<double>& b) {
  const std::complex<double> iu{0.0, u}, z = std::polar(1.0, u);
  const std::complex<double> e0 = (z - 1.0) / iu;
  b = z / iu + (z - 1.0) / (u * u);
  a = e0 - b;
}

}  // namespace plumage::detail
