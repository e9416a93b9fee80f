// local_reflection "photonic_crystal": table file path, query rules through the plug-in, and the
// on-demand build + content-hash cache (one-entry table with the fdtd_periodic builder).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/diagnostics.hpp"
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
  const auto list = diagnostics().warnings();
  REQUIRE(list.size() == 2);
  CHECK(list[0].code == "fdtd.not_converged");
  CHECK(list[0].message == "table " + (dir / "warned.plt").string() + ": 3 of 8 fdtd runs stopped at the time cap");
  CHECK(list[1].code == "fdtd.other_orders");
  CHECK(captured.echoed("fdtd.other_orders"));
  fs::remove_all(dir);
}

TEST_CASE("photonic_crystal builds a table on demand and caches it", "[photonic-crystal][table]") {
  PluginRegistry registry;
  registry.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_photonic_crystal.so");
  registry.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_fdtd_periodic.so");
  PluginContext ctx = registry.context();
  ctx.config_dir = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "crystals";
  ctx.cache_dir = fs::temp_directory_path() / "plumage_test_pc_cache";
  fs::remove_all(ctx.cache_dir);
  const auto doc = ConfigDocument::parse(
      "crystal: mallard-green.yaml\n"
      "builder: {fidelity: preview, k_step_per_um: 0, resolution_nm: 19}\n"
      "lambda_nm: [545, 545]\nn_lambda: 1\nn_theta: 1\nn_phi: 1\n",
      "inline");
  auto model = registry.create_named<LocalReflection>("photonic_crystal", doc.root(), ctx);
  const JonesReflection r = model->reflect_one({545.0, {0.0, 0.0}, nullptr});
  CHECK(std::norm(r.ss) > 0.05);
  CHECK(std::norm(r.ss) < 0.5);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(ctx.cache_dir)) files += e.is_regular_file();
  CHECK(files == 1);
  // Second creation reads the cache (same answer, no new file).
  const auto doc2 = ConfigDocument::parse(
      "crystal: mallard-green.yaml\n"
      "builder: {fidelity: preview, k_step_per_um: 0, resolution_nm: 19}\n"
      "lambda_nm: [545, 545]\nn_lambda: 1\nn_theta: 1\nn_phi: 1\n",
      "inline");
  auto again = registry.create_named<LocalReflection>("photonic_crystal", doc2.root(), ctx);
  CHECK(again->reflect_one({545.0, {0.0, 0.0}, nullptr}).ss == r.ss);
  fs::remove_all(ctx.cache_dir);
}
