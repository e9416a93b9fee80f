#include "stack_solver.hpp"

#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

namespace plumage::multilayer {

namespace {

// Complex division without the Inf/NaN recovery of __divdc3 (operands here are O(1) and
// finite), which the compiler inlines: the recursion's hot path.
inline Complex divide(Complex a, Complex b) {
  const double inv = 1.0 / (b.real() * b.real() + b.imag() * b.imag());
  return {(a.real() * b.real() + a.imag() * b.imag()) * inv,
          (a.imag() * b.real() - a.real() * b.imag()) * inv};
}

inline Complex mul(Complex a, Complex b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

// q = sqrt(ε − sin²α) on the branch Im q ≥ 0 (and Re q ≥ 0 when Im q = 0).
// A layer exactly at its critical angle (z = 0) would make the recursion 0/0 although the
// result has a finite limit; q is then moved off zero by 1e-8, an O(1e-8) error at a
// measure-zero angle. (Grazing incidence in the ambient itself is handled exactly by callers.)
inline Complex normal_wavenumber(Complex eps, double sin2) {
  const Complex z{eps.real() - sin2, eps.imag()};
  if (z.imag() == 0.0) {
    if (z.real() == 0.0) return {1e-8, 1e-8};
    return z.real() > 0.0 ? Complex{std::sqrt(z.real()), 0.0} : Complex{0.0, std::sqrt(-z.real())};
  }
  // Principal square root by two real square roots (csqrt's special-value handling is not
  // needed: z is finite and nonzero here). The branch with Im q ≥ 0 is the principal one,
  // since Im z > 0 for passive media.
  const double r = std::sqrt(z.real() * z.real() + z.imag() * z.imag());
  const double t = std::sqrt(0.5 * (r + std::abs(z.real())));
  Complex q = z.real() >= 0.0 ? Complex{t, z.imag() / (2.0 * t)}
                              : Complex{std::abs(z.imag()) / (2.0 * t), std::copysign(t, z.imag())};
  if (q.imag() < 0.0) q = -q;
  return q;
}

inline bool is_grazing(Complex ambient, double sin2) {
  return sin2 >= ambient.real() * ambient.real();
}

// e^{2 i k0 q d}: |.| ≤ 1 because Im q ≥ 0; underflows to 0 for thick absorbers.
inline Complex round_trip_phase(Complex q, double k0d) {
  const double phase = 2.0 * k0d * q.real();
  if (q.imag() == 0.0) return {std::cos(phase), std::sin(phase)};  // lossless, propagating
  const double decay = -2.0 * k0d * q.imag();
  const double magnitude = decay < -745.0 ? 0.0 : std::exp(decay);
  return {magnitude * std::cos(phase), magnitude * std::sin(phase)};
}

// Fused interface + recursion step: with r = (a − b)/(a + b) and X = Γ_below e^{2iδ},
// (r + X)/(1 + rX) = (a − b + (a + b)X)/(a + b + (a − b)X).
// When both sides are the same medium (a = b; at grazing incidence possibly a = b = 0) there is
// no interface and Γ passes through unchanged, which the formula would turn into 0/0.
inline Complex airy_step(Complex a, Complex b, Complex x) {
  if (a == b) return x;
  const Complex sum = a + b, diff = a - b;
  return divide(diff + mul(sum, x), sum + mul(diff, x));
}

}  // namespace

StackReflection reflect_stack(std::span<const Complex> index, std::span<const double> thickness_nm,
                              double lambda_nm, double sin2_alpha) {
  const std::size_t layers = thickness_nm.size();
  assert(index.size() == layers + 2);
  const double k0 = 2.0 * std::numbers::pi / lambda_nm;

  // Grazing incidence (q_0 = 0): every passive stack reflects with Γ = −1 in both polarizations.
  if (is_grazing(index[0], sin2_alpha)) return {Complex{-1.0, 0.0}, Complex{-1.0, 0.0}};
  // Start at the bottom interface (layer L over the substrate L+1).
  Complex eps_below = index[layers + 1] * index[layers + 1];
  Complex q_below = normal_wavenumber(eps_below, sin2_alpha);
  Complex gamma_s{0.0, 0.0}, gamma_p{0.0, 0.0}, phase{0.0, 0.0};
  for (std::size_t j = layers + 1; j-- > 0;) {
    const Complex eps = index[j] * index[j];
    const Complex q = normal_wavenumber(eps, sin2_alpha);
    gamma_s = airy_step(q, q_below, mul(gamma_s, phase));
    gamma_p = airy_step(mul(eps_below, q), mul(eps, q_below), mul(gamma_p, phase));
    if (j > 0) phase = round_trip_phase(q, k0 * thickness_nm[j - 1]);
    eps_below = eps;
    q_below = q;
  }
  return {gamma_s, gamma_p};
}

StackResponse solve_stack(std::span<const Complex> index, std::span<const double> thickness_nm,
                          double lambda_nm, double sin2_alpha) {
  const std::size_t layers = thickness_nm.size();
  assert(index.size() == layers + 2);
  const double k0 = 2.0 * std::numbers::pi / lambda_nm;

  if (is_grazing(index[0], sin2_alpha)) {
    StackResponse grazing;
    grazing.r_s = grazing.r_p = Complex{-1.0, 0.0};
    grazing.R_s = grazing.R_p = 1.0;
    return grazing;
  }
  std::vector<Complex> eps(layers + 2), q(layers + 2);
  for (std::size_t j = 0; j < layers + 2; ++j) {
    eps[j] = index[j] * index[j];
    q[j] = normal_wavenumber(eps[j], sin2_alpha);
  }
  // Reflection as in reflect_stack; transmission multiplies, interface by interface,
  //   t_{j,j+1} e^{iδ_{j+1}} / (1 + r_{j,j+1} Γ_{j+1} e^{2iδ_{j+1}})
  // whose magnitude stays bounded, so a 200-layer absorbing stack underflows to 0, never NaN.
  Complex gs{0, 0}, gp{0, 0}, ts{1, 0}, tp{1, 0};
  Complex phase{0, 0}, half_phase{1, 0};
  for (std::size_t j = layers + 1; j-- > 0;) {
    const std::size_t b = j + 1;
    const Complex as = q[j], bs = q[b];
    const Complex ap = eps[b] * q[j], bp = eps[j] * q[b];
    const Complex xs = gs * phase, xp = gp * phase;
    // t = 2a/(a+b) for both fields (t_E = 1 + r_E for s, t_H = 1 + r_H for p).
    ts *= as == bs ? half_phase : divide(2.0 * as * half_phase, as + bs + (as - bs) * xs);
    tp *= ap == bp ? half_phase : divide(2.0 * ap * half_phase, ap + bp + (ap - bp) * xp);
    gs = airy_step(as, bs, xs);
    gp = airy_step(ap, bp, xp);
    if (j > 0) {
      const double k0d = k0 * thickness_nm[j - 1];
      phase = round_trip_phase(q[j], k0d);
      const double decay = -k0d * q[j].imag();
      half_phase = (decay < -745.0 ? 0.0 : std::exp(decay)) *
                   Complex{std::cos(k0d * q[j].real()), std::sin(k0d * q[j].real())};
    }
  }
  StackResponse out;
  out.r_s = gs;
  out.r_p = gp;
  out.t_s = ts;
  out.t_p = tp;
  out.R_s = std::norm(gs);
  out.R_p = std::norm(gp);
  const std::size_t sub = layers + 1;
  // Power flux along the normal: s ∝ Re(q)|E|², p ∝ Re(q/ε)|H|².
  const double flux_s0 = q[0].real();
  const double flux_p0 = (q[0] / eps[0]).real();
  out.T_s = flux_s0 > 0 ? q[sub].real() / flux_s0 * std::norm(ts) : 0.0;
  out.T_p = flux_p0 > 0 ? (q[sub] / eps[sub]).real() / flux_p0 * std::norm(tp) : 0.0;
  return out;
}

}  // namespace plumage::multilayer
