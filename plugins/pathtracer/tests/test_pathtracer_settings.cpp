// The path tracer owns its settings (issue 22): one parameter table reads, checks and documents
// the `renderer:` keys; the plug-in declares exactly that table; the ladder's reference material
// (reference/) is the tests' synthetic material bit for bit.
#include <catch2/catch.hpp>

#include <cstring>

#include "pathtracer.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "render_fixtures.hpp"
#include "settings.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

pathtracer::Settings read(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "scene.yaml");
  const pathtracer::Settings s = pathtracer::settings_table().read(doc.root());
  doc.root().finish();
  return s;
}

}  // namespace

TEST_CASE("pathtracer settings: every key is read from the renderer section", "[pathtracer][settings]") {
  const pathtracer::Settings d = read("{}");
  const pathtracer::Settings fresh;
  CHECK(d.samples_per_pixel == fresh.samples_per_pixel);
  CHECK(d.seed == fresh.seed);
  CHECK(d.max_depth == fresh.max_depth);
  CHECK(d.lod == fresh.lod);
  CHECK(d.lod_barbules == fresh.lod_barbules);
  CHECK(d.lambda_min_nm == fresh.lambda_min_nm);
  CHECK(d.lambda_max_nm == fresh.lambda_max_nm);
  CHECK(d.spectral_bins == fresh.spectral_bins);
  CHECK(d.tile_size == fresh.tile_size);
  CHECK(d.threads == fresh.threads);

  const pathtracer::Settings s = read(
      "{spp: 3, seed: 42, max_depth: 5, lod: instance, lod_barbules: 4.5, lambda_nm: [380, 720], spectral_bins: 7, "
      "tile_size: 8, threads: 2}");
  CHECK(s.samples_per_pixel == 3);
  CHECK(s.seed == 42);
  CHECK(s.max_depth == 5);
  CHECK(s.lod == pathtracer::LevelOfDetail::instance);
  CHECK(s.lod_barbules == 4.5);
  CHECK(s.lambda_min_nm == 380);
  CHECK(s.lambda_max_nm == 720);
  CHECK(s.spectral_bins == 7);
  CHECK(s.tile_size == 8);
  CHECK(s.threads == 2);
  CHECK(pathtracer::describe(s) == "3 spp, lod instance, seed 42");
  // Every declared key was given above: the table and the test agree on the names.
  CHECK(pathtracer::settings_table().names().size() == 9);
}

TEST_CASE("pathtracer settings: bad values name the key and the nearest word", "[pathtracer][settings]") {
  CHECK_THROWS_WITH(read("{spp: 0}"), Catch::Contains("spp"));
  CHECK_THROWS_WITH(read("{lod: instances}"), Catch::Contains("lod") && Catch::Contains("instance"));
  CHECK_THROWS_WITH(read("{lambda_nm: [500, 500]}"), Catch::Contains("lambda_nm") && Catch::Contains("lo < hi"));
  CHECK_THROWS_WITH(read("{lambda_nm: [200, 700]}"), Catch::Contains("lambda_nm"));
  CHECK_THROWS_WITH(read("{sp: 4}"), Catch::Contains("did you mean 'spp'"));
}

TEST_CASE("pathtracer plug-in: its declared parameters are its settings table", "[pathtracer][settings]") {
  const auto* renderer = registry().find("renderer", "pathtracer");
  REQUIRE(renderer != nullptr);
  const auto declared = renderer->info.params;
  const auto table = pathtracer::settings_table().specs();
  REQUIRE(declared.size() == table.size());
  for (std::size_t k = 0; k < table.size(); ++k) CHECK(declared[k].name == table[k].name);
  // Created from a section: unknown keys are refused with the nearest name.
  const ConfigDocument bad = ConfigDocument::parse("{type: pathtracer, sed: 3}", "scene.yaml");
  CHECK_THROWS_WITH(registry().create<Renderer>(bad.root(), "type", registry().context()),
                    Catch::Contains("did you mean 'seed'"));
  const auto* bench = registry().find("benchmark", "render");
  REQUIRE(bench != nullptr);
  std::vector<std::string> flags;
  for (const ParamSpec& p : bench->info.params) flags.push_back(p.name);
  CHECK(flags == std::vector<std::string>{"size", "spp", "material", "traversal_rays", "lod", "out"});
}

TEST_CASE("pathtracer reference: the ladder's synthetic feather is the tests' material bit for bit",
          "[pathtracer][settings]") {
  MaterialRecipe r;
  r.bins = 50;
  r.grid = 6;
  r.m_eff = [](int w, double ct, double) { return 0.15 + 0.15 * (1.0 - ct) + 0.001 * w; };
  r.phi_offset = [](int, double ct, double) { return deg_to_rad(6.0) * (1.0 - ct); };
  r.albedo = [](int w, double, double) {
    const double z = (w - 24.0) / 8.0;
    return 0.1 + (0.8 - 0.1) * std::exp(-z * z);
  };
  FeatherMaterial fixture = make_material(r, [](const Lobe& l, double t) { return hemisphere_lobe_integral(l, t); });
  fixture.noise = testing::ar1_pool(64, 64, 0.8, 0xfea7);
  const FeatherMaterial reference = pathtracer::reference::synthetic_feather_material(0.8, 6);
  CHECK(reference.label == fixture.label);
  CHECK(reference.sigma == fixture.sigma);
  CHECK(reference.l0 == fixture.l0);
  CHECK(reference.grid == fixture.grid);
  CHECK(reference.lambda_nm == fixture.lambda_nm);
  REQUIRE(reference.nodes.size() == fixture.nodes.size());
  CHECK(std::memcmp(reference.nodes.data(), fixture.nodes.data(), fixture.nodes.size() * sizeof(MaterialNode)) == 0);
  CHECK(reference.noise.samples == fixture.noise.samples);
  CHECK(reference.noise.lag1 == fixture.noise.lag1);
  CHECK(reference.noise.functions == fixture.noise.functions);
}
