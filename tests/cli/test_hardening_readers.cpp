// Readers as a hostile tester meets them (issue 23): a .plm damaged and resealed (its checksum
// recomputed with the project's own function) fails `brdf check`; a directory or FIFO given as a
// .plt, .plm or shard is refused with exit 2 and its path named, without hanging; one damaged
// journal record is recomputed alone (the material equals a single run); duplicate, mixed and
// missing shards are refused with exit 2 naming the files, and nothing is written.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "plumage/checksum.hpp"

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;

namespace {

fs::path scratch(const std::string& name) {
  return plumage::cli_test::fresh_scratch_dir("plumage-test-hardening-readers", name);
}
using plumage::cli_test::file_bytes;
std::string bytes(const fs::path& f) { return file_bytes(f); }

void write_bytes(const fs::path& f, const std::string& data) { std::ofstream(f, std::ios::binary | std::ios::trunc) << data; }

const std::string kConfig = std::string(PLUMAGE_SOURCE_DIR) + "/configs/species/rockdove.yaml";
const std::string kTiny = " --fidelity preview --grid 3 --lambda-nm 400,500 --instances 3 --noise-functions 8";
const std::string kMaterial = std::string(PLUMAGE_SOURCE_DIR) + "/tests/cli/data";

// "(preview, N units)" of a fit summary.
std::string unit_count(const std::string& output) {
  std::smatch m;
  return std::regex_search(output, m, std::regex(R"(, (\d+) units\))")) ? m[1].str() : "";
}

// A tiny material, characterised once for the suite.
const fs::path& tiny_material() {
  static const fs::path file = [] {
    const fs::path dir = scratch("material");
    const Result r = run("characterize " + kConfig + kTiny + " --out " + (dir / "tiny.plm").string());
    INFO(r.output);
    REQUIRE(r.status == 0);
    return dir / "tiny.plm";
  }();
  return file;
}

}  // namespace

TEST_CASE("readers CLI: brdf check fails a resealed .plm with NaN nodes", "[hardening-readers]") {
  const fs::path dir = scratch("plm");
  std::string data = bytes(tiny_material());
  REQUIRE(run("brdf check " + tiny_material().string()).status == 0);
  // The first node's m_eff: 4 bytes after the parameter count 8 that follows the wavelengths.
  const std::string lambdas = [] {
    std::string s;
    for (double l : {400.0, 500.0}) s.append(reinterpret_cast<const char*>(&l), 8);
    return s;
  }();
  const auto at = data.find(lambdas);
  REQUIRE(at != std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(data.data() + at + 16 + 4, &nan, 8);
  const std::uint64_t sum = plumage::fnv1a(std::string_view(data).substr(0, data.size() - 8));
  std::memcpy(data.data() + data.size() - 8, &sum, 8);
  const fs::path bad = dir / "nan.plm";
  write_bytes(bad, data);
  const Result r = run("brdf check " + bad.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find(bad.string()) != std::string::npos);
  CHECK(r.output.find("m_eff") != std::string::npos);
  CHECK(r.output.find("node 0") != std::string::npos);
  // Wavelengths out of order.
  std::string swapped = bytes(tiny_material());
  const double l1 = 300.0;
  std::memcpy(swapped.data() + at + 8, &l1, 8);
  const std::uint64_t sum2 = plumage::fnv1a(std::string_view(swapped).substr(0, swapped.size() - 8));
  std::memcpy(swapped.data() + swapped.size() - 8, &sum2, 8);
  write_bytes(bad, swapped);
  const Result order = run("brdf check " + bad.string());
  CHECK(order.status == 2);
  CHECK(order.output.find("strictly increasing") != std::string::npos);
}

TEST_CASE("readers CLI: a directory or FIFO as an input file exits 2 with its path, never hangs", "[hardening-readers]") {
  const fs::path dir = scratch("kinds");
  const fs::path folder = dir / "folder.plt", fifo = dir / "fifo.plt";
  fs::create_directories(folder);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const fs::path& p : {folder, fifo}) {
    const std::string kind = p == folder ? "a directory" : "a FIFO";
    for (const std::string& cmd : {"timeout 20 " + std::string(PLUMAGE_EXE) + " table query " + p.string() +
                                       " --lambda-nm 500 --theta-deg 0 --phi-deg 0",
                                   "timeout 20 " + std::string(PLUMAGE_EXE) + " brdf check " + p.string(),
                                   "timeout 20 " + std::string(PLUMAGE_EXE) + " merge " + p.string() + " --out " +
                                       (dir / "out.plm").string()}) {
      const Result r = plumage::cli_test::run_command(cmd);
      INFO(cmd << "\n" << r.output);
      CHECK(r.status == 2);
      CHECK(r.output.find(p.string()) != std::string::npos);
      CHECK(r.output.find(kind) != std::string::npos);
      CHECK(r.output.find("underflow") == std::string::npos);
      CHECK(!fs::exists(dir / "out.plm"));
    }
  }
}

TEST_CASE("readers CLI: one damaged journal record is recomputed alone, the rest kept", "[hardening-readers]") {
  const fs::path dir = scratch("journal");
  // A complete shard 1/1 is the journal of a whole run: put it where a resumed run looks.
  const Result shard = run("characterize " + kConfig + kTiny + " --shard 1/1 --out " + (dir / "all.shard").string());
  INFO(shard.output);
  REQUIRE(shard.status == 0);
  std::string data = bytes(dir / "all.shard");
  const char magic[4] = {'P', 'L', 'M', 'R'};
  const auto first = data.find(std::string_view(magic, 4));
  const auto second = data.find(std::string_view(magic, 4), first + 1);
  REQUIRE(second != std::string::npos);
  data[second + 40] ^= 0x20;  // inside the second record's body: 5 of 6 groups stay good
  write_bytes(dir / "out.plm.journal", data);
  const Result r = run("characterize " + kConfig + kTiny + " --out " + (dir / "out.plm").string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("damaged record at bytes " + std::to_string(second)) != std::string::npos);
  CHECK(r.output.find("resuming (5 groups") != std::string::npos);
  CHECK(bytes(dir / "out.plm") == bytes(tiny_material()));  // byte-identical to a single run
  // The damaged shard itself is refused by merge, naming the offset.
  write_bytes(dir / "damaged.shard", data);
  const Result m = run("merge " + (dir / "damaged.shard").string() + " --out " + (dir / "m.plm").string());
  CHECK(m.status == 2);
  CHECK(m.output.find("damaged record at bytes " + std::to_string(second)) != std::string::npos);
  CHECK(!fs::exists(dir / "m.plm"));
}

TEST_CASE("readers CLI: duplicate, mixed and missing shards exit 2 naming the files", "[hardening-readers]") {
  const fs::path dir = scratch("shards");
  for (const char* s : {"1/2", "2/2", "1/3"}) {
    const std::string name = std::string("part") + s[0] + "of" + s[2] + ".shard";
    const Result r = run("characterize " + kConfig + kTiny + " --shard " + s + " --out " + (dir / name).string());
    INFO(r.output);
    REQUIRE(r.status == 0);
  }
  const std::string p1 = (dir / "part1of2.shard").string(), p2 = (dir / "part2of2.shard").string(),
                    q1 = (dir / "part1of3.shard").string(), out = (dir / "out.plm").string();
  fs::copy_file(p1, dir / "copy.shard");
  const std::string copy = (dir / "copy.shard").string();
  const struct {
    std::string shards, words[2];
  } cases[] = {{p1 + " " + p2 + " " + p1, {"given twice", p1}},
               {p1 + " " + p2 + " " + copy, {copy, p1}},
               {p1 + " " + q1 + " " + p2, {q1, "different shard counts"}},
               {p1, {"shard is missing", "3 of 6 work groups"}}};
  for (const auto& c : cases) {
    const Result r = run("merge " + c.shards + " --out " + out);
    INFO(c.shards << "\n" << r.output);
    CHECK(r.status == 2);
    for (const auto& w : c.words) CHECK(r.output.find(w) != std::string::npos);
    CHECK(!fs::exists(out));
  }
  // The right shards merge, and the summary counts every unit once (as a single run does).
  const Result single = run("characterize " + kConfig + kTiny + " --out " + (dir / "single.plm").string());
  const Result merged = run("merge " + p2 + " " + p1 + " --out " + out);
  INFO(merged.output);
  REQUIRE(merged.status == 0);
  CHECK(!unit_count(single.output).empty());
  CHECK(unit_count(merged.output) == unit_count(single.output));
  CHECK(bytes(out) == bytes(dir / "single.plm"));
}

TEST_CASE("readers CLI: a damaged imported .xsec exits 2 naming the file and the line", "[hardening-readers]") {
  // Issue 25 (a): a species whose structure is xsec_file over a file cut short.
  const fs::path dir = scratch("xsec");
  const Result written = run("geometry " + kConfig + " --no-svg --no-png --out " + dir.string());
  INFO(written.output);
  REQUIRE(written.status == 0);
  const std::string whole = bytes(dir / "rockdove-forest-0.xsec");
  write_bytes(dir / "cut-0.xsec", whole.substr(0, whole.size() / 3));
  write_bytes(dir / "imported.yaml",
              "species: imported\nreflection: {model: multilayer}\n"
              "structure: {generator: xsec_file, files: \"cut-{index}.xsec\"}\n");
  const Result r = run("geometry " + (dir / "imported.yaml").string() + " --no-svg --no-png --out " + (dir / "out").string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains((dir / "cut-0.xsec").string() + ": line ") && Catch::Contains("truncated"));
  CHECK_FALSE(fs::exists(dir / "out" / "imported-0.xsec"));
  // `plumage check` lists it among the file's errors (it is not an escaped fault of check itself).
  const Result checked = run("check " + (dir / "imported.yaml").string());
  INFO(checked.output);
  CHECK(checked.status == 2);
  CHECK_THAT(checked.output, Catch::Contains((dir / "cut-0.xsec").string() + ": line ") && Catch::Contains("error(s)"));
}

TEST_CASE("readers CLI: a bad SVG cross section exits 2 naming the file and the element", "[hardening-readers]") {
  // Issue 25 (c): a species whose structure is svg_file over an outline left open.
  const fs::path dir = scratch("svg");
  write_bytes(dir / "open-0.svg",
              "<svg viewBox=\"0 0 6000 600\">\n<rect id=\"cortex\" width=\"6000\" height=\"600\" fill=\"#ccc\"/>\n"
              "<path id=\"film\" fill=\"#000\" d=\"M 0,500 h 6000 v 100 H 0\"/>\n</svg>\n");
  write_bytes(dir / "traced.yaml",
              "species: traced\nreflection: {model: multilayer}\n"
              "structure: {generator: svg_file, files: \"open-{index}.svg\", um_per_unit: 0.001,\n"
              "            materials: {\"#ccc\": keratin, \"#000\": melanin}}\n");
  const Result r = run("geometry " + (dir / "traced.yaml").string() + " --no-svg --no-png --out " + (dir / "out").string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains((dir / "open-0.svg").string() + ": element 'film' (line 3): open outline"));
  CHECK_FALSE(fs::exists(dir / "out" / "traced-0.xsec"));
}

TEST_CASE("readers CLI: a bad FeatherLab file exits 2 naming the file and the line", "[hardening-readers]") {
  // Issue 25 (b): a species whose structure is featherlab_files over an xyvals with a NaN.
  const fs::path dir = scratch("featherlab");
  fs::create_directories(dir / "geometry");
  std::string xy, info, ratio;
  for (int c = 0; c < 3; ++c) {
    info += std::to_string(11 * c) + ",11\n";
    for (int k = 0; k < 11; ++k) xy += std::to_string(-5 + k) + "," + (c == 1 && k == 4 ? "NaN" : std::to_string(-c)) + "\n";
  }
  write_bytes(dir / "geometry" / "xyvals1.txt", xy);
  write_bytes(dir / "geometry" / "info1.txt", info);
  write_bytes(dir / "featherlab.yaml",
              "species: featherlab\nreflection: {model: multilayer}\n"
              "structure: {generator: featherlab_files, instances: geometry, layers: [keratin, melanin]}\n");
  const Result r = run("geometry " + (dir / "featherlab.yaml").string() + " --no-svg --no-png --out " + (dir / "out").string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains((dir / "geometry" / "xyvals1.txt").string() + ": line 16: y: NaN is not a finite number"));
  CHECK_FALSE(fs::exists(dir / "out" / "featherlab-0.xsec"));
}
