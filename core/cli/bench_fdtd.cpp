// `plumage bench fdtd`: the periodic FDTD table builder (issue 5) — one (λ, angle) solve at
// production resolution (both polarizations), one broadband fixed-Bloch-k run, and the whole
// production table of one crystal (50 λ × 20 cos θ × 50 cos φ × 2 polarizations); optionally
// recorded in docs/benchmarks.md.
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "commands.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/table_builder.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct FdtdBench {
  std::string config = "configs/crystals/mallard-green.yaml";
  int n_lambda = 50, n_theta = 20, n_phi = 50;
  bool skip_table = false;
  double kz_min = 0.25;  // entries with cos θ cos φ below this are continued to grazing, not simulated
  std::string record;
  std::string out;  // also save the whole table here (e.g. the lazy cache's production file)
};

struct Timed {
  double wall = 0, cpu = 0;
  std::string notes;
  std::optional<ReflectionTable> table;
};

Timed timed_build(AppContext& context, const CrystalCell& cell, const std::string& params,
                  const TableGrid& grid, bool progress) {
  const ConfigDocument doc = ConfigDocument::parse(params, "bench fdtd options");
  auto builder = context.registry().create_named<TableBuilder>("fdtd_periodic", doc.root(),
                                                               context.registry().context());
  std::unique_ptr<Progress> bar;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  ReflectionTable t = builder->build(cell, grid, [&](std::size_t d, std::size_t n, std::string_view what) {
    if (!progress) return;
    if (!bar) bar = std::make_unique<Progress>(std::string(what), n, context.quiet);
    bar->advance(d);
  });
  Timed r;
  r.cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.notes = t.metadata().notes + "; resolution " + std::to_string(t.metadata().resolution_nm) + " nm";
  r.table = std::move(t);
  return r;
}

int runs_of(const std::string& notes) {
  const auto p = notes.find("fdtd runs: ");
  return p == std::string::npos ? 0 : std::atoi(notes.c_str() + p + 11);
}

void bench_fdtd(AppContext& context, const FdtdBench& b) {
  const CrystalCell cell = load_crystal_cell(b.config);
  TableGrid one;
  one.lambda_nm = {550};
  one.cos_theta = {std::cos(deg_to_rad(30))};
  one.cos_phi = {std::cos(deg_to_rad(20))};
  // One (λ, angle) entry, both polarizations: a single run at exact ε(550 nm).
  const Timed single = timed_build(context, cell, "fidelity: production\nk_step_per_um: 0\nthreads: 1\n", one, false);
  // Broadband runs at fixed Bloch k (the production path): the four k-grid corners of one entry.
  const Timed broad = timed_build(context, cell, "fidelity: production\nthreads: 1\n", one, false);
  const int broad_runs = std::max(1, runs_of(broad.notes));
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
  const std::string head = "| " + machine_description() + " | `plumage bench fdtd` | " + today_iso() + " | " + cell.name;
  md << head << " | single solve (1 lambda, 1 angle, 2 pols) | " << single.wall << " | " << single.cpu << " | "
     << single.notes << " | - |\n";
  md << head << " | broadband run (all lambda, 1 Bloch k) | " << broad.wall / broad_runs << " | "
     << broad.cpu / broad_runs << " | " << broad_runs << " runs timed | - |\n";
  std::cout << "single solve: " << single.wall << " s wall, " << single.cpu << " s CPU\n"
            << "broadband run: " << broad.wall / broad_runs << " s wall, " << broad.cpu / broad_runs
            << " s CPU (mean of " << broad_runs << ")\n";
  if (!b.skip_table) {
    const TableGrid grid = TableGrid::uniform(400, 700, b.n_lambda, b.n_theta, b.n_phi);
    const Timed full = timed_build(context, cell,
                                   "fidelity: production\nthreads: 2\nkz_min: " + std::to_string(b.kz_min) + "\n",
                                   grid, true);
    std::ostringstream item;
    item << "table " << b.n_lambda << " x " << b.n_theta << " x " << b.n_phi << " x 2 pols, kz_min " << b.kz_min;
    md << head << " | " << item.str() << " | " << full.wall << " | " << full.cpu << " | " << full.notes
       << " | <= 900 s |\n";
    if (!b.out.empty()) {
      // The same table the photonic_crystal plug-in builds on demand (same builder, grid and
      // defaults), with the crystal file's content hash as the lazy cache stores it.
      ReflectionTable t = *full.table;
      std::ifstream in(b.config, std::ios::binary);
      t.metadata().config_hash = fnv1a_hex(std::string(std::istreambuf_iterator<char>(in), {}));
      std::filesystem::create_directories(std::filesystem::absolute(b.out).parent_path());
      t.save(b.out);
      std::cerr << "wrote " << b.out << "\n";
    }
    std::cout << item.str() << ": " << full.wall << " s wall, " << full.cpu << " s CPU (" << full.notes << ")\n";
  }
  if (!b.record.empty()) {
    record_benchmark(b.record, "fdtd", md.str());
    std::cerr << "recorded in " << b.record << "\n";
  }
}

}  // namespace

void add_bench_fdtd_command(CLI::App& bench, AppContext& context) {
  auto b = std::make_shared<FdtdBench>();
  auto* cmd = bench.add_subcommand("fdtd", "Periodic FDTD: one solve, one broadband run, a whole table");
  cmd->add_option("--config", b->config, "Crystal config")->capture_default_str();
  cmd->add_option("--n-lambda", b->n_lambda, "Table wavelengths")->capture_default_str();
  cmd->add_option("--n-theta", b->n_theta, "Table cos theta nodes")->capture_default_str();
  cmd->add_option("--n-phi", b->n_phi, "Table cos phi nodes")->capture_default_str();
  cmd->add_option("--kz-min", b->kz_min, "Table entries with cos(theta)cos(phi) below this are continued to the grazing limit (impedance form), not simulated")->capture_default_str();
  cmd->add_flag("--skip-table", b->skip_table, "Only the single solve and the broadband run");
  cmd->add_option("--out", b->out, "Also save the whole table to this file (.plt), e.g. the lazy cache's build/cache/tables/<crystal>-<key>.plt")->capture_default_str();
  cmd->add_option("--record", b->record, "Markdown file to record the result in (e.g. docs/benchmarks.md)");
  cmd->callback([&context, b] { bench_fdtd(context, *b); });
}

}  // namespace plumage::cli
