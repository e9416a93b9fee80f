// Half-vector sampling of the feather lobe: closed-form marginals inverted by safeguarded Newton
// (spec geometry-and-brdf §4.10; derivation in plumage/lobe_sampling.hpp).
#include "plumage/lobe_sampling.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/error.hpp"

namespace plumage {

namespace {

constexpr double kSqrtPi = 1.7724538509055160273;

// Inverse error function on (−1, 1): Giles' single-precision approximation refined by two
// Newton steps on erf (double precision except deep in the tails, |x| > 5, where the rounding
// of v itself dominates).
double erfinv(double v) {
  v = std::clamp(v, -1.0 + 1e-16, 1.0 - 1e-16);
  double w = -std::log((1.0 - v) * (1.0 + v)), p;
  if (w < 5.0) {
    w -= 2.5;
    p = 2.81022636e-08;
    p = 3.43273939e-07 + p * w;
    p = -3.5233877e-06 + p * w;
    p = -4.39150654e-06 + p * w;
    p = 0.00021858087 + p * w;
    p = -0.00125372503 + p * w;
    p = -0.00417768164 + p * w;
    p = 0.246640727 + p * w;
    p = 1.50140941 + p * w;
  } else {
    w = std::sqrt(w) - 3.0;
    p = -0.000200214257;
    p = 0.000100950558 + p * w;
    p = 0.00134934322 + p * w;
    p = -0.00367342844 + p * w;
    p = 0.00573950773 + p * w;
    p = -0.0076224613 + p * w;
    p = 0.00943887047 + p * w;
    p = 1.00167406 + p * w;
    p = 2.83297682 + p * w;
  }
  double x = p * v;
  for (int k = 0; k < 2; ++k) x -= (std::erf(x) - v) / (2.0 / kSqrtPi * std::exp(-x * x));
  return x;
}

// r − sin r without cancellation for small r.
double r_minus_sin(double r) {
  if (r < 0.05) {
    const double r2 = r * r;
    return r * r2 * (1.0 / 6.0 - r2 * (1.0 / 120.0 - r2 * (1.0 / 5040.0 - r2 / 362880.0)));
  }
  return r - std::sin(r);
}

// Solves f(z) = target for f increasing on [lo, hi] (safeguarded Newton, bisection fallback).
template <class F, class dF>
double solve_increasing(F f, dF df, double target, double lo, double hi, double z) {
  z = std::clamp(z, lo, hi);
  for (int it = 0; it < 200; ++it) {
    const double r = f(z) - target;
    if (r == 0.0) return z;
    if (r > 0.0) hi = z; else lo = z;
    const double d = df(z);
    double next = d > 0.0 ? z - r / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - z) <= 1e-15 * std::abs(z) || hi - lo <= 1e-15 * std::abs(z)) return next;
    z = next;
  }
  return z;
}

// Normalisation S(a) = s_a + sin s_a, s_a = 2 atan(b a/m), written as π − k(2τ) with
// τ = atan(m/(b a)) so that it stays exact when m ≪ 1 (s_a → π).
double cdf_span(double m, double b, double a, double* tau_out = nullptr) {
  const double tau = std::atan2(m, b * a);
  if (tau_out) *tau_out = tau;
  return kPi - r_minus_sin(2.0 * tau);
}

}  // namespace

HalfVectorSampler::HalfVectorSampler(double m, double sigma)
    : m_(m), sigma_(sigma), b_(std::sqrt(std::max(0.0, 1.0 - m * m))), erf_norm_(std::erf(1.0 / sigma)),
      uniform_x_(b_ < 1e-7) {
  if (!(m > 0.0 && m <= 1.0)) throw Error("HalfVectorSampler: roughness m must be in (0, 1]");
  if (!(sigma > 0.0)) throw Error("HalfVectorSampler: sigma must be > 0");
}

double HalfVectorSampler::sample_hy(double u) const {
  const double y = sigma_ * erfinv((2.0 * u - 1.0) * erf_norm_);
  return std::clamp(y, -1.0, 1.0);
}

double HalfVectorSampler::pdf_hy(double hy) const {
  if (std::abs(hy) > 1.0) return 0.0;
  return std::exp(-(hy * hy) / (sigma_ * sigma_)) / (sigma_ * kSqrtPi * erf_norm_);
}

double HalfVectorSampler::sample_hx(double u, double a) const {
  if (!(a > 0.0)) return 0.0;
  if (uniform_x_) return a * (2.0 * u - 1.0);
  const double sign = u < 0.5 ? -1.0 : 1.0;
  const double v = std::min(std::abs(2.0 * u - 1.0), 1.0);
  double tau = 0.0;
  const double span = cdf_span(m_, b_, a, &tau);
  const double c = v * span;  // target of s + sin s
  double x = 0.0;
  constexpr double kSwitch = 2.0;  // s ≤ 2: direct form; s > 2: r = π − s
  if (c <= kSwitch + std::sin(kSwitch)) {
    const double s = solve_increasing([](double z) { return z + std::sin(z); },
                                      [](double z) { return 1.0 + std::cos(z); }, c, 0.0,
                                      std::min(kSwitch, kPi - 2.0 * tau), 0.5 * c);
    x = (m_ / b_) * std::tan(0.5 * s);
  } else {
    // π − (s + sin s) = k(r) with r = π − s: K = k(2τ) + (1 − v)·S.
    const double target = r_minus_sin(2.0 * tau) + (1.0 - v) * span;
    const double r = solve_increasing(r_minus_sin, [](double z) { return 1.0 - std::cos(z); }, target,
                                      2.0 * tau, kPi - kSwitch, std::cbrt(6.0 * target));
    x = (m_ / b_) / std::tan(0.5 * r);
  }
  return sign * std::min(x, a);
}

double HalfVectorSampler::pdf_hx(double hx, double a) const {
  if (!(a > 0.0) || std::abs(hx) > a) return 0.0;
  if (uniform_x_) return 0.5 / a;
  const double q = m_ * m_ + b_ * b_ * hx * hx;
  return 2.0 * m_ * m_ * m_ * b_ / (q * q * cdf_span(m_, b_, a));
}

Direction HalfVectorSampler::sample(double u1, double u2) const {
  const double y = sample_hy(u1);
  const double a = std::sqrt(std::max(0.0, 1.0 - y * y));
  const double x = sample_hx(u2, a);
  return {x, y, std::sqrt(std::max(0.0, 1.0 - x * x - y * y))};
}

double HalfVectorSampler::pdf_projected(double hx, double hy) const {
  const double r2 = hx * hx + hy * hy;
  if (r2 > 1.0) return 0.0;
  return pdf_hy(hy) * pdf_hx(hx, std::sqrt(1.0 - hy * hy));
}

double HalfVectorSampler::pdf_solid_angle(const Direction& h) const {
  return h.z > 0.0 ? pdf_projected(h.x, h.y) * h.z : 0.0;
}

double reflected_pdf(const HalfVectorSampler& s, const Direction& w_e, const Direction& w_o) {
  Direction h{w_e.x + w_o.x, w_e.y + w_o.y, w_e.z + w_o.z};
  const double len = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
  if (!(len > 1e-300)) return 0.0;
  h = {h.x / len, h.y / len, h.z / len};
  if (h.z < 0.0) h = {-h.x, -h.y, -h.z};
  const double d = std::abs(w_o.x * h.x + w_o.y * h.y + w_o.z * h.z);
  if (!(d > 0.0)) return 0.0;
  return s.pdf_solid_angle(h) / (4.0 * d);
}

}  // namespace plumage
