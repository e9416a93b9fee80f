// Benchmark "geometry" (`plumage bench geometry`): instance generation time per species (goal
// ≤ 5 ms per instance). One thread; the validity check is not timed.
#include <ctime>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/param_table.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

namespace {

struct GeometryBenchParams {
  std::vector<std::string> configs;  // empty: every configs/species/*.yaml
  int instances = 20;
};

const ParamTable<GeometryBenchParams>& geometry_bench_params() {
  static const auto table =
      ParamTable<GeometryBenchParams>{}
          .custom("configs", "list", "-", "every configs/species/*.yaml", "species configs to time",
                  [](const ParamView& p, GeometryBenchParams& o) {
                    if (!p.has("configs")) return;
                    for (const auto& item : p.items("configs")) o.configs.push_back(item.scalar_text());
                  })
          .integer("instances", &GeometryBenchParams::instances, "1", 20, Limits::at_least(1),
                   "timed instances per species (after one warm-up)");
  return table;
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

class GeometryBenchmark final : public Benchmark {
 public:
  GeometryBenchmark(const PluginRegistry& registry, GeometryBenchParams params)
      : registry_(registry), params_(std::move(params)) {}

  Report run(const Options& options) const override {
    const std::string command =
        options.command.empty() ? "plumage bench geometry --instances " + std::to_string(params_.instances) : options.command;
    std::ostringstream md;
    md << std::fixed << std::setprecision(2);
    md << "## geometry\n\n"
       << "Time to generate one procedural cross section (`StructureGenerator::generate`, one thread, "
          "default variant, "
       << params_.instances << " instances after one warm-up; the validity check is not timed), with the "
          "size of what is generated. Wall-clock best and median, and the median CPU time of the "
          "generating thread (less sensitive to other jobs on a shared machine; it includes the "
          "kernel's page faults for fresh memory).\n\n"
       << "| machine | command | date | species | top vertices | regions | region vertices | best ms | "
          "median ms | median CPU ms | goal |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& file : files()) md << row(file, command, options);
    return {"geometry", md.str()};
  }

 private:
  // The configs to time: as given, or every species file in configs/species (run from the source
  // tree), in name order.
  std::vector<std::filesystem::path> files() const {
    std::vector<std::filesystem::path> out;
    if (!params_.configs.empty()) {
      for (const auto& c : params_.configs) out.emplace_back(c);
      return out;
    }
    const std::filesystem::path dir("configs/species");
    if (!std::filesystem::is_directory(dir)) {
      throw Error("bench geometry: no configs/species here; name the configs (--configs a.yaml,b.yaml)");
    }
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() == ".yaml") out.push_back(e.path());
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  std::string row(const std::filesystem::path& file, const std::string& command, const Options& options) const {
    const SpeciesConfig cfg = load_species_config(file, registry_);
    if (!cfg.structure) throw ConfigError(cfg.root.mark(), "structure", "no structure section to generate");
    const CrossSection warm = cfg.structure->generate(0);
    std::size_t vertices = 0;
    for (const Region& r : warm.regions) vertices += r.outline.size();
    std::vector<double> ms, cpu_ms;
    for (int k = 0; k < params_.instances; ++k) {
      const double c0 = thread_cpu_ms();
      const auto t0 = std::chrono::steady_clock::now();
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k + 1));
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      cpu_ms.push_back(thread_cpu_ms() - c0);
      if (cs.top.empty() && options.progress) options.progress("warning: empty instance");
    }
    std::sort(ms.begin(), ms.end());
    std::sort(cpu_ms.begin(), cpu_ms.end());
    std::ostringstream md;
    md << std::fixed << std::setprecision(2) << "| " << machine_description() << " | `" << command << "` | "
       << today_iso() << " | " << cfg.species << "-" << cfg.variant << " | " << warm.top.size() << " | "
       << warm.regions.size() << " | " << vertices << " | " << ms.front() << " | " << ms[ms.size() / 2] << " | "
       << cpu_ms[cpu_ms.size() / 2] << " | <= 5 ms |\n";
    if (options.progress) options.progress("bench geometry: " + cfg.species + " done");
    return md.str();
  }

  const PluginRegistry& registry_;
  GeometryBenchParams params_;
};

}  // namespace

void register_geometry_benchmark(PluginRegistry& registry) {
  registry.builtin_registrar().add<Benchmark>(
      {.type = "geometry",
       .version = "1.0.0",
       .summary = "procedural cross sections: generation time per species (one thread, goal <= 5 ms)",
       .params = geometry_bench_params().specs()},
      [](const ParamView& params, const PluginContext& context) {
        if (!context.registry) throw Error("benchmark 'geometry': needs a registry in its context");
        return std::make_unique<GeometryBenchmark>(*context.registry, geometry_bench_params().read(params));
      });
}

}  // namespace plumage
