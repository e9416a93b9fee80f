// Issue 23, "a warning that always fires says nothing", end to end: `characterize` prints where
// and how much per code and stores it (with the cells) in the material; `render` passes a
// per-direction warning on only when its paths reach those directions with weight
// (render.warning_share), says the share either way, with the same counts on 1 and 2 threads;
// `simulate` names the instances (index and seed) that raised a per-instance warning.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

#include "bsdf_fixtures.hpp"
#include "plumage/exr.hpp"
#include "plumage/feather_material.hpp"

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using namespace plumage;
using namespace plumage::testing;

namespace {

const std::string kSuite = "plumage-test-hardening-warnings";
const std::string kSource = PLUMAGE_SOURCE_DIR;

std::string bytes(const fs::path& file) { return plumage::cli_test::file_bytes(file); }

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path file = plumage::cli_test::scratch_dir(kSuite) / name;
  std::ofstream(file) << text;
  return file;
}

// A synthetic material (as tests/cli/test_render_cli.cpp) characterised, as it says, with
// approx.grazing in the grazing row (cos θ_i = 1/4: θ_i ≥ 75.5°) at every azimuth and in the
// grazing column (cos φ_i = 1/4) of every row.
fs::path grazing_material() {
  MaterialRecipe r;
  r.bins = 10;
  r.grid = 4;
  r.l0 = 0.2;
  r.m_eff = [](int, double, double) { return 0.2; };
  r.albedo = [](int w, double, double) { const double d = (400.0 + 30.0 * w - 520.0) / 60.0; return 0.1 + 0.6 * std::exp(-d * d); };
  FeatherMaterial m = make_material(r, [](const Lobe& l, double t) { return lobe_integral(l, t, 12, 3); });
  m.label = "synthetic/grazing";
  m.fidelity = "test";
  m.bin_width_nm = 30.0;
  for (int w = 0; w < r.bins; ++w) m.lambda_nm[static_cast<std::size_t>(w)] = 400.0 + 30.0 * w;
  m.noise = ar1_pool(16, 128, 0.9, 42);
  m.warnings =
      "approx.grazing: raised in 70 of 160 work units (43.8 %), in 40 of 40 work groups; directions theta_i >= 75.5 "
      "deg at every phi_i; |phi_i| >= 75.5 deg at theta_i 0.0-60.0 deg; 3.0 % of the characterised reflected energy\n"
      "approx.grazing cells: 1:1-4 2:1-1 3:1-1 4:1-1\n";
  const fs::path file = plumage::cli_test::scratch_dir(kSuite) / "grazing.plm";
  write_feather_material(file, m);
  return file;
}

// The feather lies in the xy plane (normal +z). Normal: camera and light straight above it.
// Grazing: camera and light 3° above the plane, across the vane.
fs::path scene(const std::string& name, bool grazing) {
  const std::string camera = grazing ? "camera: {position_mm: [40, 4, 2.1], look_at_mm: [0, 4, 0], up: [0, 0, 1], fov_deg: 20}\n"
                                     : "camera: {position_mm: [0, 4, 40], look_at_mm: [0, 4, 0], up: [0, 1, 0], fov_deg: 20}\n";
  const std::string light = grazing ? "lights: [{type: distant, toward_light: [1, 0, 0.05], irradiance: 3}]\n"
                                    : "lights: [{type: distant, toward_light: [0, 0, 1], irradiance: 3}]\n";
  return write_file(name + ".yaml", "scene: " + name + "\n"
                                    "renderer: {spp: 2, seed: 5}\n"
                                    "render: {resolution: [24, 24]}\n" + camera + light +
                                    "materials: {g: {type: feather, file: " + grazing_material().string() + "}}\n"
                                    "objects: [{type: feather, material: g, detail: barb_level, "
                                    "shape: {length_mm: 8, vane_width_mm: 4}}]\n");
}

// The render's line about the material's approx.grazing, e.g. "  material 'g': 37.12 % of …".
std::string share_line(const std::string& output) {
  std::smatch m;
  const std::regex line("  material 'g': [^\n]*approx.grazing[^\n]*");
  return std::regex_search(output, m, line) ? m.str() : "";
}

double share_percent(const std::string& line) {
  const auto colon = line.find("': ");
  return colon == std::string::npos ? -1.0 : std::stod(line.substr(colon + 3));
}

}  // namespace

TEST_CASE("warnings: characterize says where and how much per code and stores it", "[cli][warnings]") {
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "rd") / "rd.plm";
  fs::create_directories(out.parent_path());
  const Result r = run("characterize " + kSource + "/configs/species/rockdove.yaml --fidelity preview --grid 3 "
                       "--lambda-nm 400,500 --instances 3 --noise-functions 8 --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  // The first raise as it happened, then one line per code: units of 2 x 3 x 3, groups of 2 x 3,
  // the directions, the energy share and the worst measure.
  CHECK(r.output.find("[approx.grazing]") != std::string::npos);
  CHECK(r.output.find("the material's warnings (stored in it):\n  approx.grazing: raised in ") != std::string::npos);
  CHECK(std::regex_search(r.output, std::regex("approx.grazing: raised in [0-9]+ of 18 work units \\([0-9.]+ %\\), in "
                                               "[0-9]+ of 6 work groups; directions [^;]*(theta_i|phi_i)[^;]*deg")));
  CHECK(r.output.find("of the characterised reflected energy") != std::string::npos);
  CHECK(r.output.find("worst horizon spill ratio") != std::string::npos);
  CHECK(r.output.find(" cells: ") == std::string::npos);  // the cells are for the render, not people
  const std::string plm = bytes(out);
  CHECK(plm.find("approx.grazing: raised in ") != std::string::npos);
  CHECK(plm.find("approx.grazing cells: ") != std::string::npos);
}

TEST_CASE("warnings: a render passes approx.grazing on only when its paths reach it", "[cli][render][warnings]") {
  const fs::path normal_out = plumage::cli_test::fresh_scratch_path(kSuite, "normal");
  Result r = run("render " + scene("normal", false).string() + " --threads 1 --out " + normal_out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  const std::string normal = share_line(r.output);
  REQUIRE_FALSE(normal.empty());
  CHECK(share_percent(normal) < 1.0);
  CHECK(normal.find("below render.warning_share = 1") != std::string::npos);
  CHECK(r.output.find("warning: ") == std::string::npos);
  CHECK(read_exr_string_attributes(normal_out / "normal.exr").count("plumage:warnings") == 0);

  const fs::path grazing_out = plumage::cli_test::fresh_scratch_path(kSuite, "grazing");
  r = run("render " + scene("grazing", true).string() + " --threads 1 --out " + grazing_out.string());
  REQUIRE(r.status == 0);
  const std::string grazing = share_line(r.output);
  REQUIRE_FALSE(grazing.empty());
  CHECK(share_percent(grazing) > 10.0);
  CHECK(grazing.find("at or above render.warning_share = 1") != std::string::npos);
  CHECK(grazing.find("theta_i >= 75.5 deg at every phi_i") != std::string::npos);
  CHECK(r.output.find("[material.warnings]") != std::string::npos);
  const auto attributes = read_exr_string_attributes(grazing_out / "grazing.exr");
  REQUIRE(attributes.count("plumage:warnings") == 1);
  CHECK(attributes.at("plumage:warnings").find("material 'g': ") != std::string::npos);
  CHECK(attributes.at("plumage:warnings").find("raised approx.grazing") != std::string::npos);

  // The counts do not depend on the thread count (per-tile tallies summed in tile order).
  const fs::path two_out = plumage::cli_test::fresh_scratch_path(kSuite, "grazing2");
  const Result two = run("render " + scene("grazing", true).string() + " --threads 2 --out " + two_out.string());
  REQUIRE(two.status == 0);
  CHECK(share_line(two.output) == grazing);
  CHECK(bytes(two_out / "grazing.exr") == bytes(grazing_out / "grazing.exr"));

  // The threshold is the scene's: at 1 (only if every evaluation is there) the same render is silent.
  std::string text = bytes(scene("grazing", true));
  text.replace(text.find("resolution: [24, 24]"), 20, "resolution: [24, 24], warning_share: 1");
  const fs::path strict = write_file("strict.yaml", text);
  const fs::path strict_out = plumage::cli_test::fresh_scratch_path(kSuite, "strict");
  r = run("render " + strict.string() + " --threads 1 --out " + strict_out.string());
  REQUIRE(r.status == 0);
  CHECK(r.output.find("[material.warnings]") == std::string::npos);
  CHECK(share_line(r.output).find("below render.warning_share = 100") != std::string::npos);
}

TEST_CASE("warnings: simulate names the instances of approx.rough_surface", "[cli][warnings]") {
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "rough") / "rough.ffs";
  fs::create_directories(out.parent_path());
  const Result r = run("simulate " + kSource + "/configs/validation/rough-film.yaml --lambda-nm 550 --theta-deg 0 "
                       "--phi-deg 0 --instances 3 --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  // The solver's message names the instance; simulate lists every instance with its seed.
  CHECK(std::regex_search(r.output, std::regex("approximate solver: instance [0-2] \\(seed 0x[0-9a-f]{16}\\) of [^:]+: "
                                               "top-surface rms slope[^\n]*\\[approx.rough_surface\\]")));
  CHECK(std::regex_search(r.output, std::regex("approx.rough_surface raised by [1-3] of 3 instances of [^:]*rough-film.yaml: "
                                               "instance 0 \\(seed 0x[0-9a-f]{16}, rms slope 0\\.[0-9]+ rad\\)")));
  CHECK(r.output.find("[simulate.instances]") != std::string::npos);
  CHECK(bytes(out).find("simulate.instances: approx.rough_surface raised by ") != std::string::npos);
}
