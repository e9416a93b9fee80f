// FeatherBsdf instances (paper Eqs. 19–24; spec geometry-and-brdf §4.9 steps 4–6): the average
// of 10⁴ instances against the mean BRDF, noise lookup and the no-noise fallback.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "bsdf_fixtures.hpp"
#include "plumage/feather_bsdf.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

constexpr int kInstances = 10000;

// Two bins; relative correlation lengths l/l0 = 0.3 (bin 0) and 0.21 (bin 1), so l_min = 0.21
// and the bin-0 queries with 0.21 < |x| ≤ 0.3 exercise the shared cut-off.
std::shared_ptr<FeatherMaterial> instance_material(NoisePool pool) {
  MaterialRecipe r;
  r.bins = 2;
  r.grid = 4;
  r.l0 = 0.3;
  r.m_eff = [](int, double, double) { return 0.15; };
  r.m_sta = [](int, double, double) { return 0.08; };
  r.coherent = [](int w, double, double) { return w == 0 ? 0.2 : 0.05; };  // bin 0: partly coherent; bin 1: nearly developed speckle
  r.pol_share = 0.6;
  r.correlation = 0.3;
  auto m = std::make_shared<FeatherMaterial>(
      make_material(r, [](const Lobe& l, double t) { return lobe_integral(l, t, 16, 3); }));
  for (int i = 0; i <= r.grid; ++i)
    for (int j = 0; j <= r.grid; ++j) m->node(1, i, j).correlation = 0.21;
  m->noise = std::move(pool);
  return m;
}

struct Query {
  double theta_i, phi_i, theta_o, phi_o;  // degrees
};
// Points in the noisy region |x| = |ω_i,x + ω_o,x| ≤ l_min = 0.21, on and off the specular cone,
// all four mirror quadrants of ω_i.
const Query kQueries[] = {
    {0, 0, 0, 0},     {0, 0, 0, 8},       {20, 10, -20, -5}, {-30, -15, 31, 10},
    {45, 30, -43, -20}, {10, 60, -10, -55}, {0, 0, 1, 11},     {-15, 40, 14, -35},
};

Direction dir(double t, double p) { return direction_from_angles(deg_to_rad(t), deg_to_rad(p)); }

}  // namespace

TEST_CASE("bsdf instances: the average of 1e4 instances is the mean BRDF (z-test on the measured standard error)",
          "[bsdf]") {
  const FeatherBsdf bsdf(instance_material(ar1_pool(2 * kInstances, 64, 0.8, 0xfea7)), {});
  // 8 points × 2 bins, two-sided, family-wise α = 1e-3 (Bonferroni): |z| < 4.0.
  constexpr double kZ = 4.0;
  double worst_rel = 0.0, worst_se = 0.0;
  for (const double lambda : {401.0, 407.0}) {
    for (const Query& q : kQueries) {
      const Direction wi = dir(q.theta_i, q.phi_i), wo = dir(q.theta_o, q.phi_o);
      REQUIRE(std::abs(wi.x + wo.x) <= 0.21);
      const FeatherBsdf::Incident in = bsdf.incident(lambda, wi);
      const double mean = bsdf.eval(in, wo);
      REQUIRE(mean > 0.0);
      double s = 0.0, s2 = 0.0;
      int differs = 0;
      for (int k = 0; k < kInstances; ++k) {
        const double f = bsdf.eval(in, wo, static_cast<std::uint64_t>(k));
        REQUIRE(std::isfinite(f));
        REQUIRE(f >= 0.0);
        differs += f != mean;
        s += f;
        s2 += f * f;
      }
      const double avg = s / kInstances;
      const double se = std::sqrt((s2 / kInstances - avg * avg) / (kInstances - 1));
      const double z = (avg - mean) / se;
      worst_rel = std::max(worst_rel, std::abs(avg / mean - 1.0));
      worst_se = std::max(worst_se, se / mean);
      if (report_enabled()) {
        std::printf("instances iid  λ %.0f (%4.0f,%4.0f)->(%4.0f,%4.0f): mean %.5g avg %.5g rel.dev %+.4f SE/mean %.4f z %+.2f\n",
                    lambda, q.theta_i, q.phi_i, q.theta_o, q.phi_o, mean, avg, avg / mean - 1.0, se / mean, z);
      }
      INFO("λ " << lambda << " query (" << q.theta_i << "," << q.phi_i << ")->(" << q.theta_o << "," << q.phi_o
                << "): mean " << mean << " avg " << avg << " se " << se);
      CHECK(differs > kInstances / 2);  // the noisy region is really noisy
      CHECK(std::abs(z) < kZ);
      CHECK(se / mean < 0.012);  // 10⁴ instances resolve the mean to ≈ 1 % (fully developed speckle: SE = f̄/100)
    }
  }
  if (report_enabled()) std::printf("instances iid: worst |rel.dev| %.4f, worst SE/mean %.4f\n", worst_rel, worst_se);
}

TEST_CASE("bsdf instances: with exact pool moments the average of 1e4 instances is within 1 % of the mean", "[bsdf]") {
  // The pool's own sampling error removed (every position: mean 0, variance 1 over the 10⁴
  // n_Re and the 10⁴ n_Im functions): what remains is the instance formula and the
  // variance-preserving interpolation (deterministic, no statistical tolerance needed).
  const FeatherBsdf bsdf(instance_material(normalised_pool(ar1_pool(2 * kInstances, 64, 0.8, 0xfea7))), {});
  double worst = 0.0;
  for (const double lambda : {401.0, 407.0}) {
    for (const Query& q : kQueries) {
      const Direction wi = dir(q.theta_i, q.phi_i), wo = dir(q.theta_o, q.phi_o);
      const FeatherBsdf::Incident in = bsdf.incident(lambda, wi);
      const double mean = bsdf.eval(in, wo);
      double s = 0.0;
      for (int k = 0; k < kInstances; ++k) s += bsdf.eval(in, wo, static_cast<std::uint64_t>(k));
      const double rel = s / kInstances / mean - 1.0;
      worst = std::max(worst, std::abs(rel));
      INFO("λ " << lambda << " query (" << q.theta_i << "," << q.phi_i << ")->(" << q.theta_o << "," << q.phi_o << ")");
      CHECK(std::abs(rel) < 0.01);
    }
  }
  if (report_enabled()) std::printf("instances normalised pool: worst |rel.dev| %.2e\n", worst);
}

TEST_CASE("bsdf instances: no noise beyond l_min, on transmission, or without a pool", "[bsdf]") {
  auto material = instance_material(ar1_pool(64, 64, 0.8, 7));
  const FeatherBsdf bsdf(material, {});
  const Direction wi = dir(0, 0);
  for (double phi_o : {13.0, 30.0, -40.0}) {  // |x| = |sin φ_o| > 0.21
    const Direction wo = dir(0, phi_o);
    const double mean = bsdf.eval(401.0, wi, wo);
    for (std::uint64_t k = 0; k < 20; ++k) CHECK(bsdf.eval(401.0, wi, wo, k) == mean);
  }
  const Direction down{0.1, 0.2, -std::sqrt(1 - 0.05)};
  CHECK(bsdf.eval(401.0, wi, down, 3) == bsdf.eval(401.0, wi, down));
  auto bare = std::make_shared<FeatherMaterial>(*material);
  bare->noise = {};
  const FeatherBsdf plain(bare, {});
  CHECK(plain.eval(401.0, wi, dir(0, 5), 9) == plain.eval(401.0, wi, dir(0, 5)));
}

TEST_CASE("bsdf instances: noise lookup interpolates with unit variance and is continuous across phi_i = 0", "[bsdf]") {
  auto material = instance_material(ar1_pool(4, 64, 0.8, 11));
  const FeatherBsdf bsdf(material, {});
  const float* q = material->noise.function(2);
  const double l = 0.2;
  double v = 0.0;
  // Sample t sits at x = l·(−1 + (2t + 1)/64).
  REQUIRE(bsdf.noise_value(2, l * (-1.0 + 11.0 / 64.0), l, &v));
  CHECK(v == Approx(q[5]).epsilon(1e-12));
  REQUIRE(bsdf.noise_value(2, l * (-1.0 + 12.0 / 64.0), l, &v));  // midway between t = 5 and 6
  CHECK(v == Approx(0.5 * (double(q[5]) + double(q[6])) / std::sqrt(0.5 + 0.5 * 0.8)).epsilon(1e-12));
  REQUIRE(bsdf.noise_value(2, -0.2099, 0.2101, &v));  // rim half-sample: constant extension
  CHECK(v == Approx(q[0]).epsilon(1e-12));
  CHECK_FALSE(bsdf.noise_value(2, 0.2101, 0.3, &v));   // beyond l_min = 0.21
  CHECK_FALSE(bsdf.noise_value(2, 0.15, 0.1, &v));     // beyond the function's domain (|x/l| > 1)
  // World-frame noise coordinate (Eq. 24): an instance changes continuously when φ_i changes sign.
  const Direction wo = dir(0, 3);
  const double plus = bsdf.eval(401.0, dir(5, 1e-7), wo, 1), minus = bsdf.eval(401.0, dir(5, -1e-7), wo, 1);
  CHECK(plus == Approx(minus).epsilon(1e-5));
}
