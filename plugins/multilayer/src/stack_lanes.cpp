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

// Lanes as GCC vectors, so that the recursion's arithmetic is vector code whatever the
// auto-vectoriser decides (issue 26: the interface step's loop with selects and a division had
// stayed scalar).
using simd::v4d;
using v4i = simd::v4i;
struct LaneComplex {
  v4d re;
  v4d im;
};

inline v4d real_parts(const Complex* z) { return v4d{z[0].real(), z[1].real(), z[2].real(), z[3].real()}; }
inline v4d imag_parts(const Complex* z) { return v4d{z[0].imag(), z[1].imag(), z[2].imag(), z[3].imag()}; }

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

// q of the media already met in this stack: a medium whose ε equals, in every lane, one met
// before gets its q copied (same inputs, same bits). Bird stacks repeat few media (air ambient
// and air gap, keratin cortices, alternating keratin/melanin), so most q are copies (issue 26).
class WavenumberCache {
 public:
  void get(const Complex* eps, const double* sin2, LaneComplex& q) {
    for (int k = 0; k < size_; ++k) {
      bool same = true;
      for (int l = 0; l < W; ++l) same &= (eps[l] == eps_[k][l]);
      if (same) {
        q = q_[k];
        return;
      }
    }
    normal_wavenumber(eps, sin2, q);
    const int slot = size_ < kSlots ? size_++ : kSlots - 1;  // full: the last slot is replaced
    for (int l = 0; l < W; ++l) eps_[slot][l] = eps[l];
    q_[slot] = q;
  }

 private:
  static constexpr int kSlots = 4;
  int size_ = 0;
  Complex eps_[kSlots][W];
  LaneComplex q_[kSlots];
};

inline void multiply(const Complex* eps, const LaneComplex& q, LaneComplex& out) {
  const v4d er = real_parts(eps), ei = imag_parts(eps);
  out.re = er * q.re - ei * q.im;
  out.im = er * q.im + ei * q.re;
}

// One interface of the (1 + X, 1 − X) reduction (stack_solver.cpp): with A = aξ, B = bη,
// D = A + B: ξ ← 2A/D, η ← 2B/D, and at the top interface Γ = (A − B)/D; where a = b (no
// interface) ξ, η pass and Γ = (ξ − η)/2. Selects instead of branches. |D|² stays in range for
// the accepted indices (stack_solver.hpp), so 1/D is one division.
template <bool kTop>
inline void interface_step(const LaneComplex& a, const LaneComplex& b, LaneComplex& xi, LaneComplex& eta,
                           LaneComplex& gamma) {
  const v4d Ar = a.re * xi.re - a.im * xi.im, Ai = a.re * xi.im + a.im * xi.re;
  const v4d Br = b.re * eta.re - b.im * eta.im, Bi = b.re * eta.im + b.im * eta.re;
  const v4i same = (a.re == b.re) & (a.im == b.im);
  const v4d dr = same ? simd::splat(1.0) : Ar + Br;
  const v4d di = same ? simd::splat(0.0) : Ai + Bi;
  const v4d inv = 1.0 / (dr * dr + di * di);
  const v4d ir = dr * inv, ii = -di * inv;  // 1/D
  if constexpr (kTop) {
    const v4d nr = Ar - Br, ni = Ai - Bi;
    gamma.re = same ? 0.5 * (xi.re - eta.re) : nr * ir - ni * ii;
    gamma.im = same ? 0.5 * (xi.im - eta.im) : nr * ii + ni * ir;
  }
  const v4d ir2 = 2.0 * ir, ii2 = 2.0 * ii;  // 2/D
  const v4d xr = Ar * ir2 - Ai * ii2, xim = Ar * ii2 + Ai * ir2;
  const v4d er = Br * ir2 - Bi * ii2, eim = Br * ii2 + Bi * ir2;
  xi.re = same ? xi.re : xr;
  xi.im = same ? xi.im : xim;
  eta.re = same ? eta.re : er;
  eta.im = same ? eta.im : eim;
}

// ξ ← ξE + (1 − E), η ← ηE + (1 − E).
inline void propagate(const LaneComplex& e, const LaneComplex& f, LaneComplex& xi, LaneComplex& eta) {
  const v4d xr = xi.re * e.re - xi.im * e.im + f.re, xim = xi.re * e.im + xi.im * e.re + f.im;
  const v4d er = eta.re * e.re - eta.im * e.im + f.re, eim = eta.re * e.im + eta.im * e.re + f.im;
  xi = {xr, xim};
  eta = {er, eim};
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
  const v4d k0d = v4d{k0_per_nm[0], k0_per_nm[1], k0_per_nm[2], k0_per_nm[3]} * v4d{d[0], d[1], d[2], d[3]};
  const v4d psi = k0d * q.re, x = -2.0 * k0d * q.im;
  bool out_of_range = false;
  for (int l = 0; l < W; ++l) out_of_range |= !(std::abs(psi[l]) <= simd::kMaxReducibleArgument);
  simd::v4d s, c;
  simd::sincos(psi, s, c);
  const simd::v4d m = simd::exp_nonpositive(x);
  const simd::v4d em1 = expm1_nonpositive(x, m);
  const simd::v4d mm = x > -0.25 ? 1.0 + em1 : m;  // as the scalar path: e^x from expm1 near 0
  const simd::v4d s2 = 2.0 * s * s, sc = 2.0 * s * c;
  e = {mm * (1.0 - s2), mm * sc};
  one_minus_e = {-em1 + mm * s2, -mm * sc};
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
  xi_s = eta_s = xi_p = eta_p = {simd::splat(1.0), simd::splat(0.0)};
  bool out_of_range = false;
  WavenumberCache wavenumbers;
  wavenumbers.get(eps + (layers + 1) * W, sin2_alpha, q_below);
  const Complex* eps_below = eps + (layers + 1) * W;
  for (int j = layers + 1; j-- > 1;) {
    const Complex* eps_j = eps + j * W;
    wavenumbers.get(eps_j, sin2_alpha, q);
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
  wavenumbers.get(eps, sin2_alpha, q);
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
