// The executable end to end: exit status 2 and a file:line message for bad input, nothing
// written on failure, results that agree with closed forms.
#include <catch2/catch.hpp>

#include "cli_run.hpp"
#include "hostile_plugins.hpp"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <sys/stat.h>

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using plumage::cli_test::run_command;

namespace {

fs::path scratch() { return plumage::cli_test::scratch_dir("plumage-test-cli"); }

std::string source(const std::string& rel) { return std::string(PLUMAGE_SOURCE_DIR) + "/" + rel; }

}  // namespace

TEST_CASE("plumage plugins lists and describes the multilayer plug-in", "[cli]") {
  auto r = run("plugins");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("local_reflection") && Catch::Contains("multilayer") &&
                           Catch::Contains("libplumage_multilayer.so"));
  r = run("plugins describe multilayer");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("multilayer (local_reflection"));
  r = run("plugins describe multilayr");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("did you mean 'multilayer'?"));
  // Broken libraries on the path are reported, not fatal.
  r = run(std::string("--plugin-path ") + FIXTURE_DIR + " plugins");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("problem:") && Catch::Contains("fixture_constant"));
}

TEST_CASE("a plug-in folder of truncated and garbage files stops no command", "[cli]") {
  const auto folder = plumage::testing::make_hostile_plugin_folder(
      scratch() / "hostile-plugins", fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_multilayer.so",
      fs::path(FIXTURE_DIR) / "libplumage_fixture_good.so", fs::path(FIXTURE_DIR) / "libplumage_fixture_plainint.so");
  auto r = run("--plugin-path " + folder.dir.string() + " plugins");
  CHECK(r.status == 0);  // -1 if a signal killed it (SIGBUS, SIGSEGV before the probe)
  CHECK_THAT(r.output, Catch::Contains("fixture_constant") && Catch::Contains("libplumage_multilayer.so"));
  for (const auto& bad : folder.bad) {
    INFO(bad.name);
    CHECK_THAT(r.output, Catch::Contains("problem: " + (folder.dir / bad.name).string() + ": ") &&
                             Catch::Contains(bad.reason));
  }
  // Any other command runs as well (before the probe, every command died in the scan).
  r = run("--plugin-path " + folder.dir.string() + " check " + source("configs/species/rockdove.yaml"));
  CHECK(r.status == 0);
}

TEST_CASE("plumage check accepts the shipped species and rejects bad files with file:line", "[cli]") {
  auto r = run("check " + source("configs/species/rockdove.yaml") + " " + source("configs/species/hummingbird.yaml"));
  CHECK(r.status == 0);
  const fs::path bad = scratch() / "bad.yaml";
  std::ofstream(bad) << "species: x\nnominal_stack:\n  layers:\n    - {material: keratin, thickness_nm: -5}\n";
  r = run("check " + bad.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains(bad.string() + ":4:") && Catch::Contains("out of range"));
  r = run("check " + (scratch() / "missing.yaml").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("missing.yaml: no such file"));
}

TEST_CASE("plumage check validates scenes and the species variants their materials name", "[cli]") {
  std::string shipped;
  for (const char* scene : {"demo", "starling", "hummingbird", "mallard", "rockdove-neck"})
    shipped += " " + source(std::string("configs/scenes/") + scene + ".yaml");
  auto r = run("check" + shipped);
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("ok (scene demo") && Catch::Contains("1 species checked"));
  // A variant the species file does not have: the error names the scene's material entry.
  const fs::path bad = scratch() / "bad_scene.yaml";
  std::ofstream(bad) << "scene: bad\ncamera: {position_mm: [0, 0, 50], look_at_mm: [0, 0, 0], up: [0, 1, 0]}\n"
                        "lights: [{type: distant, toward_light: [0, 0, 1], irradiance: 1}]\n"
                        "materials:\n  f: {type: feather, species: " << source("configs/species/rockdove.yaml")
                     << ", variant: scarlet}\n"
                        "objects: [{type: feather, material: f, detail: barb_level}]\n";
  r = run("check " + bad.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains(bad.string() + ":5:") && Catch::Contains("scarlet"));
}

TEST_CASE("plumage check validates comparison configs with their solvers", "[cli]") {
  // Every shipped comparison.
  auto r = run("check " + source("configs/compare/rockdove.yaml") + " " + source("configs/compare/mallard.yaml") + " " +
               source("configs/compare/hummingbird.yaml") + " " + source("configs/compare/starling.yaml"));
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("ok (comparison mallard, 7 methods (reference fullwave_rods)"));
  CHECK_THAT(r.output, Catch::Contains("ok (comparison starling, 3 methods (reference fullwave_exact)"));
  // A solver option that is not one of the choices: file, line and the valid ones.
  const fs::path bad = scratch() / "bad_compare.yaml";
  std::ofstream(bad) << "comparison: bad\nspecies: " << source("configs/species/rockdove.yaml")
                     << "\nvariant: forest\nwavelengths_nm: [550]\nincident_deg: [[0, 0]]\nreference: fw\nmethods:\n"
                        "  - name: fw\n    solver: {type: bem, method: hmatrix, preconditioner: dense_float}\n";
  r = run("check " + bad.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains(bad.string() + ":9:") && Catch::Contains("dense_single"));
}

TEST_CASE("a failing run writes nothing", "[cli]") {
  const fs::path bad = scratch() / "bad_model.yaml";
  std::ofstream(bad) << "species: x\nnominal_stack: {layers: [{material: keratin, thickness_nm: 5}]}\n"
                        "reflection: {model: multilayr}\n";
  const fs::path csv = scratch() / "never.csv";
  fs::remove(csv);
  auto r = run("spectra " + bad.string() + " --csv " + csv.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("bad_model.yaml:3:21"));
  CHECK_FALSE(fs::exists(csv));
}

namespace {

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("--out never replaces a symlink or a FIFO, and merge never overwrites its input", "[cli][out-paths]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path("plumage-test-cli", "out-paths");
  fs::create_directories(dir);
  const fs::path real = dir / "real.md", link = dir / "link.md", fifo = dir / "pipe.md";
  std::ofstream(real) << "keep me\n";
  fs::create_symlink(real, link);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);

  auto r = run("plugins describe --markdown --out " + link.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("--out " + link.string()) && Catch::Contains("symlink (to " + real.string()));
  CHECK(fs::is_symlink(fs::symlink_status(link)));
  CHECK(fs::read_symlink(link) == real);
  CHECK(file_bytes(real) == "keep me\n");

  r = run("plugins describe --markdown --out " + fifo.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("--out " + fifo.string()) && Catch::Contains("FIFO"));
  CHECK(fs::is_fifo(fs::symlink_status(fifo)));

  // Refused before the shard is read: its bytes stay as they were, whatever they are.
  const fs::path shard = dir / "shard.plmshard";
  std::ofstream(shard, std::ios::binary) << "plumage shard bytes\n";
  const std::string before = file_bytes(shard);
  r = run("merge " + shard.string() + " --out " + shard.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("--out " + shard.string()) && Catch::Contains("is also an input (shard " + shard.string()));
  CHECK(file_bytes(shard) == before);
  // The same file under another name (a hard link) is still the input.
  fs::create_hard_link(shard, dir / "alias.plm");
  r = run("merge " + shard.string() + " --out " + (dir / "alias.plm").string());
  CHECK(r.status == 2);
  CHECK(file_bytes(shard) == before);
  r = run("merge " + shard.string() + " --out " + fifo.string());
  CHECK(r.status == 2);
  CHECK(fs::is_fifo(fs::symlink_status(fifo)));
  // Only the files made above: nothing written beside them.
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 5);
}

TEST_CASE("plumage multilayer prints the Airy reflection of a film", "[cli]") {
  auto r = run("multilayer --stack \"air | 1.5 100 | air\" --lambda-nm 600 --theta-deg 0");
  REQUIRE(r.status == 0);
  // Last line: lambda,theta,re_rs,im_rs,re_rp,im_rp,R_s,R_p.
  std::istringstream lines(r.output);
  std::string line, last;
  while (std::getline(lines, line)) if (!line.empty()) last = line;
  double v[8];
  char comma;
  std::istringstream row(last);
  for (int i = 0; i < 8; ++i) row >> v[i] >> comma;
  // Closed form: r01 = -0.2, r12 = +0.2, δ = 2π·1.5·100/600 = π/2 → r = (-0.2 - 0.2)/(1 + 0.04)... with e^{2iδ} = -1.
  const double expected_R = std::pow((-0.2 - 0.2) / (1.0 + 0.04), 2);
  CHECK(v[6] == Approx(expected_R).epsilon(1e-9));
  CHECK(v[7] == Approx(expected_R).epsilon(1e-9));
  r = run("multilayer --stack \"air | keratn 3 | air\"");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("did you mean 'keratin'?"));
  r = run("multilayer --stack \"air | keratin 3 | air\" --theta-deg 95");
  CHECK(r.status == 2);
  r = run("multilayer --stack \"air | keratin 300 | air\" --lambda-nm 500 --format json");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("\"rows\": ["));
}

TEST_CASE("plumage geometry writes instances, pictures and statistics", "[cli][geometry]") {
  const fs::path out = scratch() / "geometry";
  fs::remove_all(out);
  auto r = run("geometry " + source("configs/species/hummingbird.yaml") + " --instances 2 --out " +
               out.string() + " --stats");
  REQUIRE(r.status == 0);
  for (const char* f : {"hummingbird-pink-0.xsec", "hummingbird-pink-1.xsec", "hummingbird-pink-0.svg",
                        "hummingbird-pink-1.png"}) {
    CHECK(fs::exists(out / f));
  }
  CHECK_THAT(r.output, Catch::Contains("correlation length") && Catch::Contains("width (um)"));
  std::ifstream xsec(out / "hummingbird-pink-0.xsec");
  std::string first;
  std::getline(xsec, first);
  CHECK(first == "plumage-cross-section 1");
  // Crystal species and their variants; validation shapes.
  r = run("geometry " + source("configs/species/magpie.yaml") + " --variant teal --stats");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("regularity min"));
  r = run("geometry " + source("configs/validation/keratin-cylinder.yaml") + " --stats");
  CHECK(r.status == 0);
  // A bad config writes nothing and exits 2 with file:line.
  const fs::path bad = scratch() / "bad_structure.yaml";
  std::ofstream(bad) << "species: bad\nstructure:\n  generator: layered_barbule\n  model: films\n"
                        "  cortex_nm: -5\n";
  const fs::path none = scratch() / "geometry-none";
  fs::remove_all(none);
  r = run("geometry " + bad.string() + " --out " + none.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("bad_structure.yaml:5:"));
  CHECK_FALSE(fs::exists(none));
  r = run("check " + source("configs/crystals/peacock-cyan.yaml"));
  CHECK(r.status == 0);
}

TEST_CASE("plumage bench multilayer is the multilayer plug-in's benchmark", "[cli][bench]") {
  auto r = run("bench multilayer --layers 4 --points 20 --wavelengths 3 --repeats 2");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("## multilayer") && Catch::Contains("60 evaluations per run") &&
                           Catch::Contains("`plumage bench multilayer --layers 4 --points 20 --wavelengths 3`"));
  r = run("bench multilayer --help");
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("--layers VALUE") && Catch::Contains("default 30"));
  r = run("bench multilayer --layers 0");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("layers"));
}

// The explicit preparation step (issue 22): a crystal species' table is built before simulating,
// by option; `check` says what is to build and builds nothing; `never` refuses by name.
TEST_CASE("crystal tables come from the preparation step, as --tables says", "[cli][tables]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path("plumage-test-cli", "tables");
  fs::create_directories(dir);
  const std::string in_dir = "cd " + dir.string() + " && " + PLUMAGE_EXE + " ";
  const std::string mallard = source("configs/species/mallard.yaml");
  auto r = run_command(in_dir + "check " + mallard);
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("to prepare: green: build the reflection table of mallard-green "
                                       "(201 x 20 x 50 entries) into build/cache/tables/mallard-green-"));
  CHECK_FALSE(fs::exists(dir / "build"));
  r = run_command(in_dir + "--tables never simulate " + mallard +
                  " --lambda-nm 550 --theta-deg 0 --phi-deg 0 --instances 1 --out x.ffs");
  CHECK(r.status == 1);
  CHECK_THAT(r.output, Catch::Contains("mallard-green (201 x 20 x 50 entries)") && Catch::Contains("--tables build"));
  CHECK_FALSE(fs::exists(dir / "x.ffs"));
  // The option may follow the subcommand; a bad value is a usage error.
  r = run_command(in_dir + "simulate " + mallard + " --tables sometimes --out x.ffs");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("--tables"));
  fs::remove_all(dir);
}
