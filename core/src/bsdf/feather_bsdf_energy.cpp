// Energy budget of FeatherBsdf (paper Eq. 12 and §7.2 last paragraph; spec geometry-and-brdf
// §4.3, §4.11): the reflected directional albedo A_r by stratified importance sampling on a fine
// (cos θ_i, cos φ_i) table, the transmission albedo T_w, and the reflection clamp that keeps
// A_r + T ≤ 1 between the nodes (see feather_bsdf.hpp, "Energy").
#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "plumage/feather_bsdf.hpp"
#include "plumage/fitter.hpp"
#include "plumage/lobe_sampling.hpp"

namespace plumage {

namespace {

// ω_i from its cosines, exactly on the horizon when either is 0.
Direction from_cosines(double ct, double cp) {
  return {ct * std::sqrt(std::max(0.0, 1.0 - cp * cp)), std::sqrt(std::max(0.0, 1.0 - ct * ct)), ct * cp};
}

// Gauss–Legendre nodes and weights on [0, 1].
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0.0);
  w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p1 = 1.0, p2 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
      }
      dp = n * (z * p1 - p2) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[static_cast<std::size_t>(i)] = 0.5 * (1.0 - z);
    w[static_cast<std::size_t>(i)] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

}  // namespace

// ∫ L dω_o = ∫∫ L/pdf du1 du2 over the sampler's unit square (the sampler is a bijection onto
// the sphere), by Gauss–Legendre in u1 (h_y) and, per u1, in u2 (h_x) on the pieces where ω_o is
// above the horizon: the crossings (at most a few) are bracketed on a 2·strata-step scan and
// refined by bisection, so the kink of the integrand at the horizon (G1 → 0) never sits inside
// a Gauss–Legendre panel. Cost ≈ strata × (2·strata + 30·crossings + strata·pieces) lobe
// evaluations. Accuracy (tests/test_bsdf_furnace.cpp): ≤ 1 % relative for the worst lobes
// (m ≈ 0.001 at θ_i ≈ 85°), ≤ 1e-3 for ordinary ones.
double FeatherBsdf::reflection_albedo(const Incident& in, int strata) const {
  if (!in.valid || !in.reflects || strata < 1) return 0.0;
  std::vector<double> x, w;
  gauss_legendre(strata, x, w);
  const HalfVectorSampler sampler(in.mean.m, in.mean.sigma);
  auto out_z = [&](double u1, double u2) { return reflect(in.w_eff, sampler.sample(u1, u2)).z; };
  auto weight = [&](double u1, double u2) {
    const Direction o = reflect(in.w_eff, sampler.sample(u1, u2));
    if (!(o.z > 0.0)) return 0.0;
    const double p = reflected_pdf(sampler, in.w_eff, o);
    return p > 0.0 ? lobe_value(in.mean, in.theta_abs, o) / p : 0.0;  // L = f̄ cos (spec §3)
  };
  const int kScan = 2 * strata;
  double sum = 0.0;
  std::vector<double> breaks;
  for (int a = 0; a < strata; ++a) {
    const double u1 = x[static_cast<std::size_t>(a)];
    breaks.assign({0.0});
    double prev = out_z(u1, 0.0);
    for (int k = 1; k <= kScan; ++k) {
      const double u = static_cast<double>(k) / kScan, z = out_z(u1, u);
      if ((z > 0.0) != (prev > 0.0)) {
        double lo = u - 1.0 / kScan, hi = u;  // bracket, refined to 2^-30 of a step
        for (int it = 0; it < 30; ++it) {
          const double mid = 0.5 * (lo + hi);
          ((out_z(u1, mid) > 0.0) == (prev > 0.0) ? lo : hi) = mid;
        }
        breaks.push_back(0.5 * (lo + hi));
      }
      prev = z;
    }
    breaks.push_back(1.0);
    double row = 0.0;
    for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
      const double lo = breaks[p], len = breaks[p + 1] - lo;
      if (!(out_z(u1, lo + 0.5 * len) > 0.0)) continue;  // a piece below the horizon
      for (int b = 0; b < strata; ++b) {
        row += w[static_cast<std::size_t>(b)] * len * weight(u1, lo + x[static_cast<std::size_t>(b)] * len);
      }
    }
    sum += w[static_cast<std::size_t>(a)] * row;
  }
  return sum;
}

// The same integral by plain n × n Gauss–Legendre over the sampler's square (no horizon splits):
// cheap, a few % off for lobes cut by the horizon.
double FeatherBsdf::screen_albedo(const Incident& in, int strata) const {
  if (!in.valid || !in.reflects || strata < 1) return 0.0;
  std::vector<double> x, w;
  gauss_legendre(strata, x, w);
  const HalfVectorSampler sampler(in.mean.m, in.mean.sigma);
  double sum = 0.0;
  for (int a = 0; a < strata; ++a) {
    for (int b = 0; b < strata; ++b) {
      const Direction o = reflect(in.w_eff, sampler.sample(x[static_cast<std::size_t>(a)], x[static_cast<std::size_t>(b)]));
      if (!(o.z > 0.0)) continue;
      const double p = reflected_pdf(sampler, in.w_eff, o);
      if (p > 0.0) sum += w[static_cast<std::size_t>(a)] * w[static_cast<std::size_t>(b)] * lobe_value(in.mean, in.theta_abs, o) / p;
    }
  }
  return sum;
}

void FeatherBsdf::compute_energy_budget() {
  const FeatherMaterial& m = *material_;
  const std::size_t bins = m.lambda_nm.size();
  const int g = m.grid;
  transmission_.assign(bins, 0.0);
  p_transmit_.assign(bins, 0.0);
  max_albedo_.assign(bins, 0.0);
  if (options_.albedo_strata < 1) return;
  // Fine axis: nodes, cell midpoints, and three extra points inside the grazing cell.
  for (int k = 0; k <= g; ++k) axis_.push_back(static_cast<double>(k) / g);
  for (int k = 0; k < g; ++k) axis_.push_back((k + 0.5) / g);
  for (double f : {0.125, 0.25, 0.75}) axis_.push_back(f / g);
  std::sort(axis_.begin(), axis_.end());
  const std::size_t n = axis_.size();
  // Start points of locate_energy: M cells of width 1/M, a few axis points per cell.
  const std::size_t cells = 8 * static_cast<std::size_t>(g);
  axis_start_.resize(cells + 1);
  for (std::size_t c = 0; c <= cells; ++c) {
    axis_start_[c] = static_cast<std::size_t>(
        std::upper_bound(axis_.begin(), axis_.end(), static_cast<double>(c) / static_cast<double>(cells)) - axis_.begin());
  }
  albedo_table_.assign(bins * n * n, 0.0);
  std::vector<double> mean_albedo(bins, 0.0);
  const double cap = 1.0 - options_.transmission_albedo - options_.albedo_margin;
  const double screen_above = cap - 0.15, refine_above = cap - 0.05;
  tbb::parallel_for(std::size_t{0}, bins, [&](std::size_t w) {
    double worst = 0.0, total = 0.0;
    int nodes = 0;
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b < n; ++b) {
        // The grazing rows hold the limit ct, cp → 0⁺ (the BSDF is 0 exactly on the horizon,
        // but F = table/(cos θ_i cos φ_i) tends to a finite, possibly large, value).
        const double ct = std::max(axis_[a], 1e-6), cp = std::max(axis_[b], 1e-6);
        const Incident in = raw_incident(w, make_geometry(ct, cp, from_cosines(ct, cp)));
        // Three levels, each only where the budget may bind: a plain Gauss–Legendre screen
        // (errors up to a few %), the horizon-split estimate (≤ 1.7 %), and the fitter's
        // accurate hemisphere integral (the rule of its Eq. 12 normalisation, ~1e-7).
        double albedo = screen_albedo(in, options_.albedo_strata);
        if (albedo > screen_above) albedo = reflection_albedo(in, options_.albedo_strata);
        if (in.reflects && albedo > refine_above) albedo = hemisphere_lobe_integral(in.mean, in.theta_abs);
        albedo_table_[(w * n + a) * n + b] = albedo;
        const double it = axis_[a] * g, jt = axis_[b] * g;
        if (it == std::round(it) && jt == std::round(jt) && it >= 1 && jt >= 1) {  // a fitted node
          worst = std::max(worst, albedo);
          total += albedo;
          ++nodes;
        }
      }
    }
    max_albedo_[w] = worst;
    mean_albedo[w] = total / nodes;
  });
  for (std::size_t w = 0; w < bins; ++w) {
    transmission_[w] = std::clamp(1.0 - max_albedo_[w] - options_.albedo_margin, 0.0, options_.transmission_albedo);
    // Lobe choice in proportion to the albedos (constant per bin, so pdf() stays cheap).
    const double t = transmission_[w];
    p_transmit_[w] = t > 0.0 ? t / (t + std::max(mean_albedo[w], 1e-3)) : 0.0;
  }
}

// The index upper_bound(axis_, v) − 1 (clamped to a cell) and the weight of v in that cell: the
// upper bound found from a precomputed start and a short walk, equal to std::upper_bound's.
void FeatherBsdf::locate_energy(double v, std::size_t& i, double& t) const {
  const std::size_t n = axis_.size(), cells = axis_start_.size() - 1;
  v = std::clamp(v, 0.0, 1.0);
  const std::size_t c = std::min(static_cast<std::size_t>(v * static_cast<double>(cells)), cells);
  std::size_t k = axis_start_[c];
  while (k > 0 && axis_[k - 1] > v) --k;  // c/M rounded above v
  while (k < n && axis_[k] <= v) ++k;
  i = std::clamp<std::size_t>(k, 1, n - 1) - 1;
  t = (v - axis_[i]) / (axis_[i + 1] - axis_[i]);
}

double FeatherBsdf::energy_scale(std::size_t bin, const IncidentGeometry& g) const {
  if (albedo_table_.empty()) return 1.0;
  const std::size_t n = axis_.size();
  const std::size_t a = g.energy_a, b = g.energy_b;
  const double u = g.energy_u, v = g.energy_v;
  const double* row = albedo_table_.data() + bin * n * n;
  const double albedo = (1 - u) * ((1 - v) * row[a * n + b] + v * row[a * n + b + 1]) +
                        u * ((1 - v) * row[(a + 1) * n + b] + v * row[(a + 1) * n + b + 1]);
  const double cap = 1.0 - transmission_albedo(bin) - options_.albedo_margin;
  return albedo > cap && albedo > 0.0 ? std::max(cap, 0.0) / albedo : 1.0;
}

}  // namespace plumage
