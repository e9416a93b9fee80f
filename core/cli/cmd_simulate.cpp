// `plumage simulate CONFIG`: geometry → far fields of every instance for each work unit
// (λ, ω_i) → a FarFieldSet file, plus optional Eq. 10 CSV and a Fig. 7-style picture, through
// the library (plumage/simulation.hpp).
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "grid_parse.hpp"
#include "plumage/simulation.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string config;
  std::string variant;
  std::string lambda_nm;  // default: the config's simulation wavelengths
  std::string theta_deg = "0";
  std::string phi_deg = "0";
  int instances = 0;  // default: the config's
  std::string out;
  std::string pattern;
  std::string csv;
  std::string directions = "pattern";  // pattern (pattern + projected sets) | full
};

void run(AppContext& context, const Options& o) {
  check_output_flag("--out", o.out, {o.config}, "species config");
  check_output_flag("--pattern", o.pattern, {o.config}, "species config");
  check_output_flag("--csv", o.csv, {o.config}, "species config");
  const SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
  SimulationRequest request;
  if (!o.lambda_nm.empty()) request.lambdas_nm = parse_wavelengths(o.lambda_nm, "--lambda-nm");
  request.theta_deg = parse_samples(o.theta_deg, "--theta-deg");
  request.phi_deg = parse_samples(o.phi_deg, "--phi-deg");
  request.instances = o.instances;
  request.preparation = context.preparation();
  const bool full = o.directions == "full";
  request.directions = full ? SimulationRequest::Directions::full_circle : SimulationRequest::Directions::pattern;
  if (full && !o.pattern.empty()) {
    throw UsageError("--pattern draws the reflection pattern on (-90, 90) deg; it is not available with "
                     "--directions full (use --csv)");
  }
  const std::size_t wavelengths = o.lambda_nm.empty() ? config.simulation.wavelengths_nm.size() : request.lambdas_nm.size();
  if (!o.pattern.empty() && wavelengths < 2) throw UsageError("--pattern needs at least two wavelengths");

  std::optional<Progress> progress;
  SimulationCallbacks callbacks;
  callbacks.started = [&](std::size_t total) { progress.emplace("work units", total, context.quiet); };
  callbacks.progress = [&](std::size_t done, std::size_t) { progress->advance(done); };
  const FarFieldSet set = simulate(config, request, callbacks);

  write_far_field_set(set, o.out);
  if (!context.quiet) std::cerr << "wrote " << o.out << "\n";
  if (!o.csv.empty()) {
    if (full) write_scattering_width_csv(set, o.csv);
    else write_pattern_csv(set, o.csv);
    if (!context.quiet) std::cerr << "wrote " << o.csv << "\n";
  }
  if (!o.pattern.empty()) {
    std::ostringstream title;
    title << config.common_name << " (" << config.variant << "), θi = " << request.theta_deg.front()
          << "°, φi = " << request.phi_deg.front() << "°";
    draw_cone_colours(set, o.pattern, title.str());
    if (!context.quiet) std::cerr << "wrote " << o.pattern << "\n";
  }
}

}  // namespace

void add_simulate_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("simulate", "Far fields of every instance of a species (paper §4)");
  cmd->add_option("config", o->config, "Species YAML file")->required();
  cmd->add_option("--variant", o->variant, "Variant (default: the file's)");
  cmd->add_option("--lambda-nm", o->lambda_nm, "Wavelengths (default: the config's simulation grid)");
  cmd->add_option("--theta-deg", o->theta_deg, "Incident θ_i in degrees (list or range)")->capture_default_str();
  cmd->add_option("--phi-deg", o->phi_deg, "Incident φ_i in degrees (list or range)")->capture_default_str();
  cmd->add_option("--instances", o->instances, "Barbule instances (default: the config's)")->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cmd->add_option("--out", o->out, "FarFieldSet file to write (.ffs)")->required();
  cmd->add_option("--pattern", o->pattern, "Draw a Fig. 7-style picture to this PNG");
  cmd->add_option("--csv", o->csv,
                  "Write the instance-mean Eq. 10 patterns as CSV (with --directions full: the 2D "
                  "differential scattering width, normalisation in the header)");
  cmd->add_option("--directions", o->directions,
                  "Outgoing directions: pattern (400 bins on (-90, 90) deg plus the projected set) or "
                  "full (the full circle in 1 deg steps, for validation bodies and full-wave solvers)")
      ->check(CLI::IsMember({"pattern", "full"}))
      ->capture_default_str();
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
