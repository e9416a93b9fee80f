// `plumage bench geometry`: instance generation time per species (goal ≤ 5 ms per instance),
// optionally recorded in docs/benchmarks.md. One thread; the validity check is not timed.
#include <ctime>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "commands.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

namespace {

struct GeometryBench {
  std::vector<std::string> configs;
  int instances = 20;
  std::string record;
};

void bench_geometry(AppContext& context, const GeometryBench& b) {
  if (b.instances < 1) throw UsageError("bench geometry: --instances must be positive");
  std::vector<std::filesystem::path> files;
  if (b.configs.empty()) {
    // Every species file in configs/species (run from the source tree), in name order.
    const std::filesystem::path dir("configs/species");
    if (!std::filesystem::is_directory(dir)) throw UsageError("bench geometry: no configs/species here; name the configs");
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() == ".yaml") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
  } else {
    for (const auto& c : b.configs) files.emplace_back(c);
  }
  std::ostringstream md;
  md << std::fixed << std::setprecision(2);
  md << "## geometry\n\n"
     << "Time to generate one procedural cross section (`StructureGenerator::generate`, one thread, "
        "default variant, "
     << b.instances << " instances after one warm-up; the validity check is not timed), with the "
        "size of what is generated. Wall-clock best and median, and the median CPU time of the "
        "generating thread (less sensitive to other jobs on a shared machine; it includes the "
        "kernel's page faults for fresh memory).\n\n"
     << "| machine | command | date | species | top vertices | regions | region vertices | best ms | "
        "median ms | median CPU ms | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& file : files) {
    SpeciesConfig cfg = load_species_config(file, context.registry());
    if (!cfg.structure) throw UsageError(file.string() + ": no structure section");
    CrossSection warm = cfg.structure->generate(0);
    std::size_t vertices = 0;
    for (const Region& r : warm.regions) vertices += r.outline.size();
    std::vector<double> ms, cpu_ms;
    auto thread_cpu_ms = [] {
      timespec t{};
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
      return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
    };
    for (int k = 0; k < b.instances; ++k) {
      const double c0 = thread_cpu_ms();
      const auto t0 = std::chrono::steady_clock::now();
      CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k + 1));
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      cpu_ms.push_back(thread_cpu_ms() - c0);
      if (cs.top.empty()) std::cerr << "warning: empty instance\n";
    }
    std::sort(ms.begin(), ms.end());
    std::sort(cpu_ms.begin(), cpu_ms.end());
    md << "| " << machine_description() << " | `plumage bench geometry --instances " << b.instances
       << "` | " << today_iso() << " | " << cfg.species << "-" << cfg.variant << " | " << warm.top.size()
       << " | " << warm.regions.size() << " | " << vertices << " | " << ms.front() << " | "
       << ms[ms.size() / 2] << " | " << cpu_ms[cpu_ms.size() / 2] << " | <= 5 ms |\n";
    if (!context.quiet) std::cerr << "bench geometry: " << cfg.species << " done\n";
  }
  std::cout << md.str();
  if (!b.record.empty()) {
    record_benchmark(b.record, "geometry", md.str());
    std::cerr << "recorded in " << b.record << "\n";
  }
}

}  // namespace

void add_bench_geometry_command(CLI::App& bench, AppContext& context) {
  auto b = std::make_shared<GeometryBench>();
  auto* cmd = bench.add_subcommand("geometry", "Procedural cross sections: generation time per species");
  cmd->add_option("configs", b->configs, "Species configs (default: every configs/species/*.yaml)");
  cmd->add_option("--instances", b->instances, "Timed instances per species")->capture_default_str();
  cmd->add_option("--record", b->record, "Markdown file to record the result in (e.g. docs/benchmarks.md)");
  cmd->callback([&context, b] { bench_geometry(context, *b); });
}

}  // namespace plumage::cli
