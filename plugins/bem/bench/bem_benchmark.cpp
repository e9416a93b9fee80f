// Benchmark "bem" (`plumage bench bem`): the full-wave BEM ScatteringSolver (issue 6) on a segment
// of a species' barbule (default: the hummingbird) with its exact geometry at one (λ, θ_i), 20
// incident azimuths (cos φ_i = 0.05 b, spec §1.1), both polarizations, 400 pattern directions;
// time, CPU time, peak memory, and the speed ratio of the approximate solver on the same barbule.
// The solver is made by the registry from the `bem` map (`--bem key=value`), so its options have
// the plug-in's own table, defaults and checks; the benchmark states only those its recorded
// configuration needs (kSolverSettings).
#include "bem_benchmark.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bem_solver.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/param_table.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::bem {

namespace {

using Settings = std::vector<std::pair<std::string, std::string>>;

// Solver options the benchmark sets unless `--bem` gives them, where its record needs other values
// than the plug-in's defaults (dense LU, GMRES 1e-8: for the validation bodies): the solver for
// large barbules, method hmatrix, at the GMRES tolerance of issue 6's measurements. Every other
// option (30 points per wavelength, ACA 1e-6, ...) is the plug-in's default.
const Settings& solver_settings() {
  static const Settings settings = {{"method", "hmatrix"}, {"gmres_tolerance", "1e-6"}};
  return settings;
}

std::string settings_text(const Settings& settings) {
  std::string out;
  for (const auto& [key, value] : settings) out += (out.empty() ? "" : ", ") + key + ": " + value;
  return "{" + out + "}";
}

struct BenchParams {
  std::string config;
  std::vector<double> widths_um;
  double lambda_nm, theta_deg;
  int azimuths;
  Settings bem;  // the solver's options: solver_settings() with the `bem` map's entries over them
};

const ParamTable<BenchParams>& bench_params() {
  static const auto table =
      ParamTable<BenchParams>{}
          .text("config", &BenchParams::config, "configs/species/hummingbird.yaml",
                "species config whose barbule (instance 0) gives the segments")
          .numbers("width_um", &BenchParams::widths_um, "um", {10.0}, Limits::positive(),
                   "segment widths: structure.outline.width_um replaced (rounded corners, where the outline has them: min(1 um, W/10))")
          .number("lambda_nm", &BenchParams::lambda_nm, "nm", 550.0, Limits::positive(), "wavelength")
          .number("theta_deg", &BenchParams::theta_deg, "deg", 0.0, Limits::closed(-89.0, 89.0), "theta_i")
          .integer("azimuths", &BenchParams::azimuths, "1", 20, Limits::closed(2, 20),
                   "incident azimuths: 20 = all (cos phi_i = 0.05 b), fewer = a subset spread over them")
          .custom("bem", "map", "-", settings_text(solver_settings()),
                  "options of the bem solver (`plumage plugins describe bem`), as --bem key=value; the plug-in's "
                  "defaults for the others",
                  [](const ParamView& p, BenchParams& o) {
                    const auto given = p.child_if("bem");
                    if (!given) return;
                    for (const std::string& key : given->keys()) {
                      if (key == "log_file") given->fail(key, "the benchmark reads the solver's log itself");
                      const std::string value = given->node(key).scalar_text();
                      const auto same = [&](const auto& kv) { return kv.first == key; };
                      if (auto it = std::find_if(o.bem.begin(), o.bem.end(), same); it != o.bem.end()) {
                        it->second = value;
                      } else {
                        o.bem.emplace_back(key, value);
                      }
                    }
                  },
                  [](BenchParams& o) { o.bem = solver_settings(); });
  return table;
}

std::string yaml_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

double peak_rss_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / (1024.0 * 1024.0);
}

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Run {
  double width_um = 0, approx_s = 0, bem_s = 0, bem_cpu_s = 0, rss_gb = 0;
  std::string status, log;  // log: the solver's own line (sizes, time split, iterations per RHS)
};

class BemBenchmark final : public Benchmark {
 public:
  BemBenchmark(BenchParams params, const PluginContext& context)
      : params_(std::move(params)), registry_(*context.registry), context_(context) {
    log_path_ = std::filesystem::temp_directory_path() / ("plumage-bench-bem-" + std::to_string(getpid()) + ".log");
    // The solver, through its own factory and table (unknown keys and bad values fail here).
    std::vector<ConfigDocument::Override> overrides;
    for (const auto& [key, value] : params_.bem) overrides.push_back({key, yaml_quoted(value), true});
    overrides.push_back({"log_file", yaml_quoted(log_path_.string()), true});
    const ConfigDocument none = ConfigDocument::parse("{}", "bench bem --bem");
    const ConfigDocument options = ConfigDocument::derive(none.root(), overrides, {}, "bench bem --bem");
    solver_ = registry_.create_named<ScatteringSolver>("bem", options.root(), context_);
    const auto* bem = dynamic_cast<const BemSolver*>(solver_.get());
    if (!bem) throw PluginError("bench bem: the registry's 'bem' solver is not this plug-in's");
    options_ = bem->options();
  }

  Report run(const Options& options) const override;

 private:
  Run run_width(double width_um, const Options& options) const;
  std::string description() const;

  BenchParams params_;
  const PluginRegistry& registry_;
  PluginContext context_;
  std::filesystem::path log_path_;
  std::unique_ptr<ScatteringSolver> solver_;
  BemOptions options_;
};

// Instance 0 of the species with the outline width replaced (load_species_segment: width_um = W
// and, where the outline has rounded corners, corner_um = min(1, W/10), written as the segments of
// the earlier records were, so the geometry is the same to the bit).
struct BarbuleSegment {
  SpeciesConfig species;
  CrossSection section;
};
BarbuleSegment segment(const std::string& config, double width_um, const PluginRegistry& registry) {
  BarbuleSegment out{load_species_segment(config, width_um, registry), {}};
  out.section = out.species.structure->generate(0);
  const CrossSection& cs = out.section;
  // Narrow segments can be outside the generator's valid range (at 0.3 um the hummingbird's
  // platelets cross each other and the outline): timing such a mesh would be meaningless.
  if (const auto problems = validate(cs); !problems.empty()) {
    std::ostringstream m;
    m << "bench bem: " << config << " at width " << width_um << " um is not a valid cross section ("
      << problems.front() << "); choose a wider segment";
    throw Error(m.str());
  }
  return out;
}

// φ_i: cos φ_i = 0.05 b, b = 1..20, or `count` of them spread over that set.
std::vector<double> incident_azimuths(int count) {
  std::vector<double> phi_i;
  if (count >= 20) {
    for (int k = 1; k <= 20; ++k) phi_i.push_back(std::acos(0.05 * k));
  } else {
    for (int j = 0; j < count; ++j) phi_i.push_back(std::acos(0.05 * (1 + std::lround(19.0 * j / (count - 1)))));
  }
  return phi_i;
}

Run BemBenchmark::run_width(double width_um, const Options& options) const {
  Run r;
  r.width_um = width_um;
  const auto [species, cs] = segment(params_.config, width_um, registry_);
  // A crystal species' reflection table, resolved or built before anything is timed.
  PreparationOptions preparation = options.preparation;  // the command's --tables
  if (options.progress && !preparation.progress) {
    preparation.progress = [&](std::size_t done, std::size_t total, std::string_view what) {
      if (done == 0 || done == total) options.progress("bench bem: " + std::string(what));
    };
  }
  prepare_species(species, preparation);
  const double theta = deg_to_rad(params_.theta_deg);
  const std::vector<double> phi_i = incident_azimuths(params_.azimuths);
  const auto phi_o = pattern_directions(400).phi_o_rad;
  // The budget first (issue 23): a segment whose system would not fit is refused in about a second,
  // before the approximate solver is timed.
  check_memory(solver_->estimate_memory(cs, params_.lambda_nm, phi_i.size(), phi_o.size()),
               memory_available(options_.max_memory));
  // approximate solver (its defaults), best of 3
  auto approx = registry_.create_named<ScatteringSolver>("approximate", ParamView{}, context_);
  r.approx_s = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto prep = approx->prepare(cs, species.reflection);
    const auto ff = approx->solve(*prep, params_.lambda_nm, theta, phi_i, phi_o);
    r.approx_s = std::min(r.approx_s, seconds_since(t0));
  }
  std::filesystem::remove(log_path_);
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  try {
    const auto prep = solver_->prepare(cs, species.reflection);
    const auto ff = solver_->solve(*prep, params_.lambda_nm, theta, phi_i, phi_o);
    r.bem_s = seconds_since(t0);
    r.bem_cpu_s = process_cpu_seconds() - cpu0;
    r.status = "solved (" + std::string(method_name(options_.method)) + ")";
  } catch (const MemoryBudgetError&) {
    throw;  // over the budget: the benchmark is refused (exit status 2), not recorded as "not solved"
  } catch (const Error& e) {
    r.bem_s = -1;
    r.status = std::string("not solved: ") + e.what();
  }
  r.rss_gb = peak_rss_gb();
  if (std::ifstream log(log_path_); log) std::getline(log, r.log);
  std::filesystem::remove(log_path_);
  return r;
}

std::string BemBenchmark::description() const {
  std::ostringstream md;
  md << std::setprecision(3);
  md << "Full-wave 2.5D BEM (plug-in `bem`, " << options_.points_per_wavelength << " points per wavelength, method "
     << method_name(options_.method);
  if (options_.method == BemOptions::Method::hmatrix) md << ", ACA tolerance " << options_.hmatrix.aca_tolerance;
  if (options_.method != BemOptions::Method::dense) md << ", GMRES tolerance " << options_.gmres_tolerance;
  md << "; solver options `" << settings_text(params_.bem) << "` and the plug-in's defaults for the rest — "
     << "the benchmark's own defaults are `" << settings_text(solver_settings())
     << "`, where the plug-in defaults to dense LU and GMRES 1e-8; `--bem key=value` sets any solver option) on `"
     << params_.config << "` instance 0 with the outline width replaced (rounded corners min(1 um, W/10)), lambda = "
     << params_.lambda_nm << " nm, theta_i = " << params_.theta_deg << " deg, " << incident_azimuths(params_.azimuths).size()
     << " incident azimuths (cos phi_i = 0.05 b; fewer than 20 = a subset spread over them, for both solvers), "
        "both polarizations, 400 pattern directions. "
        "Approximate solver: the same barbule and directions, prepare + solve, best of 3. Peak RSS of "
        "the whole process so far; BEM CPU = process CPU time during the BEM solve (both threads). Goal "
        "(issue 6): 10 um segment in <= 600 s and <= 8 GB. The solver's own line (unknowns, assembly = "
        "near field + ACA, factor = near-field LU, solve = GMRES for all right-hand sides, far field, "
        "H-matrix sizes, GMRES iterations per right-hand side) follows the table.\n\n";
  return md.str();
}

Benchmark::Report BemBenchmark::run(const Options& options) const {
  std::ostringstream md;
  md << std::setprecision(3);
  md << "## bem\n\n" << description()
     << "| machine | command | date | width um | BEM s | BEM CPU s | approximate s | ratio | peak RSS GB | status | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  const std::string command = options.command.empty() ? "plumage bench bem" : options.command;
  std::ostringstream logs;
  for (double w : params_.widths_um) {
    const Run r = run_width(w, options);
    md << "| " << machine_description() << " | `" << command << "` | " << today_iso() << " | " << w << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_s) : std::string("-")) << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_cpu_s) : std::string("-")) << " | " << r.approx_s << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_s / r.approx_s) + "x" : std::string("-")) << " | " << r.rss_gb
       << " | " << r.status << " | <= 600 s, <= 8 GB (W = 10) |\n";
    if (options.progress) {
      std::ostringstream line;
      line << "width " << w << " um: BEM " << r.bem_s << " s (CPU " << r.bem_cpu_s << " s), approximate " << r.approx_s
           << " s, peak RSS " << r.rss_gb << " GB; " << r.status << "\n" << r.log;
      options.progress(line.str());
    }
    if (!r.log.empty()) logs << "\nW = " << w << " um: `" << r.log << "`\n";
  }
  md << logs.str();
  return {"bem", md.str()};
}

}  // namespace

void register_bem_benchmark(Registrar& registrar) {
  registrar.add<Benchmark>(
      {.type = "bem",
       .version = "0.1.0",
       .summary = "full-wave BEM on a segment of a species' barbule (default: the hummingbird) against the "
                  "approximate solver: time, CPU, peak memory",
       .params = bench_params().specs()},
      [](const ParamView& p, const PluginContext& context) {
        if (!context.registry) throw PluginError("bench bem: needs the plug-in registry");
        return std::make_unique<BemBenchmark>(bench_params().read(p), context);
      });
}

}  // namespace plumage::bem
