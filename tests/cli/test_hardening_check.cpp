// Issue 23, "check equals the run": every case where `plumage check` said ok and the run then
// refused or died, every error of every file reported, `check --resolved`, a structure-only
// variant's spectrum, declared wavelength and scene ranges, and CLI numbers. Each case writes its
// own files into a scratch folder and asserts the exit code, the message (file:line:col or the
// flag, and the field), that check and the run refuse with the same message, and that nothing
// was written.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;

namespace {

const std::string kSuite = "plumage-test-hardening-check";

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path file = plumage::cli_test::scratch_dir(kSuite) / name;
  std::ofstream(file) << text;
  return file;
}

// A path in the scratch folder that does not exist (removed first).
fs::path absent(const std::string& name) { return plumage::cli_test::fresh_scratch_path(kSuite, name); }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// A small two-film species (as configs/species/examples/twofilm.yaml); variant b changes only the
// cortex of its structure.
const std::string kSpecies = R"(species: hcheck
variant: a
variants:
  a: {}
  b:
    structure: {cortex_nm: 300}
nominal_stack:
  layers:
    - {material: keratin, thickness_nm: 150}
    - {material: melanin, thickness_nm: 40}
    - {material: keratin, thickness_nm: 140}
    - {material: melanin, thickness_nm: 40}
    - {material: keratin, thickness_nm: 2630}
  substrate: air
reflection: {model: multilayer}
structure:
  generator: layered_barbule
  model: films
  cortex_nm: 150
  films:
    - {material: melanin, thickness_nm: 40}
    - {material: melanin, thickness_nm: 40}
  film_spacing_nm: 140
  outline:
    shape: pillow
    width_um: 30
    thickness_um: 3.0
    spacing_nm: 30
    cap_ratio: [2, 3]
    roughness: {correlation_um: 1.0, range_um: [-0.15, 0.15]}
    bottom:
      mode: mirror
      roughness: {correlation_um: 1.0, range_um: [-0.15, 0.15]}
)";

const std::string kScene = R"(scene: hcheck
render: {resolution: [8, 8]}
camera: {position_mm: [0, 0, 50], look_at_mm: [0, 0, 0], up: [0, 1, 0], fov_deg: 20}
lights: [{type: distant, toward_light: [0, 0, 1], irradiance: 2}]
renderer: {type: pathtracer, spp: 1, seed: 5}
materials: {paper: {type: diffuse, albedo: 0.5}}
objects: [{type: plane, material: paper, size_mm: 200}]
)";

// The "error: ..." lines of an output.
std::vector<std::string> error_lines(const std::string& output) {
  std::vector<std::string> out;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("error: ", 0) == 0) out.push_back(line);
  return out;
}

// `check FILE` refuses with one error located in FILE (file:line:col, then `field`), and `run`
// refuses with the same line; neither writes `out`.
void check_and_run_refuse(const fs::path& file, const std::string& field, const std::string& run_args,
                          const fs::path& out) {
  const Result c = run("check " + file.string());
  INFO(c.output);
  CHECK(c.status == 2);
  const auto errors = error_lines(c.output);
  REQUIRE(errors.size() >= 2);  // the error and the summary line
  const std::string& error = errors.front();
  CHECK(std::regex_search(error, std::regex("error: " + std::regex_replace(file.string(), std::regex("[.+]"), "\\$&") +
                                            ":[0-9]+:[0-9]+: ")));
  CHECK(error.find(field) != std::string::npos);
  const Result r = run(run_args);
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find(error) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

// A command refused with exit 2, its message naming `flag`, nothing written at `out`.
void refused(const std::string& args, const std::string& flag, const fs::path& out) {
  const Result r = run(args);
  INFO(args << "\n" << r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find(flag) != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

// species,variant,theta_deg,lambda_nm,R_s,R_p,R rows of `spectra` output: R by (variant, λ) at θ = 0.
std::map<std::pair<std::string, double>, double> normal_reflectance(const std::string& csv) {
  std::map<std::pair<std::string, double>, double> out;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line.rfind("species,", 0) == 0 || line.rfind("hcheck,", 0) != 0) continue;
    std::vector<std::string> f;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    REQUIRE(f.size() == 7);
    if (std::stod(f[2]) == 0.0) out[{f[1], std::stod(f[3])}] = std::stod(f[6]);
  }
  return out;
}

}  // namespace

TEST_CASE("check: a default variant missing from variants: is refused by check and the run", "[cli][hardening]") {
  const fs::path file = write_file("default-variant.yaml", replaced(kSpecies, "variant: a\n", "variant: c\n"));
  const fs::path out = absent("default-variant-geometry");
  check_and_run_refuse(file, "variant: unknown variant 'c'",
                       "geometry " + file.string() + " --variant a --instances 1 --out " + out.string(), out);
}

TEST_CASE("check: a species without structure: is refused by check and by simulate/geometry", "[cli][hardening]") {
  std::string text = kSpecies.substr(0, kSpecies.find("structure:\n  generator"));
  text = replaced(text, "  b:\n    structure: {cortex_nm: 300}\n", "");
  const fs::path file = write_file("no-structure.yaml", text);
  const fs::path out = absent("no-structure.ffs");
  check_and_run_refuse(file, "structure: no 'structure:' section",
                       "simulate " + file.string() + " --lambda-nm 550 --out " + out.string(), out);
  const fs::path dir = absent("no-structure-geometry");
  check_and_run_refuse(file, "structure", "geometry " + file.string() + " --instances 1 --out " + dir.string(), dir);
}

TEST_CASE("check: outline sizes out of their declared ranges are refused by check and geometry", "[cli][hardening]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"    width_um: 30\n", "    width_um: 1e12\n"},
      {"    spacing_nm: 30\n", "    spacing_nm: 1e-9\n"},
      {"    thickness_um: 3.0\n", "    thickness_um: 1e20\n"}};
  int k = 0;
  for (const auto& [from, to] : cases) {
    const std::string key = to.substr(4, to.find(':') - 4);
    INFO(key);
    const fs::path file = write_file("outline-" + std::to_string(k) + ".yaml", replaced(kSpecies, from, to));
    const fs::path out = absent("outline-geometry-" + std::to_string(k));
    check_and_run_refuse(file, "structure.outline." + key + ": value",
                         "geometry " + file.string() + " --instances 1 --out " + out.string(), out);
    ++k;
  }
}

TEST_CASE("check: a crystal period out of range is refused by check and table build, no .plt or .partial", "[cli][hardening]") {
  std::ifstream in(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const fs::path file = write_file("huge-period.yaml", replaced(text.str(), "a_x_nm: 190", "a_x_nm: 1e9"));
  const fs::path out = plumage::cli_test::scratch_dir(kSuite) / "huge-period.plt";
  fs::remove(out);
  fs::remove(out.string() + ".partial");
  check_and_run_refuse(file, "crystal.a_x_nm: value 1e9 is out of range",
                       "table build " + file.string() + " --fidelity preview --out " + out.string(), out);
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
}

TEST_CASE("check reports every error of every file and exits 2", "[cli][hardening]") {
  // Two variants each broken in their own way, and a second broken file.
  std::string text = replaced(kSpecies, "  b:\n    structure: {cortex_nm: 300}\n",
                              "  b:\n    structure: {cortex_nm: -5}\n  c:\n    structure: {outline: {spacing_nm: 0}}\n");
  const fs::path first = write_file("many-errors.yaml", text);
  const fs::path second = write_file("second.yaml", replaced(kScene, "fov_deg: 20", "fov_deg: 500"));
  const fs::path good = write_file("good.yaml", kSpecies);
  const Result r = run("check " + first.string() + " " + good.string() + " " + second.string());
  INFO(r.output);
  CHECK(r.status == 2);
  const auto errors = error_lines(r.output);
  REQUIRE(errors.size() == 4);  // three errors and the summary
  CHECK(errors[0].find(first.string() + ":6:") != std::string::npos);
  CHECK(errors[0].find("cortex_nm") != std::string::npos);
  CHECK(errors[1].find(first.string() + ":8:") != std::string::npos);
  CHECK(errors[1].find("spacing_nm") != std::string::npos);
  CHECK(errors[2].find(second.string() + ":3:") != std::string::npos);
  CHECK(errors[2].find("camera.fov_deg") != std::string::npos);
  CHECK(errors[3].find("3 error(s) in 2 of 3 file(s)") != std::string::npos);
  CHECK(r.output.find(good.string() + ": ok") != std::string::npos);
}

TEST_CASE("check --resolved prints each merged variant with its defaults", "[cli][hardening]") {
  const fs::path file = write_file("resolved.yaml", replaced(kSpecies, "    spacing_nm: 30\n", ""));
  const Result r = run("check --resolved " + file.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("--- # " + file.string() + ", variant a") != std::string::npos);
  const auto b = r.output.find("--- # " + file.string() + ", variant b");
  REQUIRE(b != std::string::npos);
  // Variant b's own cortex, merged; the spacing left out is there at its default, marked.
  CHECK(r.output.find("cortex_nm: 300", b) != std::string::npos);
  CHECK(r.output.find("cortex_nm: 150") < b);
  CHECK(r.output.find("spacing_nm: 30  # default; nm") != std::string::npos);
  CHECK(r.output.find("variant: b", b) != std::string::npos);
  CHECK(r.output.find("variants:") == std::string::npos);
  // The output is a valid YAML stream that `check` accepts back as a species of one variant each.
  CHECK(r.output.find("width_um: 30  # um") != std::string::npos);
}

TEST_CASE("spectra: a variant that changes only its structure gets its own spectrum", "[cli][hardening]") {
  const fs::path file = write_file("structure-only.yaml", kSpecies);
  const Result a = run("spectra " + file.string() + " --variant a --lambda-nm 400:700:10 --theta-deg 0");
  const Result b = run("spectra " + file.string() + " --variant b --lambda-nm 400:700:10 --theta-deg 0");
  INFO(a.output << "\n" << b.output);
  REQUIRE(a.status == 0);
  REQUIRE(b.status == 0);
  const auto ra = normal_reflectance(a.output), rb = normal_reflectance(b.output);
  REQUIRE(ra.size() == 31);
  REQUIRE(rb.size() == 31);
  // Doubling the cortex (150 -> 300 nm keratin over the melanin films) moves the thin-film
  // fringes: the spectra differ by far more than rounding across the visible.
  double largest = 0;
  for (double l = 400; l <= 700; l += 10) largest = std::max(largest, std::abs(ra.at({"a", l}) - rb.at({"b", l})));
  CHECK(largest > 0.05);
  // Variant a (no structure override) still uses the file's nominal_stack: the same as multilayer.
  const Result m = run("multilayer --stack \"air | keratin 150 | melanin 40 | keratin 140 | melanin 40 | keratin 2630 | air\""
                       " --lambda-nm 550 --theta-deg 0 --format csv");
  INFO(m.output);
  REQUIRE(m.status == 0);
  const auto last = m.output.find_last_of(',');
  REQUIRE(last != std::string::npos);
  const auto prev = m.output.find_last_of(',', last - 1);
  const double rs = std::stod(m.output.substr(prev + 1, last - prev - 1)), rp = std::stod(m.output.substr(last + 1));
  CHECK(ra.at({"a", 550.0}) == Approx(0.5 * (rs + rp)).epsilon(1e-4));
}

TEST_CASE("wavelengths outside [100, 5000] nm are refused by every command, naming the flag or field", "[cli][hardening]") {
  const fs::path species = write_file("wl-species.yaml", kSpecies);
  const fs::path out = absent("wl-out");
  for (const std::string l : {"5", "1e9"}) {
    refused("simulate " + species.string() + " --lambda-nm " + l + " --out " + out.string(), "--lambda-nm", out);
    refused("spectra " + species.string() + " --lambda-nm " + l + " --csv " + out.string(), "--lambda-nm", out);
    refused("multilayer --stack \"air | keratin 300 | air\" --lambda-nm " + l, "--lambda-nm", out);
    refused("characterize " + species.string() + " --fidelity preview --lambda-nm " + l + " --out " + out.string(),
            "lambda_nm", out);
    refused("table build " + std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml --lambda-min " + l +
                " --out " + out.string(),
            "--lambda-min", out);
  }
  // In configs: a species' simulation grid, a comparison, a scene's tabulated spectrum.
  const fs::path sim = write_file("wl-simulation.yaml",
                                  kSpecies + "simulation: {wavelengths_nm: {from: 5, to: 700, step: 5}}\n");
  check_and_run_refuse(sim, "simulation.wavelengths_nm.from: value 5 is out of range",
                       "simulate " + sim.string() + " --out " + out.string(), out);
  std::ifstream in(std::string(PLUMAGE_SOURCE_DIR) + "/tests/cli/data/compare-tiny.yaml");
  std::stringstream cmp;
  cmp << in.rdbuf();
  const fs::path comparison = write_file(
      "wl-compare.yaml", replaced(replaced(cmp.str(), "wavelengths_nm: [450, 550, 650]", "wavelengths_nm: [450, 1e9]"),
                                  "species: ../../../configs", "species: " + std::string(PLUMAGE_SOURCE_DIR) + "/configs"));
  check_and_run_refuse(comparison, "wavelengths_nm: value 1e9 is out of range",
                       "compare " + comparison.string() + " --out " + out.string(), out);
  const fs::path scene = write_file(
      "wl-scene.yaml", replaced(kScene, "albedo: 0.5", "albedo: {lambda_nm: [5, 700], value: [0.5, 0.5]}"));
  check_and_run_refuse(scene, "lambda_nm: value 5 is out of range", "render " + scene.string() + " --out " + out.string(),
                       out);
}

TEST_CASE("scene coordinates and sizes out of range are refused before Embree", "[cli][hardening]") {
  const fs::path out = absent("scene-out");
  const fs::path camera = write_file("far-camera.yaml", replaced(kScene, "position_mm: [0, 0, 50]", "position_mm: [1e20, 0, 50]"));
  check_and_run_refuse(camera, "camera.position_mm: value 1e20 is out of range",
                       "render " + camera.string() + " --out " + out.string(), out);
  const Result c = run("render --check " + camera.string());
  CHECK(c.status == 2);
  const fs::path plane = write_file("huge-plane.yaml", replaced(kScene, "size_mm: 200", "size_mm: 1e300"));
  check_and_run_refuse(plane, "size_mm: value 1e300 is out of range", "render " + plane.string() + " --out " + out.string(),
                       out);
  const Result p = run("render --check " + plane.string());
  CHECK(p.status == 2);
}

TEST_CASE("CLI counts and sigma: 0, negative or nan are refused by every command that has them", "[cli][hardening]") {
  const fs::path species = write_file("cli-species.yaml", kSpecies);
  const fs::path out = absent("cli-out");
  const std::string characterize = "characterize " + species.string() + " --fidelity preview --out " + out.string();
  for (const std::string v : {"nan", "-1", "0"}) refused(characterize + " --sigma=" + v, "sigma", out);
  // The characterize flags are rows of its overrides table: the message names the row.
  for (const std::string flag : {"grid", "instances", "noise_functions"}) {
    std::string dashed = flag;
    std::replace(dashed.begin(), dashed.end(), '_', '-');
    for (const std::string v : {"0", "-1"}) refused(characterize + " --" + dashed + "=" + v, flag + ": value", out);
  }
  for (const std::string v : {"0", "-1"}) {
    refused("simulate " + species.string() + " --lambda-nm 550 --instances=" + v + " --out " + out.string(),
            "--instances", out);
    refused("geometry " + species.string() + " --instances=" + v + " --out " + out.string(), "--instances", out);
    refused("table build " + std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml --n-lambda=" + v +
                " --out " + out.string(),
            "--n-lambda", out);
  }
}
