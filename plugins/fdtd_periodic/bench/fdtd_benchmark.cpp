#include "fdtd_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>

#include "builder_params.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/config_document.hpp"
#include "plumage/conventions.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/table_build.hpp"
#include "table_build.hpp"

namespace plumage::fdtd_table {

namespace {

struct Timed {
  double wall = 0, cpu = 0;  // wall and process CPU seconds
  std::size_t runs = 0;
  std::string notes;
  ReflectionTable table;
};

// One build with the builder's production defaults changed by `edit`, timed.
template <class Edit>
Timed timed_build(const CrystalCell& cell, const TableGrid& grid, Edit edit, const TableBuilder::Progress& progress) {
  BuilderParams params = builder_params().defaults();
  edit(params);
  const BuildPlan plan = plan_build(params, cell);
  BuildStats stats;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  Timed r;
  r.table = build_table([&cell](double lambda_um) { return cell_from_crystal(cell, lambda_um); }, cell.a_x_nm * 1e-3,
                        grid, plan.meta, plan.options, progress, &stats);
  r.cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.runs = stats.runs + stats.resumed_runs;
  r.notes = r.table.metadata().notes + "; resolution " + std::to_string(r.table.metadata().resolution_nm) + " nm";
  return r;
}

// A status line at every tenth of the work.
TableBuilder::Progress tenths(const Benchmark::Options& options) {
  if (!options.progress) return {};
  return [progress = options.progress, last = std::size_t(0)](std::size_t done, std::size_t total,
                                                              std::string_view what) mutable {
    const std::size_t tenth = total > 0 ? 10 * done / total : 10;
    if (tenth <= last) return;
    last = tenth;
    progress(std::string(what) + ": " + std::to_string(done) + " of " + std::to_string(total));
  };
}

}  // namespace

const ParamTable<BenchParams>& bench_params() {
  using B = BenchParams;
  static const auto table =
      ParamTable<B>{}
          .text("config", &B::config, "configs/crystals/mallard-green.yaml", "crystal config")
          .integer("n_lambda", &B::n_lambda, "1", kProductionTableGrid.n_lambda, Limits::closed(1, 1000),
                   "table wavelengths (the production grid's)")
          .integer("n_theta", &B::n_theta, "1", kProductionTableGrid.n_theta, Limits::closed(1, 1000),
                   "table cos theta nodes")
          .integer("n_phi", &B::n_phi, "1", kProductionTableGrid.n_phi, Limits::closed(1, 1000), "table cos phi nodes")
          .number("kz_min", &B::kz_min, "1", 0.25, Limits::closed(0.01, 0.9),
                  "table entries with cos(theta)cos(phi) below this are continued to the grazing limit (impedance "
                  "form), not simulated")
          .boolean("skip_table", &B::skip_table, false, "only the single solve and the broadband run")
          .text("out", &B::out, "",
                "also save the whole table to this file (.plt), e.g. the lazy cache's "
                "build/cache/tables/<crystal>-<key>.plt");
  return table;
}

Benchmark::Report FdtdBenchmark::run(const Options& options) const {
  const BenchParams& b = params_;
  const CrystalCell cell = load_crystal_cell(b.config);
  TableGrid one;
  one.lambda_nm = {550};
  one.cos_theta = {std::cos(deg_to_rad(30))};
  one.cos_phi = {std::cos(deg_to_rad(20))};
  // One (λ, angle) entry, both polarizations: a single run at exact ε(550 nm).
  const Timed single = timed_build(cell, one, [](BuilderParams& p) { p.k_step_per_um = 0.0, p.threads = 1; }, {});
  // Broadband runs at fixed Bloch k (the production path): the four k-grid corners of one entry.
  const Timed broad = timed_build(cell, one, [](BuilderParams& p) { p.threads = 1; }, {});
  const std::size_t broad_count = std::max<std::size_t>(1, broad.runs);
  const double broad_runs = static_cast<double>(broad_count);
  std::ostringstream md;
  md << std::fixed << std::setprecision(2);
  md << "## fdtd\n\n"
     << "Periodic 2.5D FDTD table builder (`table_builder` fdtd_periodic, production fidelity: "
        "10 nm target grid, Bloch-k step 0.5/um, both polarizations per run). `single solve`: one "
        "(550 nm, theta 30 deg, phi 20 deg) entry with exact eps(lambda), one thread. `broadband "
        "run`: one fixed-Bloch-k run returning every table wavelength, one thread (mean of the "
        "four k-grid corners of that entry). `table`: the whole table on 2 threads. Wall and "
        "process CPU seconds.\n\n"
     << "| machine | command | date | crystal | item | wall s | CPU s | notes | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  const std::string head = "| " + machine_description() + " | `" + options.command + "` | " + today_iso() + " | " + cell.name;
  md << head << " | single solve (1 lambda, 1 angle, 2 pols) | " << single.wall << " | " << single.cpu << " | "
     << single.notes << " | - |\n";
  md << head << " | broadband run (all lambda, 1 Bloch k) | " << broad.wall / broad_runs << " | "
     << broad.cpu / broad_runs << " | " << broad_count << " runs timed | - |\n";
  if (options.progress) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(2) << "single solve: " << single.wall << " s wall, " << single.cpu
         << " s CPU; broadband run: " << broad.wall / broad_runs << " s wall, " << broad.cpu / broad_runs
         << " s CPU (mean of " << broad_count << ")";
    options.progress(line.str());
  }
  if (!b.skip_table) {
    const TableGrid grid = TableGrid::uniform(400, 700, b.n_lambda, b.n_theta, b.n_phi);
    const Timed full = timed_build(cell, grid, [&](BuilderParams& p) { p.kz_min = b.kz_min; }, tenths(options));
    std::ostringstream item;
    item << "table " << b.n_lambda << " x " << b.n_theta << " x " << b.n_phi << " x 2 pols, kz_min " << b.kz_min;
    md << head << " | " << item.str() << " | " << full.wall << " | " << full.cpu << " | " << full.notes
       << " | <= 900 s |\n";
    if (!b.out.empty()) {
      // The same table the photonic_crystal plug-in builds on demand (same builder, grid and
      // defaults), with the crystal file's content hash as the lazy cache stores it.
      ReflectionTable t = full.table;
      std::ifstream in(b.config, std::ios::binary);
      t.metadata().config_hash = fnv1a_hex(std::string(std::istreambuf_iterator<char>(in), {}));
      create_output_directory(std::filesystem::absolute(b.out).parent_path());
      t.save(b.out);
      if (options.progress) options.progress("wrote " + b.out);
    }
  }
  return {"fdtd", md.str()};
}

}  // namespace plumage::fdtd_table
