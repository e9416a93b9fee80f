// `plumage table build|query|plot` end to end on a tiny crystal (one row of mallard-green rods,
// preview fidelity, one wavelength, 2 angles: 8 broadband FDTD runs in two checkpoint chunks,
// seconds): build →
// query (json) → plot writes a PNG; an interrupted build resumes and redoes only the missing
// runs; bad input exits 2 naming file, line and field; nothing is half-written on failure.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using plumage::cli_test::run_command;

namespace {

fs::path scratch() { return plumage::cli_test::scratch_dir("plumage-test-table-cli"); }

// mallard-green with a single row of rods: the cheapest real crystal cell.
fs::path tiny_crystal() {
  std::ifstream in(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const std::string yaml = std::regex_replace(text.str(), std::regex("rows: 6"), "rows: 1");
  REQUIRE(yaml != text.str());
  const fs::path file = scratch() / "tiny-crystal.yaml";
  std::ofstream(file) << yaml;
  return file;
}

const std::string kGrid = " --fidelity preview --n-lambda 1 --lambda-min 550 --lambda-max 550 --n-theta 1 --n-phi 2";

// "fdtd runs: N (R resumed ...)" from the build summary.
std::pair<int, int> runs_of(const std::string& out) {
  std::smatch m;
  int total = -1, resumed = 0;
  if (std::regex_search(out, m, std::regex("fdtd runs: ([0-9]+)"))) total = std::stoi(m[1]);
  if (std::regex_search(out, m, std::regex("\\(([0-9]+) resumed from a checkpoint\\)"))) resumed = std::stoi(m[1]);
  return {total, resumed};
}

}  // namespace

TEST_CASE("table build, query as json and plot a PNG", "[cli][table]") {
  const fs::path crystal = tiny_crystal();
  const fs::path out = scratch() / "tiny.plt";
  fs::remove(out);
  auto r = run("table build " + crystal.string() + kGrid + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  CHECK_THAT(r.output, Catch::Contains("wrote " + out.string()) && Catch::Contains("fdtd runs:"));

  r = run("table query " + out.string() + " --lambda-nm 550 --theta-deg 20 --phi-deg 30 --format json");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("\"crystal\": \"mallard-green\"") && Catch::Contains("\"jones\": {\"ss\": ["));
  std::smatch m;
  REQUIRE(std::regex_search(r.output, m, std::regex("\"R_s\": ([-0-9.eE+]+), \"R_p\": ([-0-9.eE+]+)")));
  const double Rs = std::stod(m[1]), Rp = std::stod(m[2]);
  CHECK(Rs > 0.0);  // one absorbing melanin row under keratin reflects a few per cent
  CHECK(Rs < 1.0);
  CHECK(Rp > 0.0);
  CHECK(Rp < 1.0);
  // Exact grazing limit through the query: diag(−1, −1).
  r = run("table query " + out.string() + " --lambda-nm 550 --theta-deg 10 --phi-deg 90 --format json");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("\"ss\": [-1, 0]") && Catch::Contains("\"pp\": [-1, 0]"));

  const fs::path png = scratch() / "tiny.png";
  fs::remove(png);
  r = run("table plot " + out.string() + " --out " + png.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  REQUIRE(fs::exists(png));
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  CHECK(std::string(magic + 1, 3) == "PNG");
  CHECK(fs::file_size(png) > 1000);
}

TEST_CASE("table build: grazing entries are reported on stderr and in the table's notes", "[cli][table][warnings]") {
  // cos φ_local = 0.2 is below kz_min = 0.25: that entry is continued, not simulated (issue 9).
  const fs::path crystal = tiny_crystal();
  const fs::path out = scratch() / "grazing.plt";
  fs::remove(out);
  auto r = run("table build " + crystal.string() +
               " --fidelity preview --n-lambda 1 --lambda-min 550 --lambda-max 550 --n-theta 1 --n-phi 5 --out " +
               out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("warning: ") && Catch::Contains("[fdtd.grazing_continued]"));
  r = run("table query " + out.string() + " --lambda-nm 550 --theta-deg 0 --phi-deg 0 --format json");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("\"notes\": \"") && Catch::Contains("[fdtd.grazing_continued]"));
  // -q silences the echo; the notes still carry it.
  fs::remove(out);
  r = run("-q table build " + crystal.string() +
          " --fidelity preview --n-lambda 1 --lambda-min 550 --lambda-max 550 --n-theta 1 --n-phi 5 --out " + out.string());
  REQUIRE(r.status == 0);
  CHECK(r.output.find("[fdtd.grazing_continued]") == std::string::npos);
  r = run("table query " + out.string() + " --lambda-nm 550 --theta-deg 0 --phi-deg 0");
  CHECK_THAT(r.output, Catch::Contains("notes: ") && Catch::Contains("[fdtd.grazing_continued]"));
}

TEST_CASE("an interrupted table build resumes and redoes only the missing runs", "[cli][table]") {
  const fs::path crystal = tiny_crystal();
  const fs::path fresh = scratch() / "fresh.plt", out = scratch() / "resumed.plt";
  const std::string partial = out.string() + ".partial";
  fs::remove(fresh), fs::remove(out), fs::remove(partial);
  auto r = run("table build " + crystal.string() + kGrid + " --out " + fresh.string());
  REQUIRE(r.status == 0);
  const auto [fresh_runs, none] = runs_of(r.output);
  REQUIRE(fresh_runs > 4);  // more than one checkpoint chunk (2 threads × 2 runs)
  CHECK(none == 0);

  // Start a build and kill it (SIGKILL: no clean-up) once the checkpoint holds finished runs.
  const std::string exe = PLUMAGE_EXE;
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::freopen("/dev/null", "w", stderr);
    execl(exe.c_str(), exe.c_str(), "table", "build", crystal.c_str(), "--fidelity", "preview", "--n-lambda", "1",
          "--lambda-min", "550", "--lambda-max", "550", "--n-theta", "1", "--n-phi", "2", "--out", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  bool killed = false;
  for (int i = 0; i < 6000 && !killed; ++i) {  // up to 60 s
    std::error_code ec;
    if (fs::exists(partial) && fs::file_size(partial, ec) > 16 && !ec) {
      kill(pid, SIGKILL);
      killed = true;
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    int st = 0;
    if (!killed && waitpid(pid, &st, WNOHANG) == pid) break;  // finished before we could interrupt
  }
  if (killed) waitpid(pid, nullptr, 0);
  REQUIRE(killed);
  CHECK_FALSE(fs::exists(out));  // nothing half-written: only the checkpoint
  CHECK(fs::exists(partial));

  r = run("table build " + crystal.string() + kGrid + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  const auto [total, resumed] = runs_of(r.output);
  CHECK(resumed >= 1);
  CHECK(resumed < fresh_runs);
  CHECK(total == fresh_runs);  // resumed + newly run = the whole set, none run twice
  CHECK_FALSE(fs::exists(partial));
  // Same table as the uninterrupted build.
  for (const char* angles : {"--theta-deg 0 --phi-deg 0", "--theta-deg 25 --phi-deg 40", "--theta-deg 50 --phi-deg 70"}) {
    const auto a = run("table query " + fresh.string() + " --lambda-nm 550 " + angles + " --format json");
    const auto b = run("table query " + out.string() + " --lambda-nm 550 " + angles + " --format json");
    // Values equal; the notes differ by design (they count the resumed runs).
    auto values = [](const std::string& out) {
      const auto from = out.find("\"lambda_nm\"");
      return out.substr(from, out.find(", \"notes\"") - from);
    };
    CHECK(values(a.output) == values(b.output));
  }
}

TEST_CASE("table commands reject bad input with exit 2 and write nothing", "[cli][table]") {
  const fs::path dir = scratch();
  const fs::path out = dir / "bad.plt";
  fs::remove(out), fs::remove(out.string() + ".partial");
  // A crystal value out of range: file, line, column and field named.
  std::ifstream in(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const fs::path bad = dir / "bad-crystal.yaml";
  std::ofstream(bad) << std::regex_replace(text.str(), std::regex("rod_diameter_nm: 152"), "rod_diameter_nm: -152");
  auto r = run("table build " + bad.string() + " --fidelity preview --out " + out.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("bad-crystal.yaml:8:") && Catch::Contains("rod_diameter_nm"));
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  // Rods that overlap their neighbours.
  std::ofstream(bad) << std::regex_replace(text.str(), std::regex("rod_diameter_nm: 152"), "rod_diameter_nm: 200");
  r = run("table build " + bad.string() + " --fidelity preview --out " + out.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("bad-crystal.yaml"));
  CHECK_FALSE(fs::exists(out));
  // A builder parameter out of range (the options document is named).
  r = run("table build " + std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml --fidelity preview "
          "--resolution-nm -3 --out " + out.string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("resolution_nm"));
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(out.string() + ".partial"));
  // Unknown fidelity on the command line.
  r = run("table build " + std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml --fidelity fast --out " +
          out.string());
  CHECK(r.status == 2);
  CHECK_FALSE(fs::exists(out));
  // Query and plot of a file that is not a table, and of a missing file.
  const fs::path junk = dir / "junk.plt";
  std::ofstream(junk) << "not a table\n";
  r = run("table query " + junk.string() + " --lambda-nm 500");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("junk.plt") && Catch::Contains("not a PLMRTAB reflection table"));
  r = run("table plot " + junk.string() + " --out " + (dir / "junk.png").string());
  CHECK(r.status == 2);
  CHECK_FALSE(fs::exists(dir / "junk.png"));
  r = run("table query " + (dir / "missing.plt").string());
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("missing.plt"));
}
