// local_reflection "photonic_crystal": table file path, query rules through the plug-in, and the
// explicit preparation step (issue 22): nothing is built or loaded before prepare(), reflect()
// before it throws naming the table, build + content-hash cache (one-entry table with the
// fdtd_periodic builder), `never` refusing by name, and the warnings prepare() raises.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <iostream>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/reflection_table.hpp"

using namespace plumage;
namespace fs = std::filesystem;

TEST_CASE("photonic_crystal reflection reads a table file", "[photonic-crystal][table]") {
  TableGrid g = TableGrid::uniform(400, 700, 3, 5, 6);
  ReflectionTable t(g, {"synthetic", 190.0, "", 10.0, "test", ""});
  for (std::size_t l = 0; l < 3; ++l)
    for (std::size_t i = 0; i < 5; ++i)
      for (std::size_t j = 0; j < 6; ++j)
        t.at(l, i, j) = {{-0.3 * g.cos_phi[j], 0.1}, {0.01 * l, 0.02}, {0.03, -0.01 * i}, {0.3, 0.05}};
  const fs::path dir = fs::temp_directory_path() / "plumage_test_pc_table";
  fs::create_directories(dir);
  t.save(dir / "syn.plt");

  PluginRegistry registry;
  registry.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_photonic_crystal.so");
  PluginContext ctx = registry.context();
  ctx.config_dir = dir;
  const auto doc = ConfigDocument::parse("table: syn.plt\n", "inline");
  auto model = registry.create_named<LocalReflection>("photonic_crystal", doc.root(), ctx);
  const LocalReflection::Request reqs[] = {{520.0, {0.3, 0.4}, nullptr},
                                           {520.0, {0.3, -0.4}, nullptr},
                                           {520.0, {0.3, kPi / 2}, nullptr},
                                           {520.0, {0.3, 2.0}, nullptr}};
  JonesReflection out[4];
  model->reflect(reqs, out);
  const JonesReflection q = t.query(520.0, 0.3, 0.4);
  CHECK(std::abs(out[0].ss - q.ss) < 1e-15);
  CHECK(std::abs(out[0].sp - q.sp) < 1e-15);
  CHECK(std::abs(out[1].sp + q.sp) < 1e-15);  // mirror
  CHECK(std::abs(out[1].pp - q.pp) < 1e-15);
  CHECK(out[2].ss == Complex(-1.0, 0.0));      // grazing
  CHECK(out[2].pp == Complex(-1.0, 0.0));
  CHECK(out[3].ss == Complex(0.0, 0.0));       // back-facing
  fs::remove_all(dir);
}

TEST_CASE("photonic_crystal passes a table's warnings on to the run that uses it", "[photonic-crystal][table][warnings]") {
  TableGrid g = TableGrid::uniform(400, 700, 2, 2, 2);
  // Notes as fdtd_periodic writes them: plain counts, then "WARNING: <text> [<code>]" items.
  ReflectionTable t(g, {"synthetic", 190.0, "", 10.0, "test",
                        "fdtd runs: 8; entries continued to the grazing limit: 0 of 8; WARNING: 3 of 8 fdtd runs "
                        "stopped at the time cap [fdtd.not_converged]; WARNING: 2 samples with other propagating "
                        "diffraction orders [fdtd.other_orders]"});
  const fs::path dir = fs::temp_directory_path() / "plumage_test_pc_table_warnings";
  fs::create_directories(dir);
  t.save(dir / "warned.plt");
  PluginRegistry registry;
  registry.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_photonic_crystal.so");
  PluginContext ctx = registry.context();
  ctx.config_dir = dir;
  CapturedWarnings captured;
  const auto doc = ConfigDocument::parse("table: warned.plt\n", "inline");
  auto model = registry.create_named<LocalReflection>("photonic_crystal", doc.root(), ctx);
  CHECK(model->pending_preparation().empty());  // a given table file is loaded on creation
  CHECK(diagnostics().empty());                 // its warnings come with the preparation step
  model->prepare({});
  const auto list = diagnostics().warnings();
  REQUIRE(list.size() == 2);
  CHECK(list[0].code == "fdtd.not_converged");
  CHECK(list[0].message == "table " + (dir / "warned.plt").string() + ": 3 of 8 fdtd runs stopped at the time cap");
  CHECK(list[1].code == "fdtd.other_orders");
  CHECK(captured.echoed("fdtd.other_orders"));
  fs::remove_all(dir);
}

namespace {

// A one-entry mallard-green table at preview fidelity without the Bloch-k grid: seconds to build.
constexpr const char* kOneEntry =
    "crystal: mallard-green.yaml\n"
    "builder: {fidelity: preview, k_step_per_um: 0, resolution_nm: 19}\n"
    "lambda_nm: [545, 545]\nn_lambda: 1\nn_theta: 1\nn_phi: 1\n";

struct CrystalFixture {
  PluginRegistry registry;
  PluginContext ctx;
  explicit CrystalFixture(const std::string& cache) {
    registry.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_photonic_crystal.so");
    registry.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_fdtd_periodic.so");
    ctx = registry.context();
    ctx.config_dir = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "crystals";
    ctx.cache_dir = fs::temp_directory_path() / cache;
    fs::remove_all(ctx.cache_dir);
  }
  ~CrystalFixture() { fs::remove_all(ctx.cache_dir); }
  std::unique_ptr<LocalReflection> create(const std::string& yaml) const {
    const auto doc = ConfigDocument::parse(yaml, "inline");
    return registry.create_named<LocalReflection>("photonic_crystal", doc.root(), ctx);
  }
  std::size_t cached_files() const {
    std::size_t files = 0;
    if (!fs::exists(ctx.cache_dir)) return 0;
    for (const auto& e : fs::recursive_directory_iterator(ctx.cache_dir)) files += e.is_regular_file();
    return files;
  }
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("photonic_crystal builds its table in the preparation step and caches it", "[photonic-crystal][table][prepare]") {
  CrystalFixture f("plumage_test_pc_cache");
  auto model = f.create(kOneEntry);
  // Creating the model builds and loads nothing; it says what the preparation step would do.
  CHECK(f.cached_files() == 0);
  const std::string pending = model->pending_preparation();
  CHECK_THAT(pending, Catch::StartsWith("build the reflection table of mallard-green (1 x 1 x 1 entries) into ") &&
                          Catch::Contains((f.ctx.cache_dir / "tables").string()));
  // reflect() before prepare() refuses, naming the table and the step.
  CHECK_THAT(error_of([&] { model->reflect_one({545.0, {0.0, 0.0}, nullptr}); }),
             Catch::Contains("mallard-green (1 x 1 x 1 entries)") && Catch::Contains("not prepared"));
  std::vector<std::string> lines;
  PreparationOptions options;
  options.progress = [&](std::size_t, std::size_t total, std::string_view what) {
    if (total == 0) lines.emplace_back(what);
  };
  model->prepare(options);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0], Catch::Contains("building the reflection table of mallard-green"));
  CHECK(model->pending_preparation().empty());
  const JonesReflection r = model->reflect_one({545.0, {0.0, 0.0}, nullptr});
  CHECK(std::norm(r.ss) > 0.05);
  CHECK(std::norm(r.ss) < 0.5);
  CHECK(f.cached_files() == 1);
  model->prepare(options);  // idempotent: nothing built again
  CHECK(lines.size() == 1);
  // A second model of the same request loads the cached table (same answer, no new file), also
  // when building is refused.
  auto again = f.create(kOneEntry);
  CHECK_THAT(again->pending_preparation(), Catch::StartsWith("load the reflection table of mallard-green"));
  again->prepare({PreparationOptions::Tables::never, {}});
  CHECK(again->reflect_one({545.0, {0.0, 0.0}, nullptr}).ss == r.ss);
  CHECK(f.cached_files() == 1);
}

TEST_CASE("photonic_crystal: tables never refuses to build, naming the table and the command", "[photonic-crystal][table][prepare]") {
  CrystalFixture f("plumage_test_pc_never");
  auto model = f.create(kOneEntry);
  const std::string message = error_of([&] { model->prepare({PreparationOptions::Tables::never, {}}); });
  CHECK_THAT(message, Catch::Contains("mallard-green (1 x 1 x 1 entries)") &&
                          Catch::Contains((f.ctx.cache_dir / "tables").string()) &&
                          Catch::Contains("--tables build"));
  CHECK(f.cached_files() == 0);
  CHECK_FALSE(model->pending_preparation().empty());  // still to do
}

TEST_CASE("photonic_crystal: the preview option is used only for larger tables", "[photonic-crystal][table][prepare]") {
  // A table no larger than the preview grid (4 x 5 x 5) is built as asked: no preview warning.
  CrystalFixture f("plumage_test_pc_small");
  CapturedWarnings captured;
  auto model = f.create(kOneEntry);
  model->prepare({PreparationOptions::Tables::preview, {}});
  CHECK_FALSE(captured.echoed("photonic_crystal.preview_table"));
  CHECK(f.cached_files() == 1);
}

TEST_CASE("photonic_crystal: the preview option puts the preview table in place of a larger one, with a warning", "[photonic-crystal][table][prepare]") {
  CrystalFixture f("plumage_test_pc_preview");
  // 5 x 5 x 5 entries: larger than the 4 x 5 x 5 preview grid.
  const std::string request =
      "crystal: mallard-green.yaml\nlambda_nm: [500, 600]\nn_lambda: 5\nn_theta: 5\nn_phi: 5\n";
  // A synthetic preview table where the preview table is cached (docs/formats.md: key = FNV-1a of
  // the crystal file's bytes, the builder, its preview fidelity and the preview grid), so that no
  // FDTD runs here.
  std::ifstream in(f.ctx.config_dir / "mallard-green.yaml", std::ios::binary);
  const std::string crystal_bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string key =
      "crystal=" + fnv1a_hex(crystal_bytes) + ";builder=fdtd_periodic;fidelity{preview};grid=500,600,4,5,5";
  const fs::path preview_file = f.ctx.cache_dir / "tables" / ("mallard-green-preview-" + fnv1a_hex(key) + ".plt");
  const TableGrid g = TableGrid::uniform(500, 600, 4, 5, 5);
  ReflectionTable t(g, {"mallard-green", 170.0, "", 15.0, "test", "WARNING: synthetic entries [test.synthetic]"});
  for (std::size_t l = 0; l < 4; ++l)
    for (std::size_t i = 0; i < 5; ++i)
      for (std::size_t j = 0; j < 5; ++j) t.at(l, i, j) = {{0.3, 0.01 * l}, {0.0, 0.0}, {0.0, 0.0}, {0.2, 0.0}};
  fs::create_directories(preview_file.parent_path());
  t.save(preview_file);

  CapturedWarnings captured;
  auto model = f.create(request);
  CHECK_THAT(model->pending_preparation(),
             Catch::StartsWith("build the reflection table of mallard-green (5 x 5 x 5 entries)"));
  model->prepare({PreparationOptions::Tables::preview, {}});
  CHECK(f.cached_files() == 1);  // nothing built: the cached preview table serves
  CHECK(captured.count("photonic_crystal.preview_table") == 1);
  CHECK_THAT(captured.message("photonic_crystal.preview_table"),
             Catch::Contains(preview_file.string()) && Catch::Contains("mallard-green (5 x 5 x 5 entries)") &&
                 Catch::Contains("tables = preview"));
  CHECK(captured.count("test.synthetic") == 1);  // the table's own warnings come along
  const LocalReflection::Request r{550.0, {0.2, 0.1}, nullptr};
  CHECK(model->reflect_one(r).ss == t.query(550.0, r.incidence).ss);
  // Every preparation raises them again, so each run (and file) made with the shortcut says so.
  model->prepare({PreparationOptions::Tables::preview, {}});
  CHECK(captured.count("photonic_crystal.preview_table") == 2);
  // Without the shortcut the preview table is not used: never refuses (the full table is missing).
  auto strict = f.create(request);
  CHECK_THAT(error_of([&] { strict->prepare({PreparationOptions::Tables::never, {}}); }),
             Catch::Contains("mallard-green (5 x 5 x 5 entries)") && Catch::Contains("never"));
}
