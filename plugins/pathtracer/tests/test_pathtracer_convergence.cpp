// Acceptance 4 and 5 (issue 8): image noise falls as 1/√spp; the same seed gives bit-identical
// images on 1 and 2 threads. Also: the level-of-detail switch follows the footprint.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "pathtracer.hpp"
#include "render_fixtures.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

double rms(const LinearImage& a, const LinearImage& ref) {
  double s = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) {
    const RgbF p = a.pixels()[i], q = ref.pixels()[i];
    s += (p.r - q.r) * (p.r - q.r) + (p.g - q.g) * (p.g - q.g) + (p.b - q.b) * (p.b - q.b);
  }
  return std::sqrt(s / (3.0 * a.pixels().size()));
}

}  // namespace

TEST_CASE("pathtracer convergence: RMS error against a 1024-spp reference falls as spp^-1/2", "[pathtracer]") {
  const Scene scene = noisy_feather_scene(10);
  pathtracer::Settings settings;
  settings.samples_per_pixel = 1024;
  settings.seed = 1000;  // the reference's samples are independent of the levels'
  const LinearImage ref = pathtracer::PathTracer(settings).render(scene, {}).rgb;
  const int levels[3] = {4, 16, 64};
  double e[3];
  for (int i = 0; i < 3; ++i) {
    // The RMS over 100 pixels × 3 channels of one image has ~6 % relative scatter; averaging 4
    // independent images per level brings it to ~3 % (slope error ≈ ±0.02 over 16× in spp).
    double s2 = 0;
    for (int rep = 0; rep < 4; ++rep) {
      settings.samples_per_pixel = levels[i];
      settings.seed = 10 * (i + 1) + rep;
      const double r = rms(pathtracer::PathTracer(settings).render(scene, {}).rgb, ref);
      s2 += r * r;
    }
    e[i] = std::sqrt(s2 / 4);
  }
  // Least-squares slope of log e against log spp.
  double mx = 0, my = 0;
  for (int i = 0; i < 3; ++i) { mx += std::log(levels[i]) / 3; my += std::log(e[i]) / 3; }
  double sxy = 0, sxx = 0;
  for (int i = 0; i < 3; ++i) {
    sxy += (std::log(levels[i]) - mx) * (std::log(e[i]) - my);
    sxx += (std::log(levels[i]) - mx) * (std::log(levels[i]) - mx);
  }
  const double slope = sxy / sxx;
  std::printf("convergence: rms %.5f %.5f %.5f at 4/16/64 spp, slope %.3f\n", e[0], e[1], e[2], slope);
  INFO("rms " << e[0] << " " << e[1] << " " << e[2] << " slope " << slope);
  CHECK(slope >= -0.6);
  CHECK(slope <= -0.4);
}

TEST_CASE("pathtracer determinism: the same seed gives bit-identical images on 1 and 2 threads", "[pathtracer]") {
  const Scene scene = noisy_feather_scene(40);
  pathtracer::Settings settings;
  settings.samples_per_pixel = 4;
  settings.tile_size = 8;
  settings.spectral_bins = 6;
  settings.threads = 1;
  const RenderResult one = pathtracer::PathTracer(settings).render(scene, {});
  settings.threads = 2;
  const RenderResult two = pathtracer::PathTracer(settings).render(scene, {});
  REQUIRE(one.rgb.pixels().size() == two.rgb.pixels().size());
  CHECK(std::memcmp(one.rgb.pixels().data(), two.rgb.pixels().data(), one.rgb.pixels().size_bytes()) == 0);
  CHECK(one.spectral.bins == 6);
  CHECK(one.spectral.values == two.spectral.values);
  CHECK(one.stats.rays == two.stats.rays);
  settings.seed = 2;
  const RenderResult other = pathtracer::PathTracer(settings).render(scene, {});
  CHECK(std::memcmp(one.rgb.pixels().data(), other.rgb.pixels().data(), one.rgb.pixels().size_bytes()) != 0);
}

TEST_CASE("pathtracer level of detail: mean BRDF where the footprint covers the barbules", "[pathtracer]") {
  Scene s;
  s.name = "lod";
  s.materials = {feather(synthetic_feather(0.8, 6))};
  s.meshes.push_back(square(10.0, 0));
  s.distant_lights.push_back({v3f(0, 0, 1), 1.0});
  s.camera = far_camera({0.0, 0.0, 1.0}, 100.0, 0.05, 16);  // pixel footprint ≈ 100·0.05/16 = 0.31 mm
  pathtracer::Settings settings;
  settings.samples_per_pixel = 2;
  settings.max_depth = 1;
  s.meshes[0].barbule_spacing_mm = 0.01;  // 31 barbules per pixel: mean
  CHECK(pathtracer::PathTracer(settings).render(s, {}).stats.mean_lod_fraction == 1.0);
  s.meshes[0].barbule_spacing_mm = 1.0;  // a third of a barbule per pixel: instances
  CHECK(pathtracer::PathTracer(settings).render(s, {}).stats.mean_lod_fraction == 0.0);
  settings.lod = pathtracer::LevelOfDetail::mean;
  CHECK(pathtracer::PathTracer(settings).render(s, {}).stats.mean_lod_fraction == 1.0);
  settings.lod = pathtracer::LevelOfDetail::instance;
  s.meshes[0].barbule_spacing_mm = 0.01;
  CHECK(pathtracer::PathTracer(settings).render(s, {}).stats.mean_lod_fraction == 0.0);
}
