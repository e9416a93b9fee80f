// Acceptance 1 (issue 8): white furnace. A convex closed mesh (icosphere) of white Lambertian
// albedo 1 inside a constant D65 environment of radiance R: every pixel, sphere or background,
// has expectation R·white (the renderer's colour convention: D65 × 1 → the D65 white point).
// With the feather BSDF instead the sphere can only be darker (energy conservation).
//
// Noise bounds, from the sample count:
//  * Hoeffding (rigorous, loose): one camera sample's colour lies in a known interval of width
//    M_c per channel (path weight ≤ 1.5 on a convex Lambertian body: 1 for the escaping BSDF ray
//    plus ≤ 0.5 for the power-heuristic NEE of the uniform-sphere environment sample; times the
//    spectral factor range·max(D65·cmf)/∫D65·cmf), so the image mean over n samples is within
//    M_c·sqrt(ln(2/δ)/(2n)) of R with probability ≥ 1 − δ, δ = 1e-9;
//  * CLT (tighter): the sphere pixels' mean within 4 standard errors (σ̂/√N from their spread),
//    and no pixel farther than 6 σ̂ from R (no bias, no outliers).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "pathtracer.hpp"
#include "render_fixtures.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

constexpr double kEnv = 0.7;
constexpr int kSize = 32, kSpp = 64;

Scene furnace(SceneMaterial material) {
  Scene s;
  s.name = "furnace";
  s.materials = {std::move(material)};
  s.meshes.push_back(icosphere(1.0, 3, 0));
  s.environment.radiance = kEnv;
  s.camera = far_camera({0.0, 0.0, 1.0}, 4.0, 0.6, kSize);
  return s;
}

struct Channel {
  double Rgb::*c;
  const char* name;
};
const Channel kChannels[3] = {{&Rgb::r, "r"}, {&Rgb::g, "g"}, {&Rgb::b, "b"}};
double pick(const RgbF& p, int c) { return c == 0 ? p.r : c == 1 ? p.g : p.b; }

// Width of the interval one sample's linear sRGB channel c can take, for path weights in [0, w].
double sample_range(int c, double w) {
  const CieTables& t = cie_tables();
  double max_x = 0, max_y = 0, max_z = 0, ix = 0, iy = 0, iz = 0;
  for (std::size_t i = 0; i < t.lambda_nm.size(); ++i) {
    const double l = t.lambda_nm[i];
    if (l < 400.0 || l > 700.0) continue;
    max_x = std::max(max_x, t.d65[i] * t.xbar[i]);
    max_y = std::max(max_y, t.d65[i] * t.ybar[i]);
    max_z = std::max(max_z, t.d65[i] * t.zbar[i]);
    const double h = (l == 400.0 || l == 700.0) ? 2.5 : 5.0;
    ix += h * t.d65[i] * t.xbar[i];
    iy += h * t.d65[i] * t.ybar[i];
    iz += h * t.d65[i] * t.zbar[i];
  }
  const Xyz white = d65_white_point();
  // Largest XYZ of one sample (all four λ at the maximum), ×1.02 for the 5 nm table's interpolation.
  const double k = 1.02 * w * kEnv * 300.0;
  const double X = k * max_x * white.x / ix, Y = k * max_y * white.y / iy, Z = k * max_z * white.z / iz;
  const Rgb mx = xyz_to_linear_srgb({1, 0, 0}), my = xyz_to_linear_srgb({0, 1, 0}), mz = xyz_to_linear_srgb({0, 0, 1});
  return std::abs(mx.*kChannels[c].c) * X + std::abs(my.*kChannels[c].c) * Y + std::abs(mz.*kChannels[c].c) * Z;
}

}  // namespace

TEST_CASE("pathtracer furnace: a white Lambertian sphere in a constant environment vanishes", "[pathtracer]") {
  pathtracer::Settings settings;
  settings.samples_per_pixel = kSpp;
  settings.max_depth = 8;
  const RenderResult r = pathtracer::PathTracer(settings).render(furnace(diffuse(1.0)), {});
  const Rgb white = xyz_to_linear_srgb(d65_white_point());
  const double n = static_cast<double>(kSize) * kSize * kSpp;
  for (int c = 0; c < 3; ++c) {
    const double expected = kEnv * (white.*kChannels[c].c);
    // Sphere pixels: the central disc (radius 0.8 of the sphere's image radius ≈ 0.34·size).
    double sum_all = 0, sum = 0, sum2 = 0, count = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const double v = pick(r.rgb.at(x, y), c);
        sum_all += v;
        const double dx = x + 0.5 - 0.5 * kSize, dy = y + 0.5 - 0.5 * kSize;
        if (dx * dx + dy * dy < std::pow(0.8 * 0.34 * kSize, 2)) {
          sum += v;
          sum2 += v * v;
          count += 1;
        }
      }
    }
    const double mean_all = sum_all / (kSize * kSize);
    const double hoeffding = sample_range(c, 1.5) * std::sqrt(std::log(2.0 / 1e-9) / (2.0 * n));
    const double mean = sum / count, sd = std::sqrt(std::max(0.0, sum2 / count - mean * mean));
    const double se = sd / std::sqrt(count);
    double worst = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) worst = std::max(worst, std::abs(pick(r.rgb.at(x, y), c) - expected));
    INFO("channel " << kChannels[c].name << ": expected " << expected << ", image mean " << mean_all << " (Hoeffding "
                    << hoeffding << "), sphere mean " << mean << " ± " << se << " (pixel sd " << sd << ", " << count
                    << " px), worst pixel deviation " << worst);
    std::printf("furnace lambert %s: expected %.5f image mean %.5f (Hoeffding bound %.4f) sphere mean %.5f se %.5f sd %.5f worst %.4f\n",
                kChannels[c].name, expected, mean_all, hoeffding, mean, se, sd, worst);
    CHECK(std::abs(mean_all - expected) <= hoeffding);
    CHECK(std::abs(mean - expected) <= 4.0 * se);
    CHECK(worst <= 6.0 * sd);
  }
}

namespace {
// Mean sRGB luminance (Y) of the pixels well inside the sphere's silhouette, and its standard error.
std::pair<double, double> sphere_luminance(const RenderResult& r) {
  double sum = 0, sum2 = 0, count = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double dx = x + 0.5 - 0.5 * kSize, dy = y + 0.5 - 0.5 * kSize;
      if (dx * dx + dy * dy >= std::pow(0.8 * 0.34 * kSize, 2)) continue;
      const RgbF p = r.rgb.at(x, y);
      const double Y = srgb_luminance({p.r, p.g, p.b});
      sum += Y;
      sum2 += Y * Y;
      count += 1;
    }
  }
  const double mean = sum / count;
  return {mean, std::sqrt(std::max(0.0, sum2 / count - mean * mean) / count)};
}
}  // namespace

TEST_CASE("pathtracer furnace: a feather-BSDF sphere is no brighter than the environment", "[pathtracer]") {
  pathtracer::Settings settings;
  settings.samples_per_pixel = kSpp;
  settings.max_depth = 8;
  settings.lod = pathtracer::LevelOfDetail::mean;
  const RenderResult r = pathtracer::PathTracer(settings).render(furnace(feather(synthetic_feather(1.0, 8))), {});
  // Luminance (Y) of the sphere pixels against the environment's (Y = R).
  const auto [mean, se] = sphere_luminance(r);
  std::printf("furnace feather: sphere luminance %.5f ± %.5f, environment %.5f\n", mean, se, kEnv);
  INFO("sphere luminance " << mean << " ± " << se << " vs environment " << kEnv);
  CHECK(mean <= kEnv + 4.0 * se);
  CHECK(mean > 0.2 * kEnv);  // it does reflect
}

TEST_CASE("pathtracer furnace: a smooth dielectric sphere (ior 1.5) vanishes too", "[pathtracer]") {
  // Fresnel reflection + refraction with the 1/η² radiance scaling conserve radiance along every
  // path, so a closed dielectric body in a constant environment is invisible; paths trapped by
  // total internal reflection in the faceted sphere longer than max_depth are the only loss.
  SceneMaterial glass;
  glass.name = "glass";
  glass.kind = SceneMaterial::Kind::dielectric;
  glass.ior = 1.5;
  pathtracer::Settings settings;
  settings.samples_per_pixel = 32;
  settings.max_depth = 32;
  const RenderResult r = pathtracer::PathTracer(settings).render(furnace(glass), {});
  const auto [mean, se] = sphere_luminance(r);
  std::printf("furnace dielectric: sphere luminance %.5f ± %.5f, environment %.5f\n", mean, se, kEnv);
  CHECK(std::abs(mean - kEnv) <= 4.0 * se + 0.005 * kEnv);
}
