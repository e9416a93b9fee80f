// `plumage materials` (the command behind `make materials`, issue 26) end to end on a tiny grid
// (rock dove's 6 variants, 3 wavelengths x 4 x 4 incident nodes, 3 instances: seconds): every
// variant is written under the name the material store looks up, a second run skips them all
// and rewrites nothing, a run killed with SIGKILL resumes from its journal to the same bytes,
// a deleted material alone is made again; and the Makefile target calls the command.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <thread>

#include "plumage/material_store.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using plumage::cli_test::run_command;
using namespace plumage;

namespace {

const std::string kSuite = "plumage-test-materials-cli";
const std::string kConfig = std::string(PLUMAGE_SOURCE_DIR) + "/configs/species/rockdove.yaml";
const std::string kTiny = " --fidelity preview --grid 4 --lambda-nm 400,450,500 --instances 3 --noise-functions 8";

std::string bytes(const fs::path& f) { return plumage::cli_test::file_bytes(f); }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

// Where the library's material store looks up each rock-dove variant of the tiny settings in `dir`.
std::vector<fs::path> lookup_paths(const fs::path& dir) {
  MaterialStoreOptions o;
  o.directory = dir;
  o.overrides.grid = 4;
  o.overrides.lambda_nm = {400, 450, 500};
  o.overrides.instances = 3;
  o.overrides.noise_functions = 8;
  const MaterialStore store(testing::registry(), o);
  std::vector<fs::path> out;
  for (const std::string& v : species_variants(kConfig))
    out.push_back(store.canonical_path(store.settings(load_species_config(kConfig, testing::registry(), v), "preview")));
  return out;
}

}  // namespace

TEST_CASE("materials: every variant made under its lookup name, then skipped", "[cli][materials]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "made");
  const std::vector<fs::path> paths = lookup_paths(dir);
  REQUIRE(paths.size() == 6);

  const Result first = run("materials " + kConfig + kTiny + " --into " + dir.string());
  INFO(first.output);
  REQUIRE(first.status == 0);
  CHECK(count(first.output, ": done in ") == 6);
  CHECK(first.output.find("6 variants, 6 made, 0 skipped") != std::string::npos);
  std::vector<std::string> made;
  for (const fs::path& p : paths) {
    INFO(p);
    REQUIRE(fs::exists(p));
    CHECK(!fs::exists(p.string() + ".journal"));  // removed on success
    made.push_back(bytes(p));
  }
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 6);  // nothing else

  const Result second = run("materials " + kConfig + kTiny + " --into " + dir.string());
  INFO(second.output);
  REQUIRE(second.status == 0);
  CHECK(count(second.output, ": skipped (current)") == 6);
  CHECK(second.output.find("6 variants, 0 made, 6 skipped") != std::string::npos);
  for (std::size_t i = 0; i < paths.size(); ++i) CHECK(bytes(paths[i]) == made[i]);

  // A deleted material alone is made again, to the same bytes (the characterisation is deterministic).
  fs::remove(paths[2]);
  const Result third = run("materials " + kConfig + kTiny + " --into " + dir.string());
  INFO(third.output);
  REQUIRE(third.status == 0);
  CHECK(third.output.find("6 variants, 1 made, 5 skipped") != std::string::npos);
  CHECK(bytes(paths[2]) == made[2]);

  // Other settings (another grid) are another key: nothing there is current for them.
  const Result other = run("materials " + kConfig + " --fidelity preview --grid 3 --lambda-nm 400,450,500 "
                           "--instances 3 --noise-functions 8 --into " + dir.string());
  INFO(other.output);
  REQUIRE(other.status == 0);
  CHECK(other.output.find("6 variants, 6 made, 0 skipped") != std::string::npos);
}

TEST_CASE("materials: a run killed with SIGKILL resumes from the journal to the same bytes", "[cli][materials]") {
  const fs::path ref_dir = plumage::cli_test::fresh_scratch_path(kSuite, "ref");
  const fs::path dir = plumage::cli_test::fresh_scratch_path(kSuite, "killed");
  REQUIRE(run("materials " + kConfig + kTiny + " --into " + ref_dir.string()).status == 0);
  const std::vector<fs::path> paths = lookup_paths(dir), refs = lookup_paths(ref_dir);

  const fs::path journal = paths[0].string() + ".journal";
  const Result started = run_command("sh -c '" + std::string(PLUMAGE_EXE) + " materials " + kConfig + kTiny + " --into " +
                                     dir.string() + " > " + (dir.string() + ".log") + " 2>&1 & echo $!'");
  const pid_t pid = std::stoi(started.output);
  // Wait until the first variant's journal holds two records, then SIGKILL.
  bool killed = false;
  for (int k = 0; k < 6000 && !killed; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (count(bytes(journal), "PLMR") >= 2) killed = ::kill(pid, SIGKILL) == 0;
  }
  REQUIRE(killed);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  REQUIRE(!fs::exists(paths[0]));  // nothing half-written under the lookup name
  REQUIRE(fs::exists(journal));

  const Result resumed = run("materials " + kConfig + kTiny + " --into " + dir.string());
  INFO(resumed.output);
  REQUIRE(resumed.status == 0);
  CHECK(std::regex_search(resumed.output, std::regex("resuming \\([0-9]+ groups")));
  CHECK(resumed.output.find("6 variants, 6 made, 0 skipped") != std::string::npos);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    INFO(paths[i]);
    CHECK(bytes(paths[i]) == bytes(refs[i]));
  }
}

TEST_CASE("materials: `make materials` calls the command with FIDELITY and SPECIES", "[cli][materials]") {
  const Result all = run_command("make -n -s -C " + std::string(PLUMAGE_SOURCE_DIR) + " materials");
  INFO(all.output);
  REQUIRE(all.status == 0);
  CHECK(std::regex_search(all.output, std::regex("plumage materials( configs/species/[a-z]+\\.yaml){7} --fidelity production")));
  const Result one = run_command("make -n -s -C " + std::string(PLUMAGE_SOURCE_DIR) +
                                 " materials FIDELITY=preview SPECIES=rockdove 'CHARACTERIZE_FLAGS=--grid 4'");
  INFO(one.output);
  REQUIRE(one.status == 0);
  CHECK(one.output.find("plumage materials configs/species/rockdove.yaml --fidelity preview --into build/materials --grid 4") !=
        std::string::npos);
}
