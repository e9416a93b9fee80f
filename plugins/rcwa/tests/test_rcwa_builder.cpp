// The rcwa table_builder through the plug-in registry: its parameters, presets and range errors,
// a small table in the (s, p) basis with the FDTD's query rules, the rcwa.other_orders warning,
// and the memory estimate.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "builder.hpp"

#include "plumage/config_document.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/table_builder.hpp"
#include "test_registry.hpp"

using namespace plumage;
using plumage::testing::registry;

namespace {

CrystalCell mallard() {
  return load_crystal_cell(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
}

}  // namespace

TEST_CASE("rcwa builder: registered with its parameter table; bad values are ConfigErrors", "[rcwa]") {
  const auto* entry = registry().find("table_builder", "rcwa");
  REQUIRE(entry);
  std::vector<std::string> names;
  for (const auto& s : entry->info.params) names.push_back(s.name);
  CHECK(names == std::vector<std::string>{"fidelity", "harmonics", "slices_per_row", "li_rule", "richardson", "threads"});
  const ConfigDocument all = ConfigDocument::parse(
      "fidelity: preview\nharmonics: 4\nslices_per_row: 5\nli_rule: false\nrichardson: true\nthreads: 1\n", "builder.yaml");
  CHECK_NOTHROW(registry().create_named<TableBuilder>("rcwa", all.root(), registry().context()));
  const ConfigDocument bad = ConfigDocument::parse("harmonics: 99\n", "builder.yaml");
  CHECK_THROWS_AS(registry().create_named<TableBuilder>("rcwa", bad.root(), registry().context()), ConfigError);
  CHECK(registry().find("accuracy_ladder", "rcwa"));
}

TEST_CASE("rcwa builder: a small table, its memory estimate and the other-orders warning", "[rcwa]") {
  const ConfigDocument doc = ConfigDocument::parse("fidelity: preview\nthreads: 2\n", "builder.yaml");
  auto builder = registry().create_named<TableBuilder>("rcwa", doc.root(), registry().context());
  CrystalCell cell = mallard();
  const TableGrid grid = TableGrid::uniform(450, 650, 3, 2, 2);
  const MemoryEstimate e = builder->estimate_memory(cell, grid);
  CHECK(e.total_bytes() > 0.0);
  CHECK(e.total_bytes() < 64.0 * 1024 * 1024);
  diagnostics().clear();
  const ReflectionTable t = builder->build(cell, grid, {});
  CHECK(t.metadata().producer.find("rcwa") != std::string::npos);
  for (const JonesReflection& j : t.entries()) {
    CHECK(largest_singular_value(j) <= 1.0 + 1e-12);  // passive
    CHECK(largest_singular_value(j) > 0.01);
  }
  // Normal incidence of a mirror-symmetric cell: no s-p coupling.
  const JonesReflection n = t.at(1, 1, 1);
  CHECK(std::abs(n.sp) < 1e-10);
  CHECK(std::abs(n.ps) < 1e-10);
  // 190 nm period at 450-650 nm: a second order never propagates at these angles.
  const auto w = diagnostics().warnings();
  CHECK(std::none_of(w.begin(), w.end(), [](const Warning& x) { return x.code == "rcwa.other_orders"; }));
  // A 400 nm period at 450 nm and grazing cos(phi) = 0.5: order -1 propagates.
  cell.a_x_nm = 400;
  diagnostics().clear();
  const ReflectionTable wide = builder->build(cell, grid, {});
  const auto w2 = diagnostics().warnings();
  CHECK(std::any_of(w2.begin(), w2.end(), [](const Warning& x) { return x.code == "rcwa.other_orders"; }));
  CHECK(wide.metadata().notes.find("[rcwa.other_orders]") != std::string::npos);
}

TEST_CASE("rcwa builder: a crystal's rcwa: section sets its production settings", "[rcwa]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("plumage-test-rcwa-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string base = std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml";
  std::ifstream in(base);
  const std::string yaml((std::istreambuf_iterator<char>(in)), {});
  auto with_section = [&](const std::string& name, const std::string& section) {
    const fs::path p = dir / name;
    std::ofstream(p) << yaml << "  rcwa: " << section << "\n";
    return load_crystal_cell(p.string());
  };
  const CrystalCell cell = with_section("good.yaml", "{harmonics: 7, slices_per_row: 24}");
  const rcwa::CellSettings c = rcwa::cell_settings(cell);
  rcwa::BuilderParams production, preview, explicit_options;
  preview.fidelity = rcwa::BuilderParams::Fidelity::preview;
  explicit_options.harmonics = 4;
  CHECK(rcwa::build_settings(production, c).solver.harmonics == 7);
  CHECK(rcwa::build_settings(production, c).slices_per_row == 24);
  CHECK(rcwa::build_settings(preview, c).solver.harmonics == 3);  // preview keeps its preset
  CHECK(rcwa::build_settings(explicit_options, c).solver.harmonics == 4);  // builder options win
  CHECK(rcwa::build_settings(production, rcwa::cell_settings(mallard())).solver.harmonics == 5);
  const auto* entry = registry().find("table_builder", "rcwa");
  REQUIRE(entry);
  auto builder = registry().create_named<TableBuilder>("rcwa", ConfigDocument::parse("{}", "b.yaml").root(),
                                                       registry().context());
  CHECK_NOTHROW(builder->check_cell(cell));
  CHECK_THROWS_AS(builder->check_cell(with_section("bad.yaml", "{harmonic: 7}")), ConfigError);
  CHECK_THROWS_AS(builder->check_cell(with_section("range.yaml", "{slices_per_row: 999}")), ConfigError);
  fs::remove_all(dir);
}

TEST_CASE("rcwa builder: the same bits on 1 and 2 threads (per-thread wavelength setups)", "[rcwa]") {
  const CrystalCell cell = mallard();
  const TableGrid grid = TableGrid::uniform(450, 650, 3, 3, 4);
  auto table = [&](int threads) {
    const ConfigDocument doc = ConfigDocument::parse(
        "fidelity: preview\nrichardson: true\nthreads: " + std::to_string(threads) + "\n", "builder.yaml");
    return registry().create_named<TableBuilder>("rcwa", doc.root(), registry().context())->build(cell, grid, {});
  };
  const ReflectionTable one = table(1), two = table(2);
  REQUIRE(one.entries().size() == two.entries().size());
  for (std::size_t i = 0; i < one.entries().size(); ++i) {
    const JonesReflection &a = one.entries()[i], &b = two.entries()[i];
    CAPTURE(i);
    CHECK((a.ss == b.ss && a.sp == b.sp && a.ps == b.ps && a.pp == b.pp));
  }
}
