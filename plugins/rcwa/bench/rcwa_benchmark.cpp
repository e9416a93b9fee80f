#include "rcwa_benchmark.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <sstream>

#include "builder.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/table_build.hpp"

namespace plumage::rcwa {

namespace {

struct Timed {
  double wall = 0, cpu = 0;  // wall and process CPU seconds
};

template <class Work>
Timed timed(Work work) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  work();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
          static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC};
}

int or_default(int v, int d) { return v > 0 ? v : d; }

}  // namespace

const ParamTable<BenchParams>& bench_params() {
  using B = BenchParams;
  static const auto table =
      ParamTable<B>{}
          .text("config", &B::config, "configs/crystals/mallard-green.yaml", "crystal config")
          .integer("n_lambda", &B::n_lambda, "1", 0, Limits::closed(0, 1000), "table wavelengths; 0: the production grid")
          .integer("n_theta", &B::n_theta, "1", 0, Limits::closed(0, 1000), "table cos theta nodes; 0: the production grid")
          .integer("n_phi", &B::n_phi, "1", 0, Limits::closed(0, 1000), "table cos phi nodes; 0: the production grid")
          .integer("threads", &B::threads, "1", 2, Limits::closed(1, 64), "worker threads of the table build")
          .integer("harmonics", &B::harmonics, "1", 0, Limits::closed(0, 60),
                   "the builder's harmonics option; 0: the cell's production setting")
          .integer("slices_per_row", &B::slices_per_row, "1", 0, Limits::closed(0, 200),
                   "the builder's slices_per_row option; 0: the cell's production setting")
          .boolean("skip_table", &B::skip_table, false, "only the single-entry timing");
  return table;
}

Benchmark::Report RcwaBenchmark::run(const Options& options) const {
  const BenchParams& b = params_;
  const CrystalCell cell = load_crystal_cell(b.config);
  BuilderParams single_params;
  single_params.threads = 1;
  single_params.harmonics = b.harmonics;
  single_params.slices_per_row = b.slices_per_row;
  // Single entries: one λ row of the production angle grid (20 x 50 entries, 1 thread), so the
  // mean covers normal to grazing incidence.
  const TableGrid row = TableGrid::uniform(550, 550, 1, kProductionTableGrid.n_theta, kProductionTableGrid.n_phi);
  const Timed one = timed([&] { RcwaTableBuilder(single_params).build(cell, row, {}); });
  const std::size_t n_row = row.cos_theta.size() * row.cos_phi.size();
  const double entries_row = static_cast<double>(n_row);
  const BuildSettings s = build_settings(single_params, cell_settings(cell));
  std::ostringstream settings;
  settings << "orders -" << s.solver.harmonics << "..+" << s.solver.harmonics << ", " << s.slices_per_row
           << " slices per rod diameter";
  std::ostringstream md;
  md << std::fixed << std::setprecision(2);
  md << "## rcwa\n\n"
     << "Fourier modal method table builder (`table_builder` rcwa, plugins/rcwa/NOTES.md), ("
     << settings.str() << ", Li's rule), both polarizations per entry. `entry`: the mean over the " << n_row
     << " entries of one wavelength of the production angle grid (550 nm), one thread, in ms. `table`: the whole "
        "table on "
     << b.threads << " threads. Wall and process CPU seconds.\n\n"
     << "| machine | command | date | crystal | item | wall s | CPU s | notes | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  const std::string head = "| " + machine_description() + " | `" + options.command + "` | " + today_iso() + " | " + cell.name;
  md << head << " | entry (1 lambda, 1 angle, 2 pols), ms | " << 1e3 * one.wall / entries_row << " | "
     << 1e3 * one.cpu / entries_row << " | mean of " << n_row << " entries | <= 5 ms |\n";
  if (options.progress) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(2) << "entry: " << 1e3 * one.wall / entries_row << " ms wall, "
         << 1e3 * one.cpu / entries_row << " ms CPU (mean of " << n_row << ")";
    options.progress(line.str());
  }
  if (!b.skip_table) {
    const int nl = or_default(b.n_lambda, kProductionTableGrid.n_lambda), nt = or_default(b.n_theta, kProductionTableGrid.n_theta),
              np = or_default(b.n_phi, kProductionTableGrid.n_phi);
    const TableGrid grid = TableGrid::uniform(400, 700, nl, nt, np);
    BuilderParams table_params = single_params;
    table_params.threads = b.threads;
    const Timed full = timed([&] { RcwaTableBuilder(table_params).build(cell, grid, {}); });
    md << head << " | table " << nl << " x " << nt << " x " << np << " x 2 pols | " << full.wall << " | " << full.cpu
       << " | " << 1e3 * full.cpu / (static_cast<double>(nl) * nt * np) << " ms CPU per entry | <= 120 s wall |\n";
    if (options.progress) {
      std::ostringstream line;
      line << std::fixed << std::setprecision(2) << "table: " << full.wall << " s wall, " << full.cpu << " s CPU";
      options.progress(line.str());
    }
  }
  return {"rcwa", md.str()};
}

}  // namespace plumage::rcwa
