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
// scattering-matrix formulation specialised to a layered medium. Fusing the Fresnel division
// into the recursion leaves one complex division per interface and polarization.
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

}  // namespace plumage::multilayer
