// Warnings of a run (plumage/diagnostics.hpp) and how they travel with the files a run writes
// (docs/formats.md): .plm field `warnings` (version 2; version 1 still read), EXR attribute.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <thread>
#include <vector>

#include "plumage/checksum.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/exr.hpp"
#include "plumage/feather_material.hpp"

using namespace plumage;

namespace {

std::filesystem::path temp_file(const char* name) {
  auto dir = std::filesystem::temp_directory_path() / "plumage-test-diagnostics";
  std::filesystem::create_directories(dir);
  return dir / name;
}

FeatherMaterial small_material() {
  FeatherMaterial m;
  m.label = "test/variant";
  m.config_hash = "00ff";
  m.fidelity = "preview";
  m.grid = 1;
  m.lambda_nm = {400};
  m.nodes.resize(4);
  for (std::size_t k = 0; k < m.nodes.size(); ++k)
    for (int p = 0; p < kMaterialParameters; ++p) m.nodes[k].*kMaterialFields[p] = 0.1 * (k + 1) + 0.01 * p;
  m.noise.samples = 4;
  m.noise.lag1 = 0.5;
  m.noise.functions = {1.f, -1.f, 1.f, -1.f};
  return m;
}

std::string read_bytes(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("diagnostics: a code is echoed once, counted, summarised on one line each", "[diagnostics]") {
  CapturedWarnings scope;
  CHECK(diagnostics().empty());
  warn("test.first", "first condition, x = 3");
  warn("test.second", "second condition\nwith a line break");
  warn("test.first", "first condition again, x = 4");
  CHECK(diagnostics().has("test.first"));
  CHECK_FALSE(diagnostics().has("test.third"));
  const auto list = diagnostics().warnings();
  REQUIRE(list.size() == 2);
  CHECK(list[0].code == "test.first");
  CHECK(list[0].count == 2);
  // The echo shows the first raise; the kept message is the smallest (" again" < ", x").
  CHECK(list[0].message == "first condition again, x = 4");
  CHECK(list[1].message == "second condition with a line break");
  CHECK(scope.echoed() ==
        "warning: first condition, x = 3 [test.first]\n"
        "warning: second condition with a line break [test.second]\n");
  CHECK(diagnostics().summary("; ") ==
        "test.first: first condition again, x = 4 (raised 2 times); test.second: second condition with a line break; ");
  diagnostics().set_echo(nullptr);
  warn("test.quiet", "not echoed");
  CHECK(scope.echoed().find("not echoed") == std::string::npos);
  CHECK(diagnostics().has("test.quiet"));
}

TEST_CASE("diagnostics: concurrent raises from many threads are all counted", "[diagnostics]") {
  CapturedWarnings scope;
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([t] {
      for (int k = 0; k < 1000; ++k) warn(t % 2 ? "test.odd" : "test.even", "raised in a loop");
    });
  for (auto& th : threads) th.join();
  const auto list = diagnostics().warnings();
  REQUIRE(list.size() == 2);
  CHECK(list[0].count + list[1].count == 8000);
  CHECK(list[0].count == 4000);
}

TEST_CASE("diagnostics: the kept message does not depend on which thread raised first", "[diagnostics]") {
  // Each thread raises the same code with its own numbers, in a scheduling-dependent order.
  for (int run = 0; run < 5; ++run) {
    CapturedWarnings scope;
    std::vector<std::thread> threads;
    for (int t = 0; t < 6; ++t)
      threads.emplace_back([t] {
        for (int k = 0; k < 200; ++k) warn("test.instance", "instance " + std::to_string((t * 7 + k) % 10) + " is odd");
      });
    for (auto& th : threads) th.join();
    CHECK(scope.message("test.instance") == "instance 0 is odd");
    CHECK(scope.count("test.instance") == 1200);
  }
}

TEST_CASE("feather material: warnings are stored (version >= 2), version 1 files still read", "[diagnostics][material]") {
  FeatherMaterial m = small_material();
  m.warnings = "fit.near_zero_energy: lobe energy 1e-12 at 400 nm\nfit.poor_fit: rel. L2 0.8\n";
  const auto file = temp_file("warnings.plm");
  write_feather_material(file, m);
  const FeatherMaterial r = read_feather_material(file);
  CHECK(r.warnings == m.warnings);
  CHECK(r.nodes[3].*kMaterialFields[7] == m.nodes[3].*kMaterialFields[7]);

  // A version 1 file is the version 3 layout without the `warnings`, `key` and `key_text`
  // strings: build one from a version 3 file with all three empty (drop their 4-byte lengths,
  // set version 1, new checksum).
  m.warnings.clear();
  write_feather_material(file, m);
  std::string bytes = read_bytes(file);
  const std::size_t after_fidelity = 8 + 4 + (4 + m.label.size()) + (4 + m.config_hash.size()) + (4 + m.fidelity.size());
  for (int k = 0; k < 3; ++k) {
    std::uint32_t length = 99;
    std::memcpy(&length, bytes.data() + after_fidelity + 4 * k, 4);
    REQUIRE(length == 0);
  }
  bytes.erase(after_fidelity, 12);
  const std::uint32_t v1 = 1;
  std::memcpy(bytes.data() + 8, &v1, 4);
  bytes.resize(bytes.size() - 8);
  const std::uint64_t sum = fnv1a(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), 8);
  const auto old_file = temp_file("version1.plm");
  std::ofstream(old_file, std::ios::binary) << bytes;
  const FeatherMaterial old = read_feather_material(old_file);
  CHECK(old.warnings.empty());
  CHECK(old.label == m.label);
  CHECK(old.nodes[2].*kMaterialFields[5] == m.nodes[2].*kMaterialFields[5]);
  CHECK(old.noise.functions == m.noise.functions);
}

TEST_CASE("EXR: string attributes carry the run's warnings", "[diagnostics][image]") {
  LinearImage img(2, 2);
  const auto file = temp_file("warnings.exr");
  write_exr(img, file, nullptr, {{"plumage:warnings", "material.warnings: x.plm was characterised with warnings"}});
  const auto attributes = read_exr_string_attributes(file);
  REQUIRE(attributes.count("plumage:warnings") == 1);
  CHECK(attributes.at("plumage:warnings") == "material.warnings: x.plm was characterised with warnings");
}
