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

// q = sqrt(ε − sin²α), Im q ≥ 0; a layer exactly at its critical angle is moved off zero
// by 1e-8 as in the scalar path.
inline void normal_wavenumber(const Complex* eps, const double* sin2, LaneComplex& q) {
  for (int l = 0; l < W; ++l) {
    const double x = eps[l].real() - sin2[l], y = eps[l].imag();
    const double r = std::sqrt(x * x + y * y);
    const double t = std::sqrt(0.5 * (r + std::abs(x)));
    const double safe_t = t > 0.0 ? t : 1.0;
    double qr = x >= 0.0 ? t : std::abs(y) / (2.0 * safe_t);
    double qi = x >= 0.0 ? y / (2.0 * safe_t) : std::copysign(t, y);
    const bool flip = qi < 0.0;
    qr = flip ? -qr : qr;
    qi = flip ? -qi : qi;
    const bool zero = t == 0.0;
    q.re[l] = zero ? 1e-8 : qr;
    q.im[l] = zero ? 1e-8 : qi;
  }
}

// Γ ← (a − b + (a + b)X) / (a + b + (a − b)X), or X where a = b (no interface).
inline void airy_step(const LaneComplex& a, const LaneComplex& b, const LaneComplex& x,
                      LaneComplex& gamma) {
  for (int l = 0; l < W; ++l) {
    const double sr = a.re[l] + b.re[l], si = a.im[l] + b.im[l];
    const double dr = a.re[l] - b.re[l], di = a.im[l] - b.im[l];
    const double nr = dr + (sr * x.re[l] - si * x.im[l]);
    const double ni = di + (sr * x.im[l] + si * x.re[l]);
    double mr = sr + (dr * x.re[l] - di * x.im[l]);
    double mi = si + (dr * x.im[l] + di * x.re[l]);
    const bool same = dr == 0.0 && di == 0.0;
    mr = same ? 1.0 : mr;
    mi = same ? 0.0 : mi;
    const double inv = 1.0 / (mr * mr + mi * mi);
    const double gr = (nr * mr + ni * mi) * inv, gi = (ni * mr - nr * mi) * inv;
    gamma.re[l] = same ? x.re[l] : gr;
    gamma.im[l] = same ? x.im[l] : gi;
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

// e^{2 i k0 q d} per lane; returns true when a phase exceeds the polynomial reduction range.
inline bool round_trip_phase(const double* k0_per_nm, const double* d, const LaneComplex& q,
                             LaneComplex& phase) {
  double arg[W], decay[W];
  bool out_of_range = false;
  for (int l = 0; l < W; ++l) {
    const double k0d = 2.0 * k0_per_nm[l] * d[l];
    arg[l] = k0d * q.re[l];
    decay[l] = -k0d * q.im[l];
  }
  for (int l = 0; l < W; ++l) out_of_range |= !(std::abs(arg[l]) <= simd::kMaxReducibleArgument);
  simd::v4d s, c;
  simd::sincos(simd::v4d{arg[0], arg[1], arg[2], arg[3]}, s, c);
  const simd::v4d m = simd::exp_nonpositive(simd::v4d{decay[0], decay[1], decay[2], decay[3]});
  for (int l = 0; l < W; ++l) {
    phase.re[l] = m[l] * c[l];
    phase.im[l] = m[l] * s[l];
  }
  return out_of_range;
}

}  // namespace

void reflect_stack_lanes(int layers, const Complex* eps, const double* thickness_nm,
                         const double* k0_per_nm, const double* sin2_alpha, StackReflection* out) {
  LaneComplex gamma_s{}, gamma_p{}, phase{}, q_below, q, xs, xp, ap, bp;
  bool out_of_range = false;
  normal_wavenumber(eps + (layers + 1) * W, sin2_alpha, q_below);
  const Complex* eps_below = eps + (layers + 1) * W;
  for (int j = layers + 1; j-- > 0;) {
    const Complex* eps_j = eps + j * W;
    normal_wavenumber(eps_j, sin2_alpha, q);
    multiply(gamma_s, phase, xs);
    multiply(gamma_p, phase, xp);
    airy_step(q, q_below, xs, gamma_s);
    multiply(eps_below, q, ap);
    multiply(eps_j, q_below, bp);
    airy_step(ap, bp, xp, gamma_p);
    if (j > 0) {
      const double* d = thickness_nm + (j - 1) * W;
      out_of_range |= round_trip_phase(k0_per_nm, d, q, phase);
    }
    eps_below = eps_j;
    q_below = q;
  }
  for (int l = 0; l < W; ++l) {
    out[l] = {{gamma_s.re[l], gamma_s.im[l]}, {gamma_p.re[l], gamma_p.im[l]}};
  }
  // Grazing lanes (Γ = −1 exactly) and phases beyond the reduction range: scalar path.
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
