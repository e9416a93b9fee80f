// Shared fixtures of the FeatherBsdf tests (tests/test_bsdf_*.cpp): synthetic feather
// materials, synthetic noise pools with fixed seeds, an independent quadrature over the sphere
// (adapted tensor Gauss–Legendre in the equal-area coordinates (y, ψ)), and the χ² p-value.
// Header-only; everything deterministic (own Box–Muller, not std::normal_distribution, whose
// output is implementation-defined).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "plumage/conventions.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/feather_material.hpp"

namespace plumage::testing {

// ---- materials ------------------------------------------------------------------------------

// Node parameters as functions of (bin, cos θ_i, cos φ_i).
struct MaterialRecipe {
  int bins = 1;
  int grid = 20;
  double sigma = 0.04;
  double l0 = 0.3;
  std::function<double(int, double, double)> m_eff = [](int, double, double) { return 0.2; };
  std::function<double(int, double, double)> phi_offset = [](int, double, double) { return 0.0; };  // φ_eff − φ_i
  std::function<double(int, double, double)> albedo = [](int, double, double) { return 0.5; };     // E of Eq. 12
  std::function<double(int, double, double)> m_sta = [](int, double, double) { return 0.1; };
  std::function<double(int, double, double)> coherent = [](int, double, double) { return 0.3; };  // F_sta/F_eff
  double pol_share = 0.6;
  double correlation = 1.0;
};

// Builds the material; F_eff at each node from `normalise(bin, ct, cp, lobe)`, which returns
// ∫ L_{F=1} dω for the node's lobe (the fitter's Eq. 12 integral), so that A_r = E at nodes.
inline FeatherMaterial make_material(const MaterialRecipe& r,
                                     const std::function<double(const Lobe&, double theta_i)>& integral) {
  FeatherMaterial m;
  m.label = "synthetic/test";
  m.sigma = r.sigma;
  m.l0 = r.l0;
  m.grid = r.grid;
  for (int w = 0; w < r.bins; ++w) m.lambda_nm.push_back(400.0 + 6.0 * w);
  m.nodes.resize(static_cast<std::size_t>(r.bins) * (r.grid + 1) * (r.grid + 1));
  for (int w = 0; w < r.bins; ++w) {
    for (int i = 0; i <= r.grid; ++i) {
      for (int j = 0; j <= r.grid; ++j) {
        const double ct = static_cast<double>(i) / r.grid, cp = static_cast<double>(j) / r.grid;
        MaterialNode& n = m.node(static_cast<std::size_t>(w), i, j);
        const double phi_i = std::acos(cp);
        n.m_eff = r.m_eff(w, ct, cp);
        n.phi_eff = std::clamp(phi_i + r.phi_offset(w, ct, cp), -0.5 * kPi, 0.5 * kPi);
        n.m_sta = r.m_sta(w, ct, cp);
        n.phi_sta = n.phi_eff;
        n.pol_share = r.pol_share;
        n.correlation = r.correlation;
        n.f_eff = n.f_sta = 0.0;
        if (i == 0 || j == 0) continue;  // grazing rows: F = 0 (spec §4.7)
        const double theta_i = std::acos(ct);
        const double I = integral(Lobe{n.m_eff, n.phi_eff, r.sigma, 1.0}, theta_i);
        const double F = I > 0.0 ? r.albedo(w, ct, cp) / I : 0.0;
        n.f_eff = F * ct * cp;  // premultiplied (spec §4.3)
        n.f_sta = r.coherent(w, ct, cp) * n.f_eff;
      }
    }
  }
  return m;
}

// ---- noise pools ----------------------------------------------------------------------------

class Gauss {
 public:
  explicit Gauss(std::uint64_t seed) : rng_(seed) {}
  double operator()() {
    if (has_) { has_ = false; return spare_; }
    const double u1 = (static_cast<double>(rng_() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    has_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_ = false;
};

// Independent stationary Gaussian AR(1) functions: zero mean, unit variance, lag-1 ρ.
inline NoisePool ar1_pool(std::size_t count, int samples, double rho, std::uint64_t seed) {
  NoisePool p;
  p.samples = samples;
  p.lag1 = rho;
  p.functions.resize(count * static_cast<std::size_t>(samples));
  Gauss g(seed);
  const double c = std::sqrt(1.0 - rho * rho);
  for (std::size_t k = 0; k < count; ++k) {
    double v = g();
    for (int t = 0; t < samples; ++t) {
      if (t > 0) v = rho * v + c * g();
      p.functions[k * samples + t] = static_cast<float>(v);
    }
  }
  return p;
}

// The same pool with exact sample moments: at every position, the even-indexed functions (n_Re
// of the instances) and the odd ones (n_Im) each have sample mean 0 and sample variance 1; lag1
// becomes the measured mean lag-1 correlation.
inline NoisePool normalised_pool(NoisePool p) {
  const std::size_t count = p.count();
  const int n = p.samples;
  double lag_sum = 0.0;
  for (std::size_t parity = 0; parity < 2; ++parity) {
    for (int t = 0; t < n; ++t) {
      double s = 0.0, s2 = 0.0, cnt = 0.0;
      for (std::size_t k = parity; k < count; k += 2) { s += p.functions[k * n + t]; cnt += 1; }
      const double mean = s / cnt;
      for (std::size_t k = parity; k < count; k += 2) { const double d = p.functions[k * n + t] - mean; s2 += d * d; }
      const double sd = std::sqrt(s2 / cnt);
      for (std::size_t k = parity; k < count; k += 2) {
        p.functions[k * n + t] = static_cast<float>((p.functions[k * n + t] - mean) / sd);
      }
    }
    for (int t = 0; t + 1 < n; ++t) {
      double c = 0.0, cnt = 0.0;
      for (std::size_t k = parity; k < count; k += 2) { c += double(p.functions[k * n + t]) * p.functions[k * n + t + 1]; cnt += 1; }
      lag_sum += c / cnt;
    }
  }
  p.lag1 = lag_sum / (2.0 * (n - 1));
  return p;
}

// ---- quadrature on the sphere ----------------------------------------------------------------

// Gauss–Legendre nodes and weights on [0, 1].
inline void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), pp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p1 = 1.0, p2 = 0.0;
      for (int j = 1; j <= n; ++j) { const double p3 = p2; p2 = p1; p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j; }
      pp = n * (z * p1 - p2) / (z * z - 1.0);
      const double dz = p1 / pp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1.0 - z);
    w[i] = 1.0 / ((1.0 - z * z) * pp * pp);
  }
}

// ω(y, ψ) = (sqrt(1 − y²) sin ψ, y, sqrt(1 − y²) cos ψ); dω = dy dψ (equal-area, Archimedes).
inline Direction from_y_psi(double y, double psi) {
  const double c = std::sqrt(std::max(0.0, 1.0 - y * y));
  return {c * std::sin(psi), y, c * std::cos(psi)};
}

// Edges on [lo, hi]: equal steps of the mixture CDF (1 − q)·uniform + q·(truncated kernel
// centred at c with scale s), kernel Gaussian or Cauchy; extra edges are inserted.
inline std::vector<double> adapted_edges(double lo, double hi, double c, double s, bool cauchy, int n,
                                         std::vector<double> extra = {}) {
  const double q = 0.75;
  auto kernel = [&](double x) {
    const double z = (x - c) / s;
    return cauchy ? std::atan(z) / kPi : 0.5 * std::erf(z / std::sqrt(2.0));
  };
  const double k0 = kernel(lo), k1 = kernel(hi);
  auto cdf = [&](double x) { return (1.0 - q) * (x - lo) / (hi - lo) + q * (kernel(x) - k0) / (k1 - k0); };
  std::vector<double> e{lo};
  for (int i = 1; i < n; ++i) {
    const double target = static_cast<double>(i) / n;
    double a = lo, b = hi;
    for (int it = 0; it < 60; ++it) { const double mid = 0.5 * (a + b); (cdf(mid) < target ? a : b) = mid; }
    e.push_back(0.5 * (a + b));
  }
  e.push_back(hi);
  for (double x : extra) if (x > lo && x < hi) e.push_back(x);
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }), e.end());
  return e;
}

struct SphereBins {
  std::vector<double> y_edges, psi_edges;
  std::size_t size() const { return (y_edges.size() - 1) * (psi_edges.size() - 1); }
  // Bin of a direction, or −1 if outside.
  long bin_of(const Direction& w) const {
    const double psi = std::atan2(w.x, w.z);
    const auto iy = std::upper_bound(y_edges.begin(), y_edges.end(), w.y) - y_edges.begin() - 1;
    const auto ip = std::upper_bound(psi_edges.begin(), psi_edges.end(), psi) - psi_edges.begin() - 1;
    if (iy < 0 || ip < 0 || iy >= long(y_edges.size()) - 1 || ip >= long(psi_edges.size()) - 1) return -1;
    return iy * long(psi_edges.size() - 1) + ip;
  }
};

// Bins adapted to a lobe around direction `centre` with widths s_y (in y) and s_psi (in ψ);
// `upper` restricts to the upper hemisphere (ψ ∈ [−π/2, π/2]).
// `singular`: a direction where the integrand has an integrable 1/r singularity (the reflected
// pdf at ω_o = −ω_eff, where ω_eff·h = 0): edges are added at it and geometrically around it.
inline SphereBins lobe_bins(const Direction& centre, double s_y, double s_psi, int ny, int npsi, bool upper,
                            const Direction* singular = nullptr) {
  SphereBins b;
  const double pc = std::atan2(centre.x, centre.z);
  std::vector<double> ey, ep{-0.5 * kPi, 0.5 * kPi};
  if (singular) {
    const double sy = singular->y, sp = std::atan2(singular->x, singular->z);
    ey.push_back(sy);
    ep.push_back(sp);
    for (double d = 1e-5; d < 0.1; d *= 3.0) {
      ey.insert(ey.end(), {sy - d, sy + d});
      ep.insert(ep.end(), {sp - d, sp + d});
    }
  }
  b.y_edges = adapted_edges(-1.0, 1.0, centre.y, s_y, false, ny, ey);
  if (upper) {
    b.psi_edges = adapted_edges(-0.5 * kPi, 0.5 * kPi, std::clamp(pc, -0.5 * kPi, 0.5 * kPi), s_psi, true, npsi, ep);
  } else {
    b.psi_edges = adapted_edges(-kPi, kPi, pc, s_psi, true, npsi, ep);
  }
  return b;
}

// Integral of f over each bin (tensor Gauss–Legendre of `order` points per axis).
inline std::vector<double> integrate_bins(const SphereBins& b, const std::function<double(const Direction&)>& f,
                                          int order) {
  std::vector<double> gx, gw;
  gauss_legendre(order, gx, gw);
  const std::size_t np = b.psi_edges.size() - 1;
  std::vector<double> out(b.size(), 0.0);
  for (std::size_t iy = 0; iy + 1 < b.y_edges.size(); ++iy) {
    const double y0 = b.y_edges[iy], dy = b.y_edges[iy + 1] - y0;
    for (std::size_t ip = 0; ip < np; ++ip) {
      const double p0 = b.psi_edges[ip], dp = b.psi_edges[ip + 1] - p0;
      double s = 0.0;
      for (int a = 0; a < order; ++a)
        for (int c = 0; c < order; ++c) s += gw[a] * gw[c] * f(from_y_psi(y0 + gx[a] * dy, p0 + gx[c] * dp));
      out[iy * np + ip] = s * dy * dp;
    }
  }
  return out;
}

// Directional albedo ∫_{H+} L dω of a lobe, independent of the sampling code: the change of
// variables ω_o = reflect(ω_eff, h) with h on the upper hemisphere covers the sphere once, and
// dω_o = 4|ω_o·h| dω_h = 4|ω_o·h|/h_z dh_x dh_y. In (h_y, ξ = h_x/a(h_y)) the integrand has
// separable peaks of widths σ and m (paper Eq. 17), so tensor Gauss–Legendre on edges adapted to
// them converges quickly even for m = 0.001 at grazing incidence.
inline double lobe_integral(const Lobe& lobe, double theta_i, int nbins = 32, int order = 4) {
  const Direction we = direction_from_angles(theta_i, lobe.phi_c_rad);
  if (!(we.z > 0.0)) return 0.0;
  std::vector<double> gx, gw;
  gauss_legendre(order, gx, gw);
  const std::vector<double> ye = adapted_edges(-1.0, 1.0, 0.0, lobe.sigma / std::sqrt(2.0), false, nbins);
  double total = 0.0;
  for (std::size_t iy = 0; iy + 1 < ye.size(); ++iy) {
    const double y0 = ye[iy], dy = ye[iy + 1] - y0;
    const double ymid = y0 + 0.5 * dy, rim_mid = std::sqrt(std::max(1e-12, 1.0 - ymid * ymid));
    const std::vector<double> xe = adapted_edges(-1.0, 1.0, 0.0, std::max(lobe.m / rim_mid, 1e-6), true, nbins);
    for (int a = 0; a < order; ++a) {
      const double hy = y0 + gx[a] * dy;
      const double rim = std::sqrt(std::max(0.0, 1.0 - hy * hy));
      if (!(rim > 0.0)) continue;
      double inner = 0.0;
      for (std::size_t ix = 0; ix + 1 < xe.size(); ++ix) {
        const double x0 = xe[ix], dx = xe[ix + 1] - x0;
        for (int c = 0; c < order; ++c) {
          const double hx = rim * (x0 + gx[c] * dx);
          const double hz = std::sqrt(std::max(0.0, 1.0 - hx * hx - hy * hy));
          if (!(hz > 0.0)) continue;
          const Direction h{hx, hy, hz};
          const double d = we.x * h.x + we.y * h.y + we.z * h.z;
          const Direction wo{2 * d * h.x - we.x, 2 * d * h.y - we.y, 2 * d * h.z - we.z};
          if (!(wo.z > 0.0)) continue;
          inner += gw[c] * dx * lobe_value(lobe, theta_i, wo) * 4.0 * std::abs(d) / hz;
        }
      }
      total += gw[a] * dy * inner * rim;
    }
  }
  return total;
}

// ---- statistics -----------------------------------------------------------------------------

// Regularised upper incomplete gamma Q(a, x) (series / continued fraction, Numerical Recipes).
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1.0) {
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 10000; ++n) { ap += 1; del *= x / ap; sum += del; if (std::abs(del) < std::abs(sum) * 1e-15) break; }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  double b = x + 1.0 - a, c = 1.0 / 1e-300, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b; if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c; if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

inline bool report_enabled() { return std::getenv("PLUMAGE_BSDF_REPORT") != nullptr; }

}  // namespace plumage::testing
