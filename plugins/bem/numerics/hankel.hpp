// plumage — 2.5D BEM numerics: Bessel/Hankel functions of order 0 and 1 for complex argument.
//
// Time convention e^{-i omega t}; H = H^(1) (outgoing). The BEM kernel is
//   G(R) = (i/4) H0^(1)(gamma R),  G'(R) = -(i gamma/4) H1^(1)(gamma R),
// with gamma = k0 sqrt(n^2 - sin^2 theta), Im gamma >= 0 (see spec wave-simulation.md §6.2, §6.5).
//
// Domain: designed for Re z >= 0 (both half planes; the first quadrant Im z >= 0 is the BEM case,
// the fourth quadrant is used internally for J and Y), 1e-300 < |z| < ~1e8.  Not valid for Re z < 0.
//
// Methods (see NOTES.md for the measured accuracy):
//  * "series" region  |z| + |Im z| <= 5: ascending power series of J0, J1, Y0, Y1 (Horner in z^2/4,
//    number of terms chosen from |z|), H = J + iY.  The bound on |z| + |Im z| keeps the cancellation
//    in J + iY (H1 is small, J and iY are large, when Im z > 0) to ~1e-14 relative.
//  * "table" region (outside the series region, |z| < 20): H_nu(z) = sqrt(2/(pi z)) e^{i(z - nu pi/2 - pi/4)} P_nu(z)
//    with P_0 expanded in a local Taylor series (18 terms) about the centre of a square cell
//    (side 0.5 for |z| < 10, side 1 for 10 <= |z| < 20); P_1 follows from P_0 and P_0' exactly.
//    The Taylor coefficients are built once (lazily, thread-safe, ~7 ms at -O2, 460 KB) in long double by
//    analytic continuation of the ODE  P'' + 2i P' - mu P / z^2 = 0 (mu = -1/4) from the
//    Hankel asymptotic series at Im z = 40, marching only in directions in which H^(1) is the
//    dominant solution (downwards in Im z, or horizontally), so the continuation is stable.
//  * "asymptotic" region |z| >= 20: Hankel's expansion sum_k i^k a_k(nu)/z^k with the number of
//    terms chosen from |z| (25 terms at |z| = 20, 10 at 100, 5 at 2000).
//
// J and Y outside the series region come from J = (H^(1)(z) + H^(2)(z))/2, Y = (H^(1) - H^(2))/(2i)
// with H^(2)(z) = conj(H^(1)(conj z)).

#pragma once

#include <complex>

namespace plumage::bem {

using cplx = std::complex<double>;

inline constexpr double kEulerGamma = 0.57721566490153286060651209008240243;

struct H01 {
    cplx h0;  // H0^(1)(z)
    cplx h1;  // H1^(1)(z)
};

struct JY01 {
    cplx j0, j1, y0, y1;
};

// H0^(1)(z) and H1^(1)(z) together (the fast path used by BEM assembly).
H01 hankel1_01(cplx z);
inline cplx hankel1_0(cplx z) { return hankel1_01(z).h0; }
inline cplx hankel1_1(cplx z) { return hankel1_01(z).h1; }

// J0, J1, Y0, Y1 (about twice the cost of hankel1_01 outside the series region).
JY01 bessel_jy01(cplx z);

// Regularised parts for the singular BEM integrals.
//   hankel1_1_reg(z) = H1^(1)(z) + 2i/(pi z)            (smooth: O(z ln z) as z -> 0)
//   green2d_reg(gamma, R) = (i/4) H0^(1)(gamma R) + ln(R)/(2 pi)
//       smooth in R, with green2d_reg(gamma, 0) = i/4 - (ln(gamma/2) + C_E)/(2 pi).
//   green2d_reg_deriv(gamma, R) = d/dR green2d_reg = -(i gamma/4) hankel1_1_reg(gamma R)
//       (so G'(R) = -1/(2 pi R) + green2d_reg_deriv).
// gamma may be complex (Im gamma >= 0, Re gamma > 0); R >= 0 (R = 0 allowed for green2d_reg;
// green2d_reg_deriv(gamma, 0) = 0).
cplx hankel1_1_reg(cplx z);
cplx green2d_reg(cplx gamma, double R);
cplx green2d_reg_deriv(cplx gamma, double R);
struct GreenReg {
    cplx g;   // green2d_reg(gamma, R)
    cplx dg;  // green2d_reg_deriv(gamma, R)
};
GreenReg green2d_reg_both(cplx gamma, double R);

// Full kernel and its R-derivative, for completeness: G = (i/4)H0(gamma R), dG/dR = -(i gamma/4)H1(gamma R).
struct Green {
    cplx g, dg;
};
Green green2d(cplx gamma, double R);

namespace detail {
// Which method hankel1_01 uses for z: 0 = series, 1 = table (|z| < 10), 2 = table (|z| < 20),
// 3 = asymptotic.  Exposed for tests and benchmarks.
int hankel_region(cplx z);
// Builds the lookup tables now (otherwise built on first use).
void hankel_init();
// The internal sin/cos (Cody-Waite reduction + polynomial kernels), exposed for tests.
void fast_sincos(double x, double& s, double& c);
}  // namespace detail

}  // namespace plumage::bem
