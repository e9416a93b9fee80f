// FeatherBsdf importance sampling (paper §7.2; spec geometry-and-brdf §4.10): χ² goodness of
// fit of sample() against pdf() for 20 parameter sets, ∫pdf = 1, and eval/pdf consistency
// (the mean sample weight equals the independently integrated albedo).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>

#include "bsdf_fixtures.hpp"
#include "plumage/feather_bsdf.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

struct SamplingCase {
  double m, sigma, theta_deg, phi_deg, offset_deg, albedo, transmission;
  bool below = false;  // ω_i from the lower side (two-sided BSDF)
};

// 20 sets: narrow to rough lobes, normal to grazing incidence, φ_eff ≠ φ_i, negative θ_i / φ_i
// (mirroring), lower-side incidence, with and without transmission.
const SamplingCase kCases[20] = {
    {0.2, 0.04, 0, 0, 0, 0.5, 0.0},        {0.05, 0.04, 30, 20, 0, 0.5, 0.0},
    {0.5, 0.04, 45, 0, 0, 0.5, 0.05},      {1.0, 0.04, 0, 45, 0, 0.5, 0.0},
    {0.01, 0.04, 20, 10, 5, 0.5, 0.0},     {0.003, 0.06, 10, 30, 0, 0.8, 0.02},
    {0.3, 0.08, -40, 25, 0, 0.6, 0.1},     {0.3, 0.08, 40, -25, 0, 0.6, 0.1, true},
    {0.7, 0.2, 60, 60, 0, 0.4, 0.3},       {0.1, 0.04, 75, 0, 0, 0.5, 0.0},
    {0.1, 0.04, 0, 80, 0, 0.5, 0.05},      {0.15, 0.04, 70, 70, 10, 0.5, 0.0},
    {0.4, 0.5, 20, -10, -10, 0.5, 0.2},    {0.999, 0.1, 30, 30, 0, 0.5, 0.0},
    {0.02, 0.02, 5, 5, 0, 0.9, 0.05},      {0.25, 0.04, -20, -50, 15, 0.5, 0.05},
    {0.6, 0.06, 85, 10, 0, 0.3, 0.0},      {0.08, 0.04, 50, 40, -20, 0.5, 0.1},
    {0.35, 0.3, 0, 0, 0, 0.5, 0.5},        {0.001, 0.04, 15, 15, 0, 0.5, 0.02},
};

std::shared_ptr<const FeatherMaterial> case_material(const SamplingCase& c) {
  MaterialRecipe r;
  r.grid = 4;
  r.sigma = c.sigma;
  r.m_eff = [m = c.m](int, double, double) { return m; };
  r.phi_offset = [o = deg_to_rad(c.offset_deg)](int, double, double) { return o; };
  r.albedo = [a = c.albedo](int, double, double) { return a; };
  return std::make_shared<FeatherMaterial>(
      make_material(r, [](const Lobe& l, double t) { return lobe_integral(l, t, 16, 3); }));
}

double uniform(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

}  // namespace

TEST_CASE("bsdf sampling: chi-square of sample() against pdf() for 20 parameter sets", "[bsdf]") {
  constexpr int kSamples = 200000;
  // Bonferroni: family-wise false-alarm rate 1 % over the 20 sets.
  constexpr double kAlpha = 0.01 / 20.0;
  for (int ci = 0; ci < 20; ++ci) {
    const SamplingCase& c = kCases[ci];
    FeatherBsdfOptions options;
    options.transmission_albedo = c.transmission;
    const FeatherBsdf bsdf(case_material(c), options);
    Direction wi = direction_from_angles(deg_to_rad(c.theta_deg), deg_to_rad(c.phi_deg));
    if (c.below) wi.z = -wi.z;
    const FeatherBsdf::Incident in = bsdf.incident(500.0, wi);
    REQUIRE(in.valid);
    // Bins adapted to the lobe around the mirror direction of ω_eff (world frame).
    const Direction centre{-in.w_eff.x * in.mirror_x, -in.w_eff.y * in.mirror_y, in.w_eff.z * in.flip_z};
    const double s_psi = std::max(1e-3, 2.0 * c.m / std::max(0.1, std::cos(deg_to_rad(c.theta_deg))));
    // The reflected pdf has an integrable 1/r singularity at ω_o = −ω_eff (ω_eff·h = 0).
    const Direction antipode{-in.w_eff.x * in.mirror_x, -in.w_eff.y * in.mirror_y, -in.w_eff.z * in.flip_z};
    const SphereBins bins = lobe_bins(centre, std::max(0.005, 2.0 * c.sigma), s_psi, 40, 40, false, &antipode);
    const std::vector<double> prob = integrate_bins(bins, [&](const Direction& w) { return bsdf.pdf(in, w); }, 6);
    const double total = std::accumulate(prob.begin(), prob.end(), 0.0);
    INFO("set " << ci << ": integral of pdf " << total);
    CHECK(std::abs(total - 1.0) < 1e-3);  // ∫pdf dω = 1 over the sphere

    std::mt19937_64 rng(0x5eed0000 + ci);
    std::vector<double> observed(bins.size(), 0.0);
    int invalid = 0, below = 0, outside = 0;
    double sw = 0.0, sw2 = 0.0;
    for (int k = 0; k < kSamples; ++k) {
      const double uc = uniform(rng), u1 = uniform(rng), u2 = uniform(rng);
      const BsdfSample s = bsdf.sample(in, uc, u1, u2);
      if (!(s.pdf > 0.0) || !std::isfinite(s.pdf) || !std::isfinite(s.weight) || s.weight < 0.0) ++invalid;
      if (!s.transmitted && s.wo.z * in.flip_z <= 0.0) ++below;
      const long b = bins.bin_of(s.wo);
      if (b < 0) ++outside; else observed[static_cast<std::size_t>(b)] += 1.0;
      sw += s.weight;
      sw2 += s.weight * s.weight;
    }
    CHECK(invalid == 0);
    CHECK(outside == 0);
    // Pool the cells with fewer than 5 expected samples into one.
    double chi2 = 0.0, pool_e = 0.0, pool_o = 0.0;
    int cells = 0;
    for (std::size_t b = 0; b < prob.size(); ++b) {
      const double e = prob[b] * kSamples;
      if (e < 5.0) { pool_e += e; pool_o += observed[b]; continue; }
      chi2 += (observed[b] - e) * (observed[b] - e) / e;
      ++cells;
    }
    if (pool_e >= 5.0 || pool_o > 0.0) {
      chi2 += (pool_o - pool_e) * (pool_o - pool_e) / std::max(pool_e, 1e-3);
      ++cells;
    }
    const double p = gamma_q(0.5 * (cells - 1), 0.5 * chi2);
    // Eval/pdf consistency: E[f cos/pdf] = A_r + T, with A_r integrated independently.
    const double mean_w = sw / kSamples;
    const double se_w = std::sqrt(std::max(0.0, sw2 / kSamples - mean_w * mean_w) / kSamples);
    const double albedo = lobe_integral(in.mean, in.theta_abs, 48, 6) + in.transmission;
    const double efficiency = mean_w * mean_w / (sw2 / kSamples);
    if (report_enabled()) {
      std::printf("chi2 set %2d: m %.3f sigma %.2f (%5.1f,%5.1f) cells %4d chi2 %8.1f p %.4f | int pdf %.6f | "
                  "E[w] %.5f +- %.5f vs albedo %.5f | efficiency %.3f below-horizon %.4f\n",
                  ci, c.m, c.sigma, c.theta_deg, c.phi_deg, cells, chi2, p, total, mean_w, se_w, albedo,
                  efficiency, static_cast<double>(below) / kSamples);
    }
    INFO("chi2 " << chi2 << " cells " << cells << " p " << p);
    CHECK(p > kAlpha);
    INFO("mean weight " << mean_w << " +- " << se_w << " albedo " << albedo);
    CHECK(std::abs(mean_w - albedo) < 4.0 * se_w + 1e-4);
  }
}
