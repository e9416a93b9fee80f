// The plug-in's parameters (issue 22): one declaration each — the builder's table, a crystal
// file's `fdtd_periodic:` section read by the builder (not by core), the ladder's and the
// benchmark's tables — and the thread count not changing any number.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "builder_params.hpp"
#include "layered_cell.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/table_builder.hpp"
#include "table_build.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

fs::path crystal_file(const std::string& name) {
  return fs::path(PLUMAGE_SOURCE_DIR) / "configs/crystals" / (name + ".yaml");
}

// mallard-green's cell with `extra` appended inside its `crystal:` map, as a temporary file.
fs::path write_crystal(const std::string& file, const std::string& extra) {
  std::ifstream in(crystal_file("mallard-green"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const fs::path path = fs::temp_directory_path() / file;
  std::ofstream(path) << text << extra;
  return path;
}

PluginRegistry& registry() {
  static PluginRegistry r = [] {
    PluginRegistry reg;
    reg.load_library(fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_fdtd_periodic.so");
    return reg;
  }();
  return r;
}

std::vector<std::string> names_of(const std::vector<ParamSpec>& specs) {
  std::vector<std::string> out;
  for (const auto& s : specs) out.push_back(s.name);
  return out;
}

}  // namespace

TEST_CASE("builder parameters: one table drives the defaults, the reads and the plug-in's description",
          "[fdtd-table][params]") {
  const fdtd_table::BuilderParams d = fdtd_table::builder_params().defaults();
  CHECK(d.fidelity == fdtd_table::BuilderParams::Fidelity::production);
  CHECK(!d.resolution_nm);
  CHECK(!d.k_step_per_um);
  CHECK(d.threads == 2);
  CHECK(d.pml_cells == 24);
  CHECK(d.kz_min == 0.25);
  CHECK(d.dft_tol == 3e-4);
  CHECK(d.courant == 0.95);
  CHECK(d.smoothing);
  CHECK(!d.dispersion_correction);
  CHECK(!d.exact_fill);
  CHECK(!d.grazing_anchors);
  CHECK(d.substrate_below_um == 0.30);
  CHECK(d.air_above_um == 0.30);
  CHECK(d.checkpoint.empty());
  // The plug-in describes exactly the table it reads.
  const auto* entry = registry().find(TableBuilder::plugin_kind, "fdtd_periodic");
  REQUIRE(entry);
  CHECK(names_of(entry->info.params) == names_of(fdtd_table::builder_params().specs()));
  // Every declared parameter is read (a config giving all of them is accepted by the registry,
  // which refuses a read the table does not declare, and each key is marked known).
  const ConfigDocument doc = ConfigDocument::parse(
      "fidelity: preview\nresolution_nm: 19\nk_step_per_um: 0\nthreads: 1\npml_cells: 20\nkz_min: 0.3\n"
      "grazing_anchors: 3\ndft_tol: 1e-3\ncourant: 0.9\nsmoothing: false\ndispersion_correction: true\n"
      "exact_fill: true\nsubstrate_below_um: 0.2\nair_above_um: 0.25\ncheckpoint: x.partial\n",
      "builder.yaml");
  CHECK_NOTHROW(registry().create_named<TableBuilder>("fdtd_periodic", doc.root(), registry().context()));
  const fdtd_table::BuilderParams p = fdtd_table::builder_params().read(doc.root());
  for (const auto& name : fdtd_table::builder_params().names()) {
    INFO(name);
    const auto known = doc.root().known_keys();
    CHECK(std::find(known.begin(), known.end(), name) != known.end());
  }
  CHECK(p.fidelity == fdtd_table::BuilderParams::Fidelity::preview);
  CHECK(*p.resolution_nm == 19.0);
  CHECK(*p.k_step_per_um == 0.0);
  CHECK(*p.grazing_anchors == 3);
  CHECK(*p.dispersion_correction);
  CHECK(!p.smoothing);
  CHECK(p.checkpoint == "x.partial");
  // Ranges from the table: a ConfigError naming the field.
  const ConfigDocument bad = ConfigDocument::parse("grazing_anchors: 7\n", "builder.yaml");
  CHECK_THROWS_AS(registry().create_named<TableBuilder>("fdtd_periodic", bad.root(), registry().context()),
                  ConfigError);
  // The ladder and the benchmark describe their own tables.
  const auto* ladder = registry().find("accuracy_ladder", "fdtd_periodic");
  REQUIRE(ladder);
  CHECK(names_of(ladder->info.params) == std::vector<std::string>{"crystal"});
  const auto* bench = registry().find(Benchmark::plugin_kind, "fdtd");
  REQUIRE(bench);
  CHECK(names_of(bench->info.params) ==
        std::vector<std::string>{"config", "n_lambda", "n_theta", "n_phi", "kz_min", "skip_table", "out"});
}

TEST_CASE("crystal sections: the builder reads its own fdtd_periodic section, core keeps it unread",
          "[fdtd-table][params]") {
  // The shipped numerics, as the former `fdtd:` maps gave them (NOTES.md §3a, §5a).
  for (const auto& e : fs::directory_iterator(fs::path(PLUMAGE_SOURCE_DIR) / "configs/crystals")) {
    const CrystalCell cc = load_crystal_cell(e.path());
    INFO(cc.name);
    const fdtd_table::CrystalNumerics n = fdtd_table::crystal_numerics(cc);
    const bool magpie = cc.name.rfind("magpie", 0) == 0, peacock = cc.name.rfind("peacock", 0) == 0;
    CHECK(n.grazing_anchors == (magpie || peacock ? 3 : 2));
    CHECK(n.dispersion_correction == peacock);
    CHECK(n.exact_fill == peacock);
    CHECK(n.resolution_nm.has_value() == (cc.name == "peacock-cyan"));
    CHECK(n.k_step_per_um.has_value() == magpie);  // thin shells: 0.25/µm (rcwa NOTES.md §4)
    CHECK(cc.builder_sections.size() == (magpie || peacock ? 1u : 0u));
  }
  CHECK(*fdtd_table::crystal_numerics(load_crystal_cell(crystal_file("peacock-cyan"))).resolution_nm == 7.6);
  // What a build runs: grid step by fidelity and the crystal's numerics in the producer text.
  const CrystalCell mallard = load_crystal_cell(crystal_file("mallard-green"));
  fdtd_table::BuilderParams preview = fdtd_table::builder_params().defaults();
  preview.fidelity = fdtd_table::BuilderParams::Fidelity::preview;
  const auto plan = fdtd_table::plan_build(preview, mallard);
  CHECK(plan.options.nx == 13);  // round(190 / 15)
  CHECK(plan.options.k_step_per_um == 1.0);
  CHECK(plan.meta.producer ==
        "plumage fdtd_periodic 1.0.0 fidelity=preview nx=13 k_step=1.000000 engine=3 (bilinear Lorentz ADE, "
        "exact_fill off, dispersion_correction off) grazing_anchors=2");
  const auto peacock = fdtd_table::plan_build(fdtd_table::builder_params().defaults(),
                                              load_crystal_cell(crystal_file("peacock-cyan")));
  CHECK(peacock.options.nx == 21);  // round(160 / 7.6)
  CHECK(peacock.options.sim.exact_fill);
  CHECK(peacock.options.grazing_anchors == 3);
  CHECK(peacock.options.k_step_per_um == 0.5);
  // The crystal's Bloch-k step applies at production only; an explicit builder option wins.
  const CrystalCell magpie = load_crystal_cell(crystal_file("magpie-blue"));
  CHECK(fdtd_table::plan_build(fdtd_table::builder_params().defaults(), magpie).options.k_step_per_um == 0.25);
  CHECK(fdtd_table::plan_build(preview, magpie).options.k_step_per_um == 1.0);
  fdtd_table::BuilderParams explicit_step = fdtd_table::builder_params().defaults();
  explicit_step.k_step_per_um = 0.5;
  CHECK(fdtd_table::plan_build(explicit_step, magpie).options.k_step_per_um == 0.5);

  auto builder = registry().create_named<TableBuilder>("fdtd_periodic", ParamView{}, registry().context());
  {  // a typo inside the section: the builder's table reports it at its line
    const CrystalCell cc = load_crystal_cell(write_crystal("typo_section.yaml", "  fdtd_periodic: {exact_fil: true}\n"));
    try {
      builder->check_cell(cc);
      FAIL("typo accepted");
    } catch (const ConfigError& e) {
      std::printf("[params] %s\n", e.what());
      CHECK(e.mark().file.find("typo_section.yaml") != std::string::npos);
      CHECK(e.mark().line > 0);
      CHECK(std::string(e.what()).find("exact_fill") != std::string::npos);  // the nearest valid name
    }
    CHECK_THROWS_AS(builder->build(cc, TableGrid::uniform(500, 500, 1, 1, 1), {}), ConfigError);
  }
  {  // a section of no registered builder is reported by check_builder_sections, naming it
    const CrystalCell cc = load_crystal_cell(write_crystal("old_section.yaml", "  fdtd: {grazing_anchors: 3}\n"));
    CHECK(cc.builder_sections.count("fdtd") == 1);
    try {
      check_builder_sections(cc, registry());
      FAIL("unknown builder section accepted");
    } catch (const ConfigError& e) {
      std::printf("[params] %s\n", e.what());
      CHECK(std::string(e.what()).find("no table_builder 'fdtd'") != std::string::npos);
      CHECK(std::string(e.what()).find("fdtd_periodic") != std::string::npos);  // the registered ones
    }
  }
  {  // a valid section passes; an out-of-range value does not
    const CrystalCell ok = load_crystal_cell(write_crystal("ok_section.yaml", "  fdtd_periodic: {grazing_anchors: 3}\n"));
    CHECK(check_builder_sections(ok, registry()) == std::vector<std::string>{"fdtd_periodic"});
    const CrystalCell range =
        load_crystal_cell(write_crystal("range_section.yaml", "  fdtd_periodic: {grazing_anchors: 9}\n"));
    CHECK_THROWS_AS(check_builder_sections(range, registry()), ConfigError);
  }
  // A map one typo away from a cell field is the typo, not a builder section.
  CHECK_THROWS_WITH(load_crystal_cell(write_crystal("typo_field.yaml", "  materails: {rod: melanin}\n")),
                    Catch::Contains("did you mean 'materials'"));
}

TEST_CASE("runs do not depend on the thread count", "[fdtd-table][threads]") {
  const fdtd::Cell cell = fdtd_reference::layered_cell(0.02, 2, -1.0);
  std::vector<double> omegas;
  for (double l = 0.40; l <= 0.7001; l += 0.05) omegas.push_back(2 * fdtd::kPi / l);
  fdtd::SimParams p;
  p.nx = 2;
  const std::vector<fdtd::Job> jobs = {{0.0, 0.0}, {-4.0, -2.0}, {-8.0, 3.0}};
  const auto one = fdtd::run_batch(cell, jobs, omegas, p, 1);
  const auto two = fdtd::run_batch(cell, jobs, omegas, p, 2);
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    CHECK(one[j].kx == jobs[j].kx);
    CHECK(one[j].stats.steps == two[j].stats.steps);
    for (std::size_t f = 0; f < omegas.size(); ++f)
      for (int q = 0; q < 2; ++q) {
        CHECK(one[j].freqs[f].R[q] == two[j].freqs[f].R[q]);
        for (int c = 0; c < 3; ++c) CHECK(one[j].freqs[f].E[q][c] == two[j].freqs[f].E[q][c]);
      }
  }
}

TEST_CASE("benchmark fdtd: the single solve and the broadband run, recorded as section fdtd", "[fdtd-table][bench]") {
  const ConfigDocument doc = ConfigDocument::parse(
      "config: \"" + crystal_file("mallard-green").string() + "\"\nskip_table: true\n", "command line");
  auto bench = registry().create_named<Benchmark>("fdtd", doc.root(), registry().context());
  std::vector<std::string> lines;
  Benchmark::Options options;
  options.command = "plumage bench fdtd --skip-table";
  options.progress = [&](std::string_view line) { lines.emplace_back(line); };
  const Benchmark::Report report = bench->run(options);
  std::printf("[bench] %s", report.markdown.c_str());
  CHECK(report.id == "fdtd");
  CHECK(report.markdown.rfind("## fdtd\n", 0) == 0);
  CHECK(report.markdown.find("| `plumage bench fdtd --skip-table` |") != std::string::npos);
  CHECK(report.markdown.find("single solve (1 lambda, 1 angle, 2 pols)") != std::string::npos);
  CHECK(report.markdown.find("fdtd runs: 1;") != std::string::npos);
  CHECK(report.markdown.find("| 4 runs timed |") != std::string::npos);
  CHECK(report.markdown.find("table 50 x 20") == std::string::npos);
  CHECK(!lines.empty());
}
