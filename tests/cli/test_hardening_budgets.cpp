// Issue 23, memory budgets and progress (Deliver 2 and 3): every solver and builder estimates its
// peak before allocating and refuses a job over its budget with exit status 2, naming the estimate,
// the memory available and the options that lower it, fast and before anything is written. The
// budgets are set with `--max-memory` so that the cases do not depend on the machine.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;

namespace {

const std::string kSuite = "plumage-test-hardening-budgets";

std::string source(const std::string& path) { return std::string(PLUMAGE_SOURCE_DIR) + "/" + path; }

std::string read_text(const std::string& path) { return plumage::cli_test::file_bytes(path); }

// A copy of a source config with `pattern` replaced (the replacement must happen).
fs::path variant_of(const std::string& path, const std::string& pattern, const std::string& replacement,
                    const std::string& name) {
  const std::string text = read_text(source(path));
  const std::string changed = std::regex_replace(text, std::regex(pattern), replacement);
  REQUIRE(changed != text);
  const fs::path file = plumage::cli_test::scratch_dir(kSuite) / name;
  std::ofstream(file) << changed;
  return file;
}

// Runs `plumage <args>` and returns the result with the wall time in seconds.
struct Timed {
  Result result;
  double seconds = 0;
};
Timed timed_run(const std::string& args) {
  const auto t0 = std::chrono::steady_clock::now();
  Timed t{run(args), 0};
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

// The common shape of a refusal: exit 2, quickly, naming the estimate and the memory available.
void require_refused(const Timed& t, double max_seconds = 5.0) {
  INFO(t.result.output);
  CHECK(t.result.status == 2);
  CHECK_THAT(t.result.output, Catch::Contains("estimated") && Catch::Contains("exceeds the memory available"));
  CHECK(t.seconds < max_seconds);
}

bool folder_empty_or_absent(const fs::path& dir) { return !fs::exists(dir) || fs::is_empty(dir); }

}  // namespace

TEST_CASE("bench bem, as the README shows it, refuses within 5 s on an 8 GiB budget", "[cli][budgets]") {
  const fs::path record = plumage::cli_test::scratch_dir(kSuite) / "bench-record.md";
  fs::remove(record);
  for (const std::string& args : {std::string("--max-memory 8GiB bench bem"),
                                  "bench bem --max-memory 8GiB --record " + record.string()}) {
    const Timed t = timed_run(args);
    require_refused(t);
    CHECK_THAT(t.result.output, Catch::Contains("bem hmatrix solve of") && Catch::Contains("(--max-memory 8GiB less ") &&
                                    Catch::Contains("points_per_wavelength (now 30)") && Catch::Contains("preconditioner_factor") &&
                                    Catch::Contains("a narrower segment"));
  }
  CHECK_FALSE(fs::exists(record));
}

TEST_CASE("simulate with the BEM refuses a dense system over the budget, by flag and by config key", "[cli][budgets]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "simulate-bem");
  const std::string out = (dir / "cyl.ffs").string();
  const std::string common = " --lambda-nm 550 --directions full --out " + out;
  const Timed by_flag = timed_run("--max-memory 4MiB simulate " + source("configs/validation/keratin-cylinder-bem.yaml") + common);
  require_refused(by_flag);
  CHECK_THAT(by_flag.result.output, Catch::Contains("bem dense solve of") && Catch::Contains("dense matrix 16 N^2") &&
                                        Catch::Contains("method: hmatrix") && Catch::Contains("points_per_wavelength"));
  const fs::path keyed = variant_of("configs/validation/keratin-cylinder-bem.yaml", "incidence: plane_wave",
                                    "incidence: plane_wave\n  max_memory: 4MiB", "cylinder-max-memory.yaml");
  const Timed by_key = timed_run("simulate " + keyed.string() + common);
  require_refused(by_key);
  CHECK_THAT(by_key.result.output, Catch::Contains("max_memory: 4MiB"));
  const Result bad = run("simulate " + variant_of("configs/validation/keratin-cylinder-bem.yaml", "incidence: plane_wave",
                                                  "incidence: plane_wave\n  max_memory: lots", "cylinder-bad-size.yaml")
                                           .string() + common);
  CHECK(bad.status == 2);
  CHECK_THAT(bad.output, Catch::Contains("max_memory") && Catch::Contains("not a memory size"));
  CHECK(folder_empty_or_absent(dir));
}

TEST_CASE("a bad --max-memory is refused naming the flag", "[cli][budgets]") {
  for (const std::string& size : {"0", "-5GiB", "8 parsecs", "nan"}) {
    const Result r = run("--max-memory '" + size + "' multilayer --stack 'air | keratin 300 | air' --lambda-nm 500");
    INFO(size << ": " << r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains("--max-memory") && Catch::Contains("not a memory size"));
  }
}

TEST_CASE("table build refuses a crystal whose FDTD grid would not fit, leaving no .partial", "[cli][budgets]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "table");
  fs::create_directories(dir);
  const fs::path huge = variant_of("configs/crystals/mallard-green.yaml", "a_x_nm: 190", "a_x_nm: 1e9", "huge-cell.yaml");
  const fs::path out = dir / "huge.plt";
  // a_x_nm: 1e9 is now outside the declared range (0, 5000] nm: refused at the field, before the
  // builder's estimate, fast, and nothing written.
  const Timed t = timed_run("table build " + huge.string() + " --fidelity preview --out " + out.string());
  INFO(t.result.output);
  CHECK(t.result.status == 2);
  CHECK_THAT(t.result.output, Catch::Contains(huge.string() + ":") && Catch::Contains("a_x_nm") &&
                                  Catch::Contains("out of range"));
  CHECK(t.seconds < 5.0);
  // the real cell on a budget too small for it: the builder's own estimate
  const Timed small = timed_run("--max-memory 1MiB table build " + source("configs/crystals/mallard-green.yaml") +
                                " --fidelity preview --out " + (dir / "mallard.plt").string());
  require_refused(small);
  CHECK_THAT(small.result.output, Catch::Contains("fdtd_periodic table of crystal") && Catch::Contains("resolution_nm") &&
                                      Catch::Contains("threads") && Catch::Contains("a_x_nm"));
  CHECK(fs::is_empty(dir));  // neither .plt nor .plt.partial nor a checkpoint
}

TEST_CASE("characterize refuses an absurd work-unit count naming the count and the flag", "[cli][budgets]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "characterize");
  const Timed t = timed_run("characterize " + source("configs/species/rockdove.yaml") +
                            " --fidelity preview --grid 100000 --out " + (dir / "x.plm").string());
  INFO(t.result.output);
  CHECK(t.result.status == 2);
  CHECK_THAT(t.result.output, Catch::Contains("work units") && Catch::Contains("grid 100000") && Catch::Contains("--grid"));
  CHECK(t.seconds < 5.0);
  CHECK(folder_empty_or_absent(dir));
}

TEST_CASE("geometry refuses outlines whose vertices would not fit, at the key", "[cli][budgets]") {
  const struct {
    const char *pattern, *replacement, *key;
  } cases[] = {// The largest/smallest values the declared ranges admit (1e12 um and the like are refused by
               // the range itself: tests/cli/test_hardening_check.cpp), over a 1 MiB budget.
               {"width_um: 20", "width_um: 10000", "outline.width_um"},
               {"spacing_nm: 30", "spacing_nm: 1", "outline.spacing_nm"},
               {"thickness_um: 4.0", "thickness_um: 1000", "outline.thickness_um"}};
  int k = 0;
  for (const auto& c : cases) {
    const fs::path config = variant_of("configs/species/rockdove.yaml", c.pattern, c.replacement,
                                       "rockdove-" + std::to_string(k++) + ".yaml");
    const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "geometry");
    for (const std::string& command : {"geometry " + config.string() + " --instances 1 --out " + out.string(),
                                       "check " + config.string()}) {
      const Timed t = timed_run("--max-memory 1MiB " + command);
      INFO(c.replacement << ": " << command);
      require_refused(t);
      CHECK_THAT(t.result.output, Catch::Contains(config.string() + ":") && Catch::Contains("barbule outline") &&
                                      Catch::Contains(c.key));
    }
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("render refuses a view whose image buffers would not fit", "[cli][budgets]") {
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "render");
  const Timed t = timed_run("--max-memory 16GiB render " + source("configs/scenes/demo.yaml") +
                            " --width 100000 --height 100000 --out " + out.string());
  require_refused(t);
  CHECK_THAT(t.result.output, Catch::Contains("100000 x 100000 pixels") && Catch::Contains("--width/--height"));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("long BEM steps report progress on stderr, and -q silences them", "[cli][budgets][progress]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "progress");
  fs::create_directories(dir);
  const fs::path hm = variant_of("configs/validation/keratin-cylinder-bem.yaml", "incidence: plane_wave",
                                 "incidence: plane_wave\n  method: hmatrix", "cylinder-hmatrix.yaml");
  const std::string args = "simulate " + hm.string() + " --lambda-nm 550 --directions full --out " + (dir / "a.ffs").string();
  const Result loud = run(args);
  INFO(loud.output);
  REQUIRE(loud.status == 0);
  CHECK_THAT(loud.output, Catch::Contains("bem: H-matrix assembly") && Catch::Contains("bem: GMRES") &&
                              Catch::Contains("relative residual") && Catch::Contains("right-hand side"));
  const Result quiet = run("-q " + args);
  REQUIRE(quiet.status == 0);
  CHECK(quiet.output.find("bem: GMRES") == std::string::npos);
}

// The pipeline solves instances in parallel, one per thread (solve_memory.hpp): a budget that holds
// one solve but not two lowers the parallelism instead of refusing, says so, and the file is the
// same byte for byte (each instance's far field does not depend on which thread solved it).
TEST_CASE("simulate solves fewer instances at a time when the budget holds fewer, with the same result",
          "[cli][budgets]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_dir(kSuite, "simulate-plan");
  const std::string config = source("configs/validation/keratin-cylinder-bem.yaml");
  const std::string common = " --lambda-nm 550 --instances 2 --directions full --out ";
  // One solve's estimate, printed by a refusal: "...: estimated 52.7 MiB (...".
  const Result refused = run("--max-memory 1 simulate " + config + common + (dir / "none.ffs").string());
  REQUIRE(refused.status == 2);
  std::smatch m;
  REQUIRE(std::regex_search(refused.output, m, std::regex(R"(bem dense solve of \d+ unknowns .*: estimated ([0-9.]+) MiB)")));
  const double one_mib = std::stod(m[1]);
  CHECK(one_mib > 40.0);  // the dense matrix alone is 24.4 MiB, the far-field operator 20.6 MiB
  // What the process held when it refused ("... less 31.2 MiB resident)"): ~20-40 MiB, but ~150
  // MiB under AddressSanitizer (its shadow memory), so the budget is built on the measured value.
  REQUIRE(std::regex_search(refused.output, m, std::regex(R"(less ([0-9.]+) (KiB|MiB|GiB) resident)")));
  const double resident_mib = std::stod(m[1]) * (m[2] == "KiB" ? 1.0 / 1024 : m[2] == "GiB" ? 1024.0 : 1.0);
  const Result free_run = run("simulate " + config + common + (dir / "free.ffs").string());
  REQUIRE(free_run.status == 0);
  // Room for one solve and what the process holds (with 10 MiB to spare), not for two.
  const std::string budget = std::to_string(static_cast<int>(1.4 * one_mib + resident_mib + 10.0)) + "MiB";
  const Result limited = run("--max-memory " + budget + " simulate " + config + common + (dir / "limited.ffs").string());
  INFO(limited.output);
  REQUIRE(limited.status == 0);
  if (std::thread::hardware_concurrency() >= 2) {
    CHECK_THAT(limited.output, Catch::Contains("simulate: memory: 1 solve(s) at a time instead of 2"));
  }
  CHECK(plumage::cli_test::file_bytes(dir / "limited.ffs") == plumage::cli_test::file_bytes(dir / "free.ffs"));
}

// A 2 mm wide barbule at the default 50 px/um is a 100 000 x 30 000 pixel picture: over libpng's
// 4 GiB raster limit, it was drawn for 108 s (10.8 GB) and then failed with exit 1, leaving the
// .xsec and .svg behind. Now refused before anything is written, with the scale that fits, and
// at that scale the instance is drawn with a line saying so.
TEST_CASE("geometry refuses a picture over the PNG limit before writing, naming the scale that fits",
          "[cli][budgets]") {
  const fs::path wide = variant_of("configs/species/rockdove.yaml", "width_um: 20", "width_um: 2000", "rockdove-wide.yaml");
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "geometry-wide");
  const Timed t = timed_run("geometry " + wide.string() + " --out " + dir.string());
  INFO(t.result.output);
  CHECK(t.result.status == 2);
  CHECK_THAT(t.result.output, Catch::Contains("over the PNG writer's limit") && Catch::Contains("--pixels-per-um (at most"));
  CHECK(t.seconds < 20.0);
  CHECK(!fs::exists(dir));
  std::smatch m;
  REQUIRE(std::regex_search(t.result.output, m, std::regex(R"(--pixels-per-um \(at most ([0-9.e+]+) here\))")));
  const double fits = std::stod(m[1]);
  CHECK(fits < 50.0);
  // Well inside the limit (1/8 of the scale that fits: 1/64 of the raster, 2.2e7 pixels), drawn
  // with a line saying which picture is being drawn.
  const Result drawn = run("geometry " + wide.string() + " --out " + dir.string() + " --no-svg --pixels-per-um " +
                           std::to_string(fits / 8.0));
  INFO(drawn.output);
  CHECK(drawn.status == 0);
  CHECK_THAT(drawn.output, Catch::Contains("geometry: drawing rockdove-forest-0.png: PNG picture of"));
  CHECK(fs::exists(dir / "rockdove-forest-0.png"));
}
