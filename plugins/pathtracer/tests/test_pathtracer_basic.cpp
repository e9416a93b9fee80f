// The plug-in loads and renders a small scene with every material and light kind; EXR output
// round-trips; scene errors name the mesh.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "pathtracer.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/exr.hpp"
#include "plumage/renderer.hpp"
#include "render_fixtures.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

Scene mixed_scene() {
  Scene s;
  s.name = "mixed";
  s.materials = {diffuse(0.5), feather(synthetic_feather(0.8, 6))};
  SceneMaterial glass;
  glass.name = "glass";
  glass.kind = SceneMaterial::Kind::dielectric;
  glass.ior = 1.5;
  s.materials.push_back(glass);
  SceneMesh floor = square(40.0, 0);
  for (auto& p : floor.positions) p.z = -2.0f;
  s.meshes.push_back(floor);
  s.meshes.push_back(square(10.0, 1, 100));
  SceneMesh ball = icosphere(3.0, 2, 2);
  for (auto& p : ball.positions) p.x += 8.0f;
  s.meshes.push_back(ball);
  s.distant_lights.push_back({v3f(0.3, 0.2, 0.93), 1.0});
  s.point_lights.push_back({v3f(-5, 5, 10), 50.0});
  s.area_lights.push_back({v3f(-5, -5, 20), v3f(10, 0, 0), v3f(0, 10, 0), 0.5, true});
  s.environment.radiance = 0.05;
  s.camera = far_camera({0.0, -0.5, 0.866}, 60.0, 0.6, 32);
  return s;
}

}  // namespace

TEST_CASE("pathtracer: the plug-in renders a scene with every material and light kind", "[pathtracer]") {
  // The settings come from the plug-in's own table (a scene's `renderer:` section).
  const ConfigDocument section = ConfigDocument::parse("{type: pathtracer, spp: 4, spectral_bins: 5}", "scene");
  auto renderer = registry().create<Renderer>(section.root(), "type", registry().context());
  CHECK(renderer->describe() == "4 spp, lod auto, seed 1");
  std::size_t calls = 0, last = 0;
  const RenderResult r = renderer->render(mixed_scene(), [&](std::size_t done, std::size_t total, std::string_view) {
    ++calls;
    CHECK(done > last);
    CHECK(done <= total);
    last = done;
  });
  REQUIRE(r.rgb.width() == 32);
  REQUIRE(r.rgb.height() == 32);
  CHECK(calls == 4);  // 2 × 2 tiles of 16
  double sum = 0.0;
  bool finite = true;
  for (const RgbF& p : r.rgb.pixels()) {
    finite = finite && std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b);
    sum += p.r + p.g + p.b;
  }
  CHECK(finite);
  CHECK(sum > 0.0);
  CHECK(r.spectral.values.size() == 32u * 32u * 5u);
  CHECK(r.spectral.bins == 5);
  CHECK(r.spectral.lambda_min_nm == 400.0);
  CHECK(r.spectral.lambda_max_nm == 700.0);
  CHECK(r.stats.camera_paths == 32u * 32u * 4u);
  CHECK(r.stats.rays >= r.stats.camera_paths);
  CHECK(r.stats.mean_lod_fraction >= 0.0);
  CHECK(r.stats.mean_lod_fraction <= 1.0);

  const auto path = std::filesystem::temp_directory_path() / "plumage-test-pathtracer" / "mixed.exr";
  const SpectralChannels& spectral = r.spectral;
  write_exr(r.rgb, path, &spectral);
  const LinearImage back = read_exr_rgb(path);
  REQUIRE(back.width() == 32);
  bool same = true;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      same = same && back.at(x, y).r == r.rgb.at(x, y).r && back.at(x, y).g == r.rgb.at(x, y).g &&
             back.at(x, y).b == r.rgb.at(x, y).b;
  CHECK(same);
  CHECK(spectral_channel_name(spectral, 0) == "S00.400-460nm");
  std::filesystem::remove_all(path.parent_path());
}

TEST_CASE("pathtracer: inconsistent scenes are refused with the mesh named", "[pathtracer]") {
  Scene s = mixed_scene();
  s.meshes[1].frame_axis.pop_back();
  pathtracer::Settings settings;
  CHECK_THROWS_WITH(pathtracer::PathTracer(settings).render(s, {}),
                    Catch::Contains("mesh 'square'") && Catch::Contains("frame_axis"));
  s = mixed_scene();
  s.meshes[0].material = 7;
  CHECK_THROWS_WITH(pathtracer::PathTracer(settings).render(s, {}), Catch::Contains("material index 7"));
}

TEST_CASE("exr: empty images and wrong spectral sizes are refused, naming the path", "[pathtracer]") {
  const auto path = std::filesystem::temp_directory_path() / "plumage-test-exr" / "bad.exr";
  CHECK_THROWS_WITH(write_exr(LinearImage(), path), Catch::Contains("bad.exr"));
  SpectralChannels s{3, 400, 700, std::vector<float>(5)};
  CHECK_THROWS_WITH(write_exr(LinearImage(2, 2), path, &s), Catch::Contains("bad.exr"));
  CHECK_FALSE(std::filesystem::exists(path));
}
