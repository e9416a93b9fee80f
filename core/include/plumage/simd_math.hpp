// sincos and exp over four doubles at once (header-only; used by the multilayer lanes and the
// far-field kernel), written with GCC/Clang vector extensions so they compile to AVX2 (or to
// scalar code on machines without it) without depending on the auto-vectoriser; glibc's scalar
// sin/cos/exp are opaque calls that would block vectorisation.
// Accuracy: ≤ 2 ulp against glibc (tests check it) for |x| ≤ 1e5 (Cody–Waite reduction with a
// three-part π/2, Taylor polynomials of order 17/18 on [−π/4, π/4]); callers fall back to the
// scalar library beyond that range.
#pragma once

#include <cstdint>

namespace plumage::simd {

using v4d = double __attribute__((vector_size(32)));
using v4i = std::int64_t __attribute__((vector_size(32)));

inline constexpr double kMaxReducibleArgument = 1e5;

inline v4d splat(double x) { return v4d{x, x, x, x}; }

// Round to the nearest integer (|x| < 2^51) by adding and removing 1.5·2^52.
inline v4d round_nearest(v4d x) {
  const v4d magic = splat(6755399441055744.0);
  return (x + magic) - magic;
}

// The integer value of an exactly integral x (|x| < 2^51), as int64 lanes.
inline v4i to_int(v4d integral) {
  const v4d magic = splat(6755399441055744.0);
  return reinterpret_cast<v4i>(integral + magic) - reinterpret_cast<v4i>(magic);
}

inline void sincos(v4d x, v4d& s, v4d& c) {
  const v4d k = round_nearest(x * 0.63661977236758134308);  // x·2/π
  // π/2 in three parts whose products with k ≤ 2^17 are exact.
  const v4d r = ((x - k * 1.5707963267341256e+00) - k * 6.0771005065061922e-11) -
                k * 2.0222662487959506e-21;
  const v4d r2 = r * r;
  v4d sp = splat(1.0 / 355687428096000.0);  // 1/17!
  sp = sp * r2 - 1.0 / 1307674368000.0;     // 1/15!
  sp = sp * r2 + 1.0 / 6227020800.0;        // 1/13!
  sp = sp * r2 - 1.0 / 39916800.0;          // 1/11!
  sp = sp * r2 + 1.0 / 362880.0;            // 1/9!
  sp = sp * r2 - 1.0 / 5040.0;              // 1/7!
  sp = sp * r2 + 1.0 / 120.0;               // 1/5!
  sp = sp * r2 - 1.0 / 6.0;                 // 1/3!
  const v4d sin_r = r + r * r2 * sp;
  v4d cp = splat(1.0 / 6402373705728000.0);  // 1/18!
  cp = cp * r2 - 1.0 / 20922789888000.0;     // 1/16!
  cp = cp * r2 + 1.0 / 87178291200.0;        // 1/14!
  cp = cp * r2 - 1.0 / 479001600.0;          // 1/12!
  cp = cp * r2 + 1.0 / 3628800.0;            // 1/10!
  cp = cp * r2 - 1.0 / 40320.0;              // 1/8!
  cp = cp * r2 + 1.0 / 720.0;                // 1/6!
  cp = cp * r2 - 1.0 / 24.0;                 // 1/4!
  cp = cp * r2 + 0.5;                        // 1/2!
  const v4d cos_r = 1.0 - r2 * cp;
  // Quadrant k mod 4 selects and negates.
  const v4i q = to_int(k) & 3;
  const v4i odd = (q & 1) != 0;
  const v4d s0 = odd ? cos_r : sin_r;
  const v4d c0 = odd ? sin_r : cos_r;
  s = (q & 2) != 0 ? -s0 : s0;
  c = ((q + 1) & 2) != 0 ? -c0 : c0;
}

// exp(x) for x ≤ 0 (decay factors); exactly 0 below −708.
inline v4d exp_nonpositive(v4d x) {
  const v4d xc = x < -708.0 ? splat(-708.0) : x;
  const v4d n = round_nearest(xc * 1.4426950408889634074);
  const v4d r = (xc - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
  v4d p = splat(1.0 / 6227020800.0);  // 1/13!
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^n through the exponent bits (n ≥ −1022 after the clamp).
  const v4d scale = reinterpret_cast<v4d>((to_int(n) + 1023) << 52);
  return x < -708.0 ? splat(0.0) : p * scale;
}

}  // namespace plumage::simd
