#include "stack_solver.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"

namespace plumage::multilayer {

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string complex_text(Complex z) {
  return number(z.real()) + (std::signbit(z.imag()) ? "-" : "+") + number(std::abs(z.imag())) + "i";
}

// "ambient", "layer j" (1 = top), "substrate" for medium j of a stack of `layers` layers.
std::string medium_name(std::size_t j, std::size_t layers) {
  if (j == 0) return "ambient";
  if (j == layers + 1) return "substrate";
  return "layer " + std::to_string(j);
}

// Why a medium of permittivity ε = n² cannot enter the recursion, or "" when it can.
std::string permittivity_problem(Complex eps) {
  if (!std::isfinite(eps.real()) || !std::isfinite(eps.imag())) return "is not finite";
  if (eps.imag() < 0.0)
    return "is a gain medium (Im n^2 < 0; absorbing media have Im n > 0 under exp(-i omega t)), for which "
           "a passive stack's reflection does not exist";
  const double mag2 = eps.real() * eps.real() + eps.imag() * eps.imag();
  if (!(mag2 >= kMinPermittivity2) || !(mag2 <= kMaxPermittivity2))
    return "has |n| outside [1e-20, 1e20], the range in which the recursion's products stay finite";
  return "";
}

std::string thickness_problem(double d) {
  if (std::isnan(d)) return "is NaN";
  if (d < 0.0) return "is negative";
  if (!std::isfinite(d)) return "is infinite (a semi-infinite medium is the substrate)";
  return "";
}

// Throws an Error naming the first input the recursion cannot take (issue 9). A branch-free
// test first (the recursion's hot path calls this), the messages only on failure.
void check_stack(std::span<const Complex> index, std::span<const double> thickness_nm, double lambda_nm,
                 double sin2_alpha) {
  const std::size_t layers = thickness_nm.size();
  if (index.size() == layers + 2) {
    bool ok = (lambda_nm > 0.0) & (lambda_nm <= 1.7e308) & (sin2_alpha >= 0.0) & (sin2_alpha <= 1.7e308) &
              (index[0].imag() == 0.0);
    for (const Complex n : index) {
      const double re = n.real() * n.real() - n.imag() * n.imag(), im = 2.0 * n.real() * n.imag();
      const double mag2 = re * re + im * im;
      ok &= (im >= 0.0) & (mag2 >= kMinPermittivity2) & (mag2 <= kMaxPermittivity2) & (std::abs(n.real()) <= 1.7e308) &
            (std::abs(n.imag()) <= 1.7e308);
    }
    for (const double d : thickness_nm) ok &= (d >= 0.0) & (d <= 1.7e308);
    if (ok) return;
  }
  if (index.size() != layers + 2)
    throw Error("multilayer: " + std::to_string(index.size()) + " indices for " + std::to_string(layers) +
                " layers (expected ambient, layers, substrate)");
  if (!(lambda_nm > 0.0) || !std::isfinite(lambda_nm))
    throw Error("multilayer: wavelength " + number(lambda_nm) + " nm is not a positive finite number");
  if (!(sin2_alpha >= 0.0) || !std::isfinite(sin2_alpha))
    throw Error("multilayer: sin^2 of the incidence angle " + number(sin2_alpha) + " is not a finite non-negative number");
  for (std::size_t j = 0; j < index.size(); ++j) {
    const std::string problem = permittivity_problem(index[j] * index[j]);
    const bool finite_n = std::isfinite(index[j].real()) && std::isfinite(index[j].imag());
    if (!problem.empty() || !finite_n)
      throw Error("multilayer: " + medium_name(j, layers) + ": index " + complex_text(index[j]) + " " +
                  (finite_n ? problem : std::string("is not finite")));
  }
  if (index[0].imag() != 0.0)
    throw Error("multilayer: ambient: index " + complex_text(index[0]) + " absorbs; reflectance is defined for a lossless ambient");
  for (std::size_t j = 0; j < layers; ++j) {
    const std::string problem = thickness_problem(thickness_nm[j]);
    if (!problem.empty())
      throw Error("multilayer: " + medium_name(j + 1, layers) + ": thickness " + number(thickness_nm[j]) + " nm " + problem);
  }
}

inline Complex mul(Complex a, Complex b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

// 1/z without __divdc3's Inf/NaN recovery (inlined: the recursion's hot path). |z|² stays in
// range: the terms ε q, their sums D and the media's ε lie within ~1e-80 … 1e60 for the
// accepted indices (|n| ∈ [1e-20, 1e20], q ≥ 1e-20 √|ε|; stack_solver.hpp).
inline Complex reciprocal(Complex z) {
  const double inv = 1.0 / (z.real() * z.real() + z.imag() * z.imag());
  return {z.real() * inv, -z.imag() * inv};
}

// q = sqrt(ε − sin²α) on the branch Im q ≥ 0 (and Re q ≥ 0 when Im q = 0).
// A medium exactly at its critical angle (z = 0) would make the recursion 0/0 although the
// result has a finite limit, continuous in q (the recursion below is well conditioned there);
// q is then moved off zero to (1 + i)·1e-20·√|ε|, far below any nonzero |q| ≥ 1e-8 √|ε| that
// double inputs can produce. (Grazing incidence in the ambient itself is handled exactly.)
inline Complex normal_wavenumber(Complex eps, double sin2) {
  const Complex z{eps.real() - sin2, eps.imag()};
  if (z.imag() == 0.0) {
    if (z.real() == 0.0) {
      const double nudge = 1e-20 * std::sqrt(std::abs(eps.real()));
      return {nudge, nudge};
    }
    return z.real() > 0.0 ? Complex{std::sqrt(z.real()), 0.0} : Complex{0.0, std::sqrt(-z.real())};
  }
  // Principal square root by two real square roots (csqrt's special-value handling is not
  // needed: z is finite and nonzero here). The branch with Im q ≥ 0 is the principal one,
  // since Im z > 0 for passive media.
  const double r = std::sqrt(z.real() * z.real() + z.imag() * z.imag());
  const double t = std::sqrt(0.5 * (r + std::abs(z.real())));
  if (t == 0.0) {  // |z|² underflowed (Im ε ~ 1e-300 at the critical angle): as z = 0
    const double nudge = 1e-20 * std::sqrt(std::abs(eps.real()));
    return {nudge, nudge};
  }
  Complex q = z.real() >= 0.0 ? Complex{t, z.imag() / (2.0 * t)}
                              : Complex{std::abs(z.imag()) / (2.0 * t), std::copysign(t, z.imag())};
  if (q.imag() < 0.0) q = -q;
  return q;
}

inline bool is_grazing(Complex ambient, double sin2) {
  return sin2 >= ambient.real() * ambient.real();
}

// A layer's round trip E = e^{2iδ} (|E| ≤ 1 since Im q ≥ 0; underflows to 0 for thick
// absorbers), 1 − E without cancellation (E → 1 for thin layers and for q → 0, where the
// recursion needs 1 − E to full relative precision), and the one-way factor e^{iδ} (for t).
// With δ = k0 d q = ψ + iκ: E = e^{−2κ}(cos 2ψ + i sin 2ψ), cos 2ψ = 1 − 2 sin²ψ,
// 1 − E = −expm1(−2κ) + 2 e^{−2κ} sin²ψ − i e^{−2κ} sin 2ψ.
struct RoundTrip {
  Complex e, one_minus_e, half;
};
inline RoundTrip round_trip(Complex q, double k0d) {
  const double psi = k0d * q.real(), decay = -2.0 * k0d * q.imag();
  const double s = std::sin(psi), c = std::cos(psi);
  double m = 1.0, em1 = 0.0;  // e^{decay}, e^{decay} − 1
  if (decay != 0.0) {
    if (decay > -0.25) {  // the lanes' expm1 switches at the same point
      em1 = std::expm1(decay);
      m = 1.0 + em1;
    } else {
      m = decay < -745.0 ? 0.0 : std::exp(decay);
      em1 = m - 1.0;
    }
  }
  const double s2 = 2.0 * s * s, sc = 2.0 * s * c;
  const double half_m = decay < -1490.0 ? 0.0 : std::exp(0.5 * decay);
  return {{m * (1.0 - s2), m * sc}, {-em1 + m * s2, -m * sc}, {half_m * c, half_m * s}};
}

// One-way phase k0 d Re q above which a layer's interference is not resolved: the phase is
// computed to a few ulps, ~7e-4 rad at 1e12 rad (a lossless layer ~10 km thick at 550 nm). The
// result is still returned (R, T stay passive and conserve energy; only the interference phase
// of that layer is arbitrary) with the warning multilayer.phase_precision, unless the layer is
// opaque (round-trip attenuation e^{−40} or less), where the phase does not matter.
constexpr double kMaxResolvedPhase = 1e12;

inline void check_phase(Complex q, double k0, double d_nm, std::size_t layer) {
  const double psi = std::abs(k0 * d_nm * q.real());
  if (!(psi > kMaxResolvedPhase) || 2.0 * k0 * d_nm * q.imag() > 40.0) return;
  char b[320];
  std::snprintf(b, sizeof b,
                "layer %zu: one-way phase k0 d Re(q) = %.3g rad exceeds %.0e rad, so its interference is resolved "
                "only to ~%.1g rad (thickness %.6g nm at lambda = %.6g nm); result returned, that layer's phase is arbitrary",
                layer, psi, kMaxResolvedPhase, 4.0 * psi * 2.2e-16, d_nm, 2.0 * std::numbers::pi / k0);
  warn("multilayer.phase_precision", b);
}

// The reduction from the bottom carries, per polarization, ξ = 1 + X and η = 1 − X with
// X = Γ_below e^{2iδ} (not X itself). At an interface with terms a (above) and b (below) —
// s: a = q_j, b = q_{j+1}; p: a = ε_{j+1} q_j, b = ε_j q_{j+1} —
//   Γ = (a − b + (a + b)X)/(a + b + (a − b)X) = (aξ − bη)/D,  D = aξ + bη,
//   1 + Γ = 2aξ/D,  1 − Γ = 2bη/D,
// every sum of like-signed products, so nothing cancels when a layer's q is small next to its
// neighbours' (near its critical angle, or an index near zero): the plain Airy step subtracted
// two O(1) numbers there to get an O(q) one and lost ε_mach/|q| (|R| = 0.03 instead of 1 under
// TIR through 200 near-critical layers, R + T = 2.98 for an n = 1e-50 film on keratin; issue 9). Through a
// layer: 1 ± ΓE = (1 ± Γ)E + (1 − E). ξ + η = 2 throughout, so D ≠ 0 for passive media.
struct Reduction {
  Complex xi{1.0, 0.0}, eta{1.0, 0.0};  // X = 0 below the bottom interface
};

// One interface; returns Γ (when `gamma`) and 1/D (transmission uses 2a/D).
inline Complex interface_step(Complex a, Complex b, Reduction& state, Complex* gamma = nullptr) {
  if (a == b) {  // the same medium on both sides: no interface, Γ = X passes through
    if (gamma) *gamma = 0.5 * (state.xi - state.eta);
    return reciprocal(a + a);
  }
  const Complex ax = mul(a, state.xi), bx = mul(b, state.eta);
  const Complex inv = reciprocal(ax + bx);
  if (gamma) *gamma = mul(ax - bx, inv);
  state.xi = 2.0 * mul(ax, inv);
  state.eta = 2.0 * mul(bx, inv);
  return inv;
}

inline void propagate(const RoundTrip& t, Reduction& state) {
  state.xi = mul(state.xi, t.e) + t.one_minus_e;
  state.eta = mul(state.eta, t.e) + t.one_minus_e;
}

}  // namespace

StackReflection reflect_stack(std::span<const Complex> index, std::span<const double> thickness_nm,
                              double lambda_nm, double sin2_alpha) {
  check_stack(index, thickness_nm, lambda_nm, sin2_alpha);
  const std::size_t layers = thickness_nm.size();
  const double k0 = 2.0 * std::numbers::pi / lambda_nm;

  // Grazing incidence (q_0 = 0): every passive stack reflects with Γ = −1 in both polarizations.
  if (is_grazing(index[0], sin2_alpha)) return {Complex{-1.0, 0.0}, Complex{-1.0, 0.0}};
  // Start at the bottom interface (layer L over the substrate L+1).
  Complex eps_below = index[layers + 1] * index[layers + 1];
  Complex q_below = normal_wavenumber(eps_below, sin2_alpha);
  Reduction s_state, p_state;
  Complex gamma_s, gamma_p;
  for (std::size_t j = layers + 1; j-- > 0;) {
    const Complex eps = index[j] * index[j];
    const Complex q = normal_wavenumber(eps, sin2_alpha);
    interface_step(q, q_below, s_state, j == 0 ? &gamma_s : nullptr);
    interface_step(mul(eps_below, q), mul(eps, q_below), p_state, j == 0 ? &gamma_p : nullptr);
    if (j > 0) {
      check_phase(q, k0, thickness_nm[j - 1], j);
      const RoundTrip t = round_trip(q, k0 * thickness_nm[j - 1]);
      propagate(t, s_state);
      propagate(t, p_state);
    }
    eps_below = eps;
    q_below = q;
  }
  return {gamma_s, gamma_p};
}

StackResponse solve_stack(std::span<const Complex> index, std::span<const double> thickness_nm,
                          double lambda_nm, double sin2_alpha) {
  check_stack(index, thickness_nm, lambda_nm, sin2_alpha);
  const std::size_t layers = thickness_nm.size();
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
  //   t_{j,j+1} e^{iδ_{j+1}} / (1 + r_{j,j+1} Γ_{j+1} e^{2iδ_{j+1}}) = 2a e^{iδ_{j+1}} / D
  // whose magnitude stays bounded, so a 200-layer absorbing stack underflows to 0, never NaN.
  Reduction s_state, p_state;
  Complex gs, gp, ts{1, 0}, tp{1, 0}, half_phase{1, 0};
  for (std::size_t j = layers + 1; j-- > 0;) {
    const std::size_t b = j + 1;
    const Complex as = q[j], bs = q[b];
    const Complex ap = mul(eps[b], q[j]), bp = mul(eps[j], q[b]);
    const Complex inv_ds = interface_step(as, bs, s_state, &gs);
    const Complex inv_dp = interface_step(ap, bp, p_state, &gp);
    // t = 2a/D for both fields (t_E = 1 + r_E for s, t_H = 1 + r_H for p).
    ts = mul(ts, as == bs ? half_phase : mul(2.0 * mul(as, half_phase), inv_ds));
    tp = mul(tp, ap == bp ? half_phase : mul(2.0 * mul(ap, half_phase), inv_dp));
    if (j > 0) {
      check_phase(q[j], k0, thickness_nm[j - 1], j);
      const RoundTrip t = round_trip(q[j], k0 * thickness_nm[j - 1]);
      propagate(t, s_state);
      propagate(t, p_state);
      half_phase = t.half;
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
  const double flux_p0 = (q[0] * reciprocal(eps[0])).real();
  out.T_s = flux_s0 > 0 ? q[sub].real() / flux_s0 * std::norm(ts) : 0.0;
  out.T_p = flux_p0 > 0 ? (q[sub] * reciprocal(eps[sub])).real() / flux_p0 * std::norm(tp) : 0.0;
  return out;
}

void check_stack_lanes(int layers, const Complex* eps, const double* thickness_nm, const double* k0_per_nm,
                       const double* sin2_alpha) {
  const std::size_t media = static_cast<std::size_t>(layers) + 2;
  for (int l = 0; l < kLanes; ++l) {
    const std::string lane = "multilayer (lane " + std::to_string(l) + "): ";
    if (!(k0_per_nm[l] > 0.0) || !std::isfinite(k0_per_nm[l]))
      throw Error(lane + "wavenumber " + number(k0_per_nm[l]) + " rad/nm is not a positive finite number");
    if (!(sin2_alpha[l] >= 0.0) || !std::isfinite(sin2_alpha[l]))
      throw Error(lane + "sin^2 of the incidence angle " + number(sin2_alpha[l]) + " is not a finite non-negative number");
    for (std::size_t j = 0; j < media; ++j) {
      const Complex e = eps[j * kLanes + l];
      const std::string problem = permittivity_problem(e);
      if (!problem.empty())
        throw Error(lane + medium_name(j, media - 2) + ": permittivity " + complex_text(e) + " " + problem);
    }
    if (eps[l].imag() != 0.0)
      throw Error(lane + "ambient: permittivity " + complex_text(eps[l]) + " absorbs; reflectance is defined for a lossless ambient");
    for (std::size_t j = 0; j + 2 < media; ++j) {
      const std::string problem = thickness_problem(thickness_nm[j * kLanes + l]);
      if (!problem.empty())
        throw Error(lane + medium_name(j + 1, media - 2) + ": thickness " + number(thickness_nm[j * kLanes + l]) + " nm " + problem);
    }
  }
}

}  // namespace plumage::multilayer
