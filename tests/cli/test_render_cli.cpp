// `plumage render` end to end (core/cli/cmd_render.cpp) on tiny scenes that need no characterised
// material (a clean clone has no .plm): a diffuse plane against its analytic radiance, a
// barb-level feather with a synthetic material file, the same image on 1 and 2 threads, and bad
// input (exit 2, file:line:column, nothing written).
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "bsdf_fixtures.hpp"
#include "plumage/config_document.hpp"
#include "plumage/exr.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/image.hpp"
#include "plumage/material_store.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using namespace plumage;
using namespace plumage::testing;

namespace {

const std::string kSuite = "plumage-test-render-cli";

fs::path write_scene(const std::string& name, const std::string& text) {
  const fs::path file = plumage::cli_test::scratch_dir(kSuite) / name;
  std::ofstream(file) << text;
  return file;
}

// A green-reflecting synthetic material (as tests/cli/test_brdf_cli.cpp), optionally labelled as
// a species material (label, material key, fidelity) and written to `file`.
fs::path synthetic_material(const std::string& label = "synthetic/green", const std::string& key = "",
                            const std::string& fidelity = "test", fs::path file = {}) {
  MaterialRecipe r;
  r.bins = 10;
  r.grid = 4;
  r.l0 = 0.2;
  r.m_eff = [](int, double, double) { return 0.2; };
  r.albedo = [](int w, double, double) { const double d = (400.0 + 30.0 * w - 520.0) / 60.0; return 0.1 + 0.6 * std::exp(-d * d); };
  FeatherMaterial m = make_material(r, [](const Lobe& l, double t) { return lobe_integral(l, t, 12, 3); });
  m.label = label;
  m.key = key;
  m.fidelity = fidelity;
  m.bin_width_nm = 30.0;
  for (int w = 0; w < r.bins; ++w) m.lambda_nm[static_cast<std::size_t>(w)] = 400.0 + 30.0 * w;
  m.noise = ar1_pool(16, 128, 0.9, 42);
  if (file.empty()) file = plumage::cli_test::scratch_dir(kSuite) / "green.plm";
  write_feather_material(file, m);
  return file;
}

// A white-ish plane (albedo 0.5) seen from straight above, lit by a distant light along the normal.
const std::string kPlane =
    "scene: plane\n"
    "render: {resolution: [24, 16]}\n"
    "camera: {position_mm: [0, 0, 50], look_at_mm: [0, 0, 0], up: [0, 1, 0], fov_deg: 20}\n"
    "lights: [{type: distant, toward_light: [0, 0, 1], irradiance: 2}]\n"
    "renderer: {type: pathtracer, spp: 16, seed: 5}\n"
    "materials: {paper: {type: diffuse, albedo: 0.5}}\n"
    "objects: [{type: plane, material: paper, size_mm: 200}]\n";

}  // namespace

TEST_CASE("render: a diffuse plane has radiance albedo * irradiance / pi", "[cli][render]") {
  const fs::path scene = write_scene("plane.yaml", kPlane);
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "plane");
  const Result r = run("render " + scene.string() + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("wrote") != std::string::npos);
  REQUIRE(fs::exists(out / "plane.exr"));
  REQUIRE(fs::exists(out / "plane.png"));
  const LinearImage img = read_exr_rgb(out / "plane.exr");
  REQUIRE(img.width() == 24);
  REQUIRE(img.height() == 16);
  double sum[3] = {0, 0, 0};
  for (const RgbF& p : img.pixels()) sum[0] += p.r, sum[1] += p.g, sum[2] += p.b;
  const double n = static_cast<double>(img.pixels().size()), expected = 0.5 * 2.0 / M_PI;
  // D65-shaped light on a grey surface: every channel at ρE/π (white point), up to the
  // wavelength-sampling noise of 16 × 384 samples.
  for (double s : sum) CHECK(s / n == Approx(expected).epsilon(0.03));
  // No temporary files left.
  for (const auto& e : fs::directory_iterator(out)) CHECK(e.path().string().find("partial") == std::string::npos);
  // The renderer's settings as it read them; the command-line ones go through its table.
  CHECK(r.output.find("plane: 24 x 16, 16 spp, lod auto, seed 5") != std::string::npos);
  const fs::path out2 = plumage::cli_test::fresh_scratch_path(kSuite, "plane-flags");
  const Result r2 = run("render " + scene.string() + " --spp 4 --seed 7 --lod mean --width 12 --height 8 --out " + out2.string());
  INFO(r2.output);
  REQUIRE(r2.status == 0);
  CHECK(r2.output.find("plane: 12 x 8, 4 spp, lod mean, seed 7") != std::string::npos);
  CHECK(r2.output.find("(12 x 8, 4 spp, ") != std::string::npos);
  CHECK(read_exr_rgb(out2 / "plane.exr").width() == 12);
}

TEST_CASE("render: a barb-level feather with a material file; the same image on 1 and 2 threads", "[cli][render]") {
  const fs::path plm = synthetic_material();
  const std::string text =
      "scene: feather\n"
      "renderer: {spp: 2, seed: 9}\n"
      "render: {resolution: [32, 32]}\n"
      "camera: {position_mm: [0, -5, 30], look_at_mm: [0, 4, 0], up: [0, 1, 0], fov_deg: 30}\n"
      "lights: [{type: distant, toward_light: [0, 0.3, 1], irradiance: 3}, {type: environment, radiance: 0.05}]\n"
      "materials: {green: {type: feather, file: " + plm.string() + "}}\n"
      "objects: [{type: feather, material: green, detail: barb_level, shape: {length_mm: 8, vane_width_mm: 4}}]\n"
      "views: [{name: a}, {name: b, camera: {position_mm: [10, -5, 28]}}]\n";
  const fs::path scene = write_scene("feather.yaml", text);
  const fs::path one = plumage::cli_test::fresh_scratch_path(kSuite, "one"), two = plumage::cli_test::fresh_scratch_path(kSuite, "two");
  const Result r1 = run("render " + scene.string() + " --view a --threads 1 --lod instance --out " + one.string());
  INFO(r1.output);
  REQUIRE(r1.status == 0);
  const Result r2 = run("render " + scene.string() + " --view a --threads 2 --lod instance --out " + two.string());
  REQUIRE(r2.status == 0);
  CHECK(fs::exists(one / "feather-a.png"));
  CHECK_FALSE(fs::exists(one / "feather-b.png"));  // only the view asked for
  const LinearImage a = read_exr_rgb(one / "feather-a.exr"), b = read_exr_rgb(two / "feather-a.exr");
  REQUIRE(a.pixels().size() == b.pixels().size());
  bool same = true;
  double green = 0;
  for (std::size_t k = 0; k < a.pixels().size(); ++k) {
    same = same && a.pixels()[k].r == b.pixels()[k].r && a.pixels()[k].g == b.pixels()[k].g && a.pixels()[k].b == b.pixels()[k].b;
    green += a.pixels()[k].g;
  }
  CHECK(same);
  CHECK(green > 0);  // the feather reflects something
  // Without --view: every view is written.
  const fs::path all = plumage::cli_test::fresh_scratch_path(kSuite, "all");
  REQUIRE(run("render " + scene.string() + " --spp 1 --out " + all.string()).status == 0);
  CHECK(fs::exists(all / "feather-a.exr"));
  CHECK(fs::exists(all / "feather-b.exr"));
}

TEST_CASE("render: a material's warnings reach stderr and the EXR header", "[cli][render][warnings]") {
  // The same synthetic material, once as characterised with a warning (issue 9), once clean.
  const fs::path warned = plumage::cli_test::scratch_dir(kSuite) / "warned.plm";
  FeatherMaterial m = read_feather_material(synthetic_material());
  m.warnings = "fit.two_lobes: raised while computing 3 of 40 work groups, first at lambda = 400 nm, cos theta_i = 1/4\n";
  write_feather_material(warned, m);
  auto scene_with = [](const fs::path& plm, const std::string& name) {
    return write_scene(name + ".yaml",
                       "scene: " + name + "\n"
                       "renderer: {spp: 1, seed: 3}\n"
                       "render: {resolution: [8, 8]}\n"
                       "camera: {position_mm: [0, -5, 30], look_at_mm: [0, 4, 0], up: [0, 1, 0], fov_deg: 30}\n"
                       "lights: [{type: distant, toward_light: [0, 0.3, 1], irradiance: 3}]\n"
                       "materials: {green: {type: feather, file: " + plm.string() + "}}\n"
                       "objects: [{type: feather, material: green, detail: barb_level, shape: {length_mm: 8, vane_width_mm: 4}}]\n");
  };
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "warned");
  Result r = run("render " + scene_with(warned, "warned").string() + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("[material.warnings]") != std::string::npos);
  const auto attributes = read_exr_string_attributes(out / "warned.exr");
  REQUIRE(attributes.count("plumage:warnings") == 1);
  CHECK(attributes.at("plumage:warnings").find("material.warnings: ") == 0);
  CHECK(attributes.at("plumage:warnings").find("fit.two_lobes") != std::string::npos);

  const fs::path clean_out = plumage::cli_test::fresh_scratch_path(kSuite, "clean");
  r = run("render " + scene_with(synthetic_material(), "clean").string() + " --out " + clean_out.string());
  REQUIRE(r.status == 0);
  CHECK(r.output.find("warning: ") == std::string::npos);
  CHECK(read_exr_string_attributes(clean_out / "clean.exr").count("plumage:warnings") == 0);
}

TEST_CASE("render: bad input exits 2 with file:line:column and writes nothing", "[cli][render]") {
  std::string bad = kPlane;
  bad.replace(bad.find("fov_deg"), 7, "fov_dge");
  const fs::path scene = write_scene("bad.yaml", bad);
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "bad");
  Result r = run("render " + scene.string() + " --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find("bad.yaml:3:") != std::string::npos);
  CHECK(r.output.find("did you mean 'fov_deg'") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  // Unknown renderer type: named with the nearest one.
  std::string badrenderer = kPlane;
  badrenderer.replace(badrenderer.find("renderer: {"), std::string::npos, "renderer: pathtracr\n");
  badrenderer += "materials: {paper: {type: diffuse, albedo: 0.5}}\nobjects: [{type: plane, material: paper, size_mm: 200}]\n";
  const fs::path scene2 = write_scene("badrenderer.yaml", badrenderer);
  r = run("render " + scene2.string() + " --out " + out.string());
  CHECK(r.status == 2);
  CHECK(r.output.find("badrenderer.yaml:5:") != std::string::npos);
  CHECK(r.output.find("did you mean 'pathtracer'") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  // The renderer's settings are its own: a typo in its section, and a setting left in `render:`.
  std::string badkey = kPlane;
  badkey.replace(badkey.find("seed: 5"), 7, "sed: 5");
  r = run("render " + write_scene("badkey.yaml", badkey).string() + " --out " + out.string());
  CHECK(r.status == 2);
  CHECK(r.output.find("badkey.yaml:5:") != std::string::npos);
  CHECK(r.output.find("did you mean 'seed'") != std::string::npos);
  // `plumage check` creates the renderer as `render` does, so it sees the same error.
  r = run("check " + (plumage::cli_test::scratch_dir(kSuite) / "badkey.yaml").string());
  CHECK(r.status == 2);
  CHECK(r.output.find("did you mean 'seed'") != std::string::npos);
  std::string moved = kPlane;
  moved.replace(moved.find("resolution: [24, 16]"), 20, "resolution: [24, 16], spp: 4");
  r = run("render " + write_scene("moved.yaml", moved).string() + " --out " + out.string());
  CHECK(r.status == 2);
  CHECK(r.output.find("renderer: {type: pathtracer, spp") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  // A species material that is not cached, with characterisation switched off: the message
  // names the command that makes it (a clean clone has no .plm).
  const std::string species = std::string(PLUMAGE_SOURCE_DIR) + "/configs/species/starling.yaml";
  std::string text = kPlane;
  text.replace(text.find("objects:"), std::string::npos,
               "objects: [{type: plane, material: paper, size_mm: 200}, {type: feather, material: s, detail: barb_level}]\n");
  text.replace(text.find("materials: {"), 12, "materials: {s: {type: feather, species: " + species + "}, ");
  const fs::path scene3 = write_scene("uncached.yaml", text);
  const fs::path empty = plumage::cli_test::fresh_scratch_path(kSuite, "no-materials");
  r = run("render " + scene3.string() + " --no-characterize --materials " + empty.string() + " --out " + out.string());
  CHECK(r.status == 2);
  CHECK(r.output.find("plumage characterize") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("render: a species material is found in the cache by its key", "[cli][render]") {
  const fs::path species = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / "starling.yaml";
  // The key the store looks for (plumage/material_store.hpp): the variant's inputs, fidelity, settings.
  const SpeciesConfig config = load_species_config(species, registry(), "green");
  const std::string key = MaterialStore(registry(), {}).settings(config, "preview").key();
  const fs::path cache = plumage::cli_test::fresh_scratch_path(kSuite, "cache");
  fs::create_directories(cache);
  std::string text = kPlane;
  text.replace(text.find("objects:"), std::string::npos,
               "objects: [{type: feather, material: s, detail: barb_level, shape: {length_mm: 8, vane_width_mm: 4}}]\n");
  text.replace(text.find("materials: {"), 12, "materials: {s: {type: feather, species: " + species.string() + ", variant: green}, ");
  const fs::path scene = write_scene("cached.yaml", text);
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "cached");
  // A material of another key (other inputs or settings) is stale, not a hit (and characterising
  // is switched off).
  synthetic_material("starling/green", "0000000000000000", "preview", cache / "starling-green-old.plm");
  Result r = run("render " + scene.string() + " --no-characterize --spp 1 --materials " + cache.string() + " --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find("starling-green-old.plm is stale") != std::string::npos);
  CHECK(r.output.find("no cached material for starling/green (preview)") != std::string::npos);
  // The matching one, under any name starting with <species>-<variant>.
  const fs::path good = synthetic_material("starling/green", key, "preview", cache / "starling-green-mine.plm");
  r = run("render " + scene.string() + " --no-characterize --spp 1 --materials " + cache.string() + " --out " + out.string());
  CHECK(r.status == 0);
  CHECK(r.output.find("material starling/green: " + good.string()) != std::string::npos);
  CHECK(fs::exists(out / "plane.png"));
}
