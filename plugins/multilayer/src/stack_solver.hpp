// Reflection and transmission of a planar multilayer (paper §4.2), both polarizations at once.
//
// Media 0 (ambient) … L+1 (substrate); layers 1..L with thicknesses d_j. With
// q_j = n_j cos θ_j = sqrt(n_j² − sin²α) (principal branch, Im q_j ≥ 0, so fields decay into
// absorbing layers and evanescent ones under total internal reflection) the interface
// coefficients are
//   s (E-field):  r = (q_{j−1} − q_j)/(q_{j−1} + q_j)
//   p (H-field):  r = (ε_j q_{j−1} − ε_{j−1} q_j)/(ε_j q_{j−1} + ε_{j−1} q_j),  ε = n²,
// and the stack is reduced from the bottom with the Airy (Parratt) recursion
//   Γ ← (r + Γ e^{2iδ}) / (1 + r Γ e^{2iδ}),  δ_j = k0 q_j d_j.
// Every quantity in the recursion is bounded for passive media (|e^{2iδ}| ≤ 1, |Γ| ≤ 1 before
// the top interface), so unlike a product of 2×2 transfer matrices it cannot overflow: it is the
// scattering-matrix formulation specialised to a layered medium. It is evaluated on the pair
// (1 + Γe^{2iδ}, 1 − Γe^{2iδ}) with the Fresnel division fused in (one reciprocal per interface
// and polarization), which stays accurate where some q_j is small (issue 9, stack_solver.cpp).
#pragma once

#include <complex>
#include <span>

namespace plumage::multilayer {

using Complex = std::complex<double>;

struct StackReflection {
  Complex r_s;  // E-field reflection, s polarization, referenced to the top interface
  Complex r_p;  // H-field reflection, p polarization
};

struct StackResponse {
  Complex r_s, r_p;  // as above
  Complex t_s, t_p;  // E-field (s) and H-field (p) amplitude transmission into the substrate
  double R_s = 0, R_p = 0;  // reflected power fractions
  double T_s = 0, T_p = 0;  // transmitted power fractions (0 under total internal reflection)
};

// Inputs (issue 9). The recursion takes passive media only, Im ε ≥ 0 with ε = n² (a gain medium,
// Im n < 0 under e^{−iωt}, has no passive reflection, and the branch Im q ≥ 0 silently gave
// R = 18), |n| ∈ [1e-20, 1e20] (within it every product and |D|² of the recursion stays in
// range; before issue 9 |n| ≈ 1e100 or a 1e-160 substrate gave NaN, and physical indices lie
// within [1e-3, 1e3]), a lossless ambient, finite non-negative thicknesses (zero is allowed: no
// layer), a positive finite wavelength and a finite sin²α ≥ 0. Anything else throws
// plumage::Error naming the medium ("layer 2: thickness -5 nm is negative"); nothing is
// returned that the inputs cannot support.
// Bounds on |ε|² = |n|⁴, with 1e-9 slack so that |n| = 1e±20 itself (whose square may round
// beyond 1e±40) is accepted.
inline constexpr double kMinPermittivity2 = 1e-80 * (1.0 - 1e-9);
inline constexpr double kMaxPermittivity2 = 1e80 * (1.0 + 1e-9);

// Small normal wavenumbers (a layer near its critical angle, an index near zero) keep full
// precision: the reduction carries 1 ± Γe^{2iδ} instead of Γ (stack_solver.cpp); measured in
// tests/test_stack_extremes.cpp.

// index: n_0 … n_{L+1} (size L+2); thickness_nm: d_1 … d_L (size L). sin2_alpha is sin²α with
// α the angle of incidence in the ambient medium (its index enters via n_0² sin²θ_0, so for a
// non-air ambient pass n_0² sin²θ_0).
StackReflection reflect_stack(std::span<const Complex> index, std::span<const double> thickness_nm,
                              double lambda_nm, double sin2_alpha);

// Same, plus amplitude and power transmission (for energy checks and the CLI).
StackResponse solve_stack(std::span<const Complex> index, std::span<const double> thickness_nm,
                          double lambda_nm, double sin2_alpha);

// Number of stacks reflect_stack_lanes evaluates together (one AVX2 register of doubles).
inline constexpr int kLanes = 4;

// The same recursion as reflect_stack for kLanes stacks of equal layer count at once, laid out
// lane-minor: permittivity ε = n² of medium j in lane l at eps[j * kLanes + l] (j = 0..L+1),
// thickness of layer j+1 at thickness_nm[j * kLanes + l] (j = 0..L−1), and per-lane vacuum
// wavenumber k0 (rad/nm) and sin²α. Written branch-free over lanes so the compiler vectorises
// it; agrees with reflect_stack to rounding (tests check 1e-13).
void reflect_stack_lanes(int layers, const Complex* eps, const double* thickness_nm,
                         const double* k0_per_nm, const double* sin2_alpha, StackReflection* out);

// The input checks of reflect_stack_lanes (above, in ε): throws plumage::Error naming the lane
// and medium of the first input the recursion cannot take; returns when all are valid.
void check_stack_lanes(int layers, const Complex* eps, const double* thickness_nm, const double* k0_per_nm,
                       const double* sin2_alpha);

}  // namespace plumage::multilayer
