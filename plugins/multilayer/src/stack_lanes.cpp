// reflect_stack_lanes: the Airy recursion of stack_solver.cpp over kLanes stacks at once.
// Every per-lane loop below is straight-line arithmetic with selects, so GCC vectorises it
// (compiled with -O3); see stack_solver.hpp for the physics.
#include <cmath>
#include <vector>

#include "plumage/simd_math.hpp"
#include "stack_solver.hpp"

namespace plumage::multilayer {

namespace {

constexpr int W = kLanes;
static_assert(W == 4, "simd_math works on four doubles");

struct LaneComplex {
  double re[W];
  double im[W];
};

// q = sqrt(ε − sin²α), Im q ≥ 0; a medium exactly at its critical angle is moved off zero to
// (1 + i)·1e-20·√|ε| as in the scalar path.
inline void normal_wavenumber(const Complex* eps, const double* sin2, LaneComplex& q) {
  for (int l = 0; l < W; ++l) {
    const double x = eps[l].real() - sin2[l], y = eps[l].imag();
    // |z|² stays in range: |ε| ≤ 1e40 and a nonzero |z| ≥ ~1e-16 |ε| ≥ 1e-56 (stack_solver.hpp).
    const double r = std::sqrt(x * x + y * y), ax = std::abs(x), ay = std::abs(y);
    const double t = std::sqrt(0.5 * (r + ax));
    const double safe_t = t > 0.0 ? t : 1.0;
    double qr = x >= 0.0 ? t : ay / (2.0 * safe_t);
    double qi = x >= 0.0 ? y / (2.0 * safe_t) : std::copysign(t, y);
    const bool flip = qi < 0.0;
    qr = flip ? -qr : qr;
    qi = flip ? -qi : qi;
    const bool zero = t == 0.0;
    const double nudge = 1e-20 * std::sqrt(std::abs(eps[l].real()));
    q.re[l] = zero ? nudge : qr;
    q.im[l] = zero ? nudge : qi;
  }
}

inline void multiply(const LaneComplex& a, const LaneComplex& b, LaneComplex& out) {
  for (int l = 0; l < W; ++l) {
    const double r = a.re[l] * b.re[l] - a.im[l] * b.im[l];
    const double i = a.re[l] * b.im[l] + a.im[l] * b.re[l];
    out.re[l] = r;
    out.im[l] = i;
  }
}

inline void multiply(const Complex* eps, const LaneComplex& q, LaneComplex& out) {
  for (int l = 0; l < W; ++l) {
    out.re[l] = eps[l].real() * q.re[l] - eps[l].imag() * q.im[l];
    out.im[l] = eps[l].real() * q.im[l] + eps[l].imag() * q.re[l];
  }
}

// One interface of the (1 + X, 1 − X) reduction (stack_solver.cpp): with A = aξ, B = bη,
// D = A + B: ξ ← 2A/D, η ← 2B/D, and at the top interface Γ = (A − B)/D; where a = b (no
// interface) ξ, η pass and Γ = (ξ − η)/2. Selects instead of branches. |D|² stays in range for
// the accepted indices (stack_solver.hpp), so 1/D is one division.
template <bool kTop>
inline void interface_step(const LaneComplex& a, const LaneComplex& b, LaneComplex& xi, LaneComplex& eta,
                           LaneComplex& gamma) {
  for (int l = 0; l < W; ++l) {
    const double Ar = a.re[l] * xi.re[l] - a.im[l] * xi.im[l], Ai = a.re[l] * xi.im[l] + a.im[l] * xi.re[l];
    const double Br = b.re[l] * eta.re[l] - b.im[l] * eta.im[l], Bi = b.re[l] * eta.im[l] + b.im[l] * eta.re[l];
    const bool same = a.re[l] == b.re[l] && a.im[l] == b.im[l];
    double dr = Ar + Br, di = Ai + Bi;
    dr = same ? 1.0 : dr;
    di = same ? 0.0 : di;
    const double inv = 1.0 / (dr * dr + di * di);
    const double ir = dr * inv, ii = -di * inv;  // 1/D
    if constexpr (kTop) {
      const double nr = Ar - Br, ni = Ai - Bi;
      gamma.re[l] = same ? 0.5 * (xi.re[l] - eta.re[l]) : nr * ir - ni * ii;
      gamma.im[l] = same ? 0.5 * (xi.im[l] - eta.im[l]) : nr * ii + ni * ir;
    }
    const double ir2 = 2.0 * ir, ii2 = 2.0 * ii;  // 2/D
    const double xr = Ar * ir2 - Ai * ii2, xim = Ar * ii2 + Ai * ir2;
    const double er = Br * ir2 - Bi * ii2, eim = Br * ii2 + Bi * ir2;
    xi.re[l] = same ? xi.re[l] : xr;
    xi.im[l] = same ? xi.im[l] : xim;
    eta.re[l] = same ? eta.re[l] : er;
    eta.im[l] = same ? eta.im[l] : eim;
  }
}

// ξ ← ξE + (1 − E), η ← ηE + (1 − E).
inline void propagate(const LaneComplex& e, const LaneComplex& f, LaneComplex& xi, LaneComplex& eta) {
  for (int l = 0; l < W; ++l) {
    const double xr = xi.re[l] * e.re[l] - xi.im[l] * e.im[l] + f.re[l];
    const double xim = xi.re[l] * e.im[l] + xi.im[l] * e.re[l] + f.im[l];
    const double er = eta.re[l] * e.re[l] - eta.im[l] * e.im[l] + f.re[l];
    const double eim = eta.re[l] * e.im[l] + eta.im[l] * e.re[l] + f.im[l];
    xi.re[l] = xr;
    xi.im[l] = xim;
    eta.re[l] = er;
    eta.im[l] = eim;
  }
}

// expm1(x) for x ≤ 0: Taylor series to x^12/12! on [−0.25, 0] (relative truncation
// 0.25^12/13! < 1e-17), e^x − 1 below (|e^x − 1| ≥ 0.22 there: no cancellation).
inline simd::v4d expm1_nonpositive(simd::v4d x, simd::v4d ex) {
  simd::v4d p = simd::splat(1.0 / 479001600.0);  // 1/12!
  double inv_fact = 1.0 / 479001600.0;
  for (int k = 11; k >= 1; --k) {
    inv_fact *= static_cast<double>(k + 1);  // 1/k!
    p = p * x + inv_fact;
  }
  const simd::v4d series = p * x;  // Σ_{k=1}^{12} x^k/k!
  return x > -0.25 ? series : ex - 1.0;
}

// Round trip E = e^{2iδ} and 1 − E per lane (see round_trip in stack_solver.cpp); returns true
// when a phase exceeds the polynomial reduction range.
inline bool round_trip(const double* k0_per_nm, const double* d, const LaneComplex& q, LaneComplex& e,
                       LaneComplex& one_minus_e) {
  double psi[W], decay[W];
  bool out_of_range = false;
  for (int l = 0; l < W; ++l) {
    const double k0d = k0_per_nm[l] * d[l];
    psi[l] = k0d * q.re[l];
    decay[l] = -2.0 * k0d * q.im[l];
  }
  for (int l = 0; l < W; ++l) out_of_range |= !(std::abs(psi[l]) <= simd::kMaxReducibleArgument);
  simd::v4d s, c;
  simd::sincos(simd::v4d{psi[0], psi[1], psi[2], psi[3]}, s, c);
  const simd::v4d x{decay[0], decay[1], decay[2], decay[3]};
  const simd::v4d m = simd::exp_nonpositive(x);
  const simd::v4d em1 = expm1_nonpositive(x, m);
  const simd::v4d mm = x > -0.25 ? 1.0 + em1 : m;  // as the scalar path: e^x from expm1 near 0
  const simd::v4d s2 = 2.0 * s * s, sc = 2.0 * s * c;
  for (int l = 0; l < W; ++l) {
    e.re[l] = mm[l] * (1.0 - s2[l]);
    e.im[l] = mm[l] * sc[l];
    one_minus_e.re[l] = -em1[l] + mm[l] * s2[l];
    one_minus_e.im[l] = -mm[l] * sc[l];
  }
  return out_of_range;
}

}  // namespace

void reflect_stack_lanes(int layers, const Complex* eps, const double* thickness_nm,
                         const double* k0_per_nm, const double* sin2_alpha, StackReflection* out) {
  // Inputs the recursion cannot take (issue 9): one branch-free pass (non-short-circuit &, so
  // it vectorises; NaN fails every comparison, so each test is false for NaN), the named error
  // only on failure.
  {
    bool ok = true;
    for (int i = 0; i < (layers + 2) * W; ++i) {
      const double re = eps[i].real(), im = eps[i].imag(), mag2 = re * re + im * im;
      ok &= (im >= 0.0) & (mag2 >= kMinPermittivity2) & (mag2 <= kMaxPermittivity2);
    }
    for (int l = 0; l < W; ++l) ok &= eps[l].imag() == 0.0;
    for (int i = 0; i < layers * W; ++i) ok &= (thickness_nm[i] >= 0.0) & (thickness_nm[i] <= 1.7e308);
    for (int l = 0; l < W; ++l) {
      ok &= (k0_per_nm[l] > 0.0) & (k0_per_nm[l] <= 1.7e308) & (sin2_alpha[l] >= 0.0) & (sin2_alpha[l] <= 1.7e308);
    }
    if (!ok) check_stack_lanes(layers, eps, thickness_nm, k0_per_nm, sin2_alpha);
  }
  LaneComplex gamma_s{}, gamma_p{}, q_below, q, ap, bp, e, f;
  LaneComplex xi_s, eta_s, xi_p, eta_p;  // 1 ± X per polarization; X = 0 below the bottom
  for (int l = 0; l < W; ++l) {
    xi_s.re[l] = eta_s.re[l] = xi_p.re[l] = eta_p.re[l] = 1.0;
    xi_s.im[l] = eta_s.im[l] = xi_p.im[l] = eta_p.im[l] = 0.0;
  }
  bool out_of_range = false;
  normal_wavenumber(eps + (layers + 1) * W, sin2_alpha, q_below);
  const Complex* eps_below = eps + (layers + 1) * W;
  for (int j = layers + 1; j-- > 1;) {
    const Complex* eps_j = eps + j * W;
    normal_wavenumber(eps_j, sin2_alpha, q);
    interface_step<false>(q, q_below, xi_s, eta_s, gamma_s);
    multiply(eps_below, q, ap);
    multiply(eps_j, q_below, bp);
    interface_step<false>(ap, bp, xi_p, eta_p, gamma_p);
    const double* d = thickness_nm + (j - 1) * W;
    out_of_range |= round_trip(k0_per_nm, d, q, e, f);
    propagate(e, f, xi_s, eta_s);
    propagate(e, f, xi_p, eta_p);
    eps_below = eps_j;
    q_below = q;
  }
  // The top interface (ambient over layer 1), with Γ.
  normal_wavenumber(eps, sin2_alpha, q);
  interface_step<true>(q, q_below, xi_s, eta_s, gamma_s);
  multiply(eps_below, q, ap);
  multiply(eps, q_below, bp);
  interface_step<true>(ap, bp, xi_p, eta_p, gamma_p);
  for (int l = 0; l < W; ++l) {
    out[l] = {{gamma_s.re[l], gamma_s.im[l]}, {gamma_p.re[l], gamma_p.im[l]}};
  }
  // Grazing lanes (Γ = −1 exactly) and phases beyond the reduction range: scalar path (which
  // also raises multilayer.phase_precision for unresolved phases).
  if (out_of_range) {
    std::vector<Complex> index(static_cast<std::size_t>(layers) + 2);
    std::vector<double> thick(static_cast<std::size_t>(layers));
    for (int l = 0; l < W; ++l) {
      for (int j = 0; j < layers + 2; ++j) index[j] = std::sqrt(eps[j * W + l]);
      for (int j = 0; j < layers; ++j) thick[j] = thickness_nm[j * W + l];
      out[l] = reflect_stack(index, thick, 2.0 * 3.14159265358979323846 / k0_per_nm[l], sin2_alpha[l]);
    }
  }
  for (int l = 0; l < W; ++l) {
    if (sin2_alpha[l] >= eps[l].real()) out[l] = {{-1.0, 0.0}, {-1.0, 0.0}};
  }
}

}  // namespace plumage::multilayer
