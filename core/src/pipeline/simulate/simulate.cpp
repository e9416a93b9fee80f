// simulate(): geometry → far fields of every instance for each work unit (λ, ω_i) → FarFieldSet.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>

#include "plumage/param_table.hpp"
#include "plumage/conventions.hpp"
#include "plumage/cross_section.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/simulation.hpp"
#include "plumage/structure_generator.hpp"
#include "plumage/version.hpp"
#include "pipeline/solve_memory.hpp"

namespace plumage {

namespace {

// Full-circle far fields (validation bodies): 1° steps over (−180°, 180°].
constexpr int kFullCircleSamples = 360;

[[noreturn]] void refuse(const std::string& where, const std::string& message) {
  throw ConfigError(SourceMark{where, 0, 0}, "", message);
}

// Azimuth offset of instance n of N: spread linearly over ±jitter (spec §1.1).
double jitter_rad(int n, int count, double jitter_deg) {
  if (count < 2 || jitter_deg == 0.0) return 0.0;
  return deg_to_rad(-jitter_deg + 2.0 * jitter_deg * n / (count - 1));
}

void check_request(const SpeciesConfig& config, const SimulationRequest& request,
                   const std::vector<double>& lambdas) {
  for (double t : request.theta_deg) {
    if (t < 0 || t >= 90) refuse("--theta-deg", "angles must be in [0, 90)");
  }
  for (double p : request.phi_deg) {
    if (std::abs(p) >= 90) refuse("--phi-deg", "azimuths must be in (-90, 90)");
  }
  if (request.instances < 0) refuse("--instances", "must be at least 1 (0: the config's)");
  const Limits wavelengths = Limits::wavelength_nm();
  for (double l : lambdas) {
    if (!wavelengths.admits(l))
      refuse("--lambda-nm", "wavelength " + format_param_number(l) + " nm is out of range: must be " + wavelengths.describe());
  }
  if (request.directions == SimulationRequest::Directions::full_circle && config.solver_type == "approximate") {
    refuse(config.file.string(),
           "--directions full needs a full-wave solver (e.g. `solver: {type: bem, incidence: plane_wave}`): the "
           "approximate solver radiates only the reflected field of the lit top surface, which is meaningful on "
           "the upper half of the cone alone (--directions pattern)");
  }
}

// Per code raised per instance (WarningSite::Item::instance: approx.rough_surface at preparation,
// approx.high_curvature per wavelength), the instances that raised it and their worst measure;
// report() names them (index and seed) in one warning per code, simulate.instances, so a user
// can regenerate or drop them (`plumage geometry FILE --first N`). Thread-safe add().
class InstanceWarnings {
 public:
  void add(const std::vector<WarningSite>& sites) {
    std::lock_guard lock(mutex_);
    for (const WarningSite& site : sites) {
      if (site.kind != WarningSite::Item::instance) continue;
      auto [it, fresh] = by_code_[site.code].try_emplace(site.item, site.value);
      // The measure's worst side: larger slopes, smaller radii.
      if (!fresh) it->second = site.code == "approx.high_curvature" ? std::min(it->second, site.value)
                                                                    : std::max(it->second, site.value);
    }
  }
  void report(const SpeciesConfig& config, int instances) const {
    constexpr std::size_t kListed = 10;
    for (const auto& [code, by_instance] : by_code_) {
      const char* measure = code == "approx.rough_surface"     ? "rms slope %.3g rad"
                            : code == "approx.high_curvature" ? "radius %.3g wavelengths"
                                                              : "measure %.3g";
      std::string list;
      std::size_t listed = 0;
      for (const auto& [n, value] : by_instance) {
        if (listed++ == kListed) break;
        char buffer[96];
        std::snprintf(buffer, sizeof buffer, "0x%016llx, ", static_cast<unsigned long long>(config.structure->seed_of(n)));
        char value_text[64];
        std::snprintf(value_text, sizeof value_text, measure, value);
        list += (list.empty() ? "" : "; ") + std::string("instance ") + std::to_string(n) + " (seed " + buffer + value_text + ")";
      }
      if (by_instance.size() > kListed) list += "; and " + std::to_string(by_instance.size() - kListed) + " more";
      warn("simulate.instances", code + " raised by " + std::to_string(by_instance.size()) + " of " +
                                     std::to_string(instances) + " instances of " + config.file.string() + ": " + list);
    }
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::map<std::size_t, double>> by_code_;
};

// Geometry and instance-only preparation, once per instance (reused by every unit). An invalid
// instance (e.g. a segment narrower than the generator's valid range, where platelets cross each
// other and the outline) would be meshed as given and solved without complaint by a full-wave
// solver, so it is refused here, as `plumage geometry` refuses it.
std::vector<std::shared_ptr<const ScatteringSolver::Prepared>> prepare_instances(const SpeciesConfig& config,
                                                                                 int instances,
                                                                                 InstanceWarnings& named) {
  std::vector<std::shared_ptr<const ScatteringSolver::Prepared>> prepared(instances);
  std::vector<std::string> invalid(instances);
  tbb::parallel_for(0, instances, [&](int n) {
    const CrossSection cs = config.structure->generate(static_cast<std::uint64_t>(n));
    if (const auto problems = validate(cs); !problems.empty()) {
      invalid[n] = problems.front() + (problems.size() > 1 ? " (and more)" : "");
      return;
    }
    const WarningSites scope;
    prepared[n] = config.solver->prepare(cs, config.reflection);
    named.add(scope.sites());
  });
  const std::string file = config.file.string();
  for (int n = 0; n < instances; ++n) {
    if (!invalid[n].empty()) {
      throw Error(file + ": instance " + std::to_string(n) + " is geometrically invalid: " + invalid[n] +
                  " (`plumage geometry " + file + " --first " + std::to_string(n) + "` lists every problem)");
    }
  }
  return prepared;
}

std::map<std::string, std::string> set_metadata(const SpeciesConfig& config, int instances, bool full) {
  return {{"producer", std::string("plumage ") + kVersionString},
          {"config", config.file.string()},
          {"config_hash", config.content_hash},
          {"species", config.species},
          {"variant", config.variant},
          {"solver", config.solver_type},
          {"instances", std::to_string(instances)},
          {"azimuth_jitter_deg", std::to_string(config.simulation.azimuth_jitter_deg)},
          {"field_units", "V/m*sqrt(nm) for a 1 V/m incident plane wave, e^{-i omega t}"},
          {"power_units", "W*nm/m^2 (per unit barbule length, nm)"},
          {"directions", full ? "full_circle: 360 azimuths -180, -179, ..., 179 deg (pattern_count 0)"
                              : "pattern+projected"}};
}

}  // namespace

FarFieldSet simulate(const SpeciesConfig& config, const SimulationRequest& request,
                     const SimulationCallbacks& callbacks) {
  required_structure(config);
  const SimulationSettings& sim = config.simulation;
  const std::vector<double>& lambdas = request.lambdas_nm.empty() ? sim.wavelengths_nm : request.lambdas_nm;
  check_request(config, request, lambdas);
  const bool full = request.directions == SimulationRequest::Directions::full_circle;
  const int instances = request.instances > 0 ? request.instances : sim.instances;

  prepare_species(config, request.preparation);
  InstanceWarnings named;
  const auto prepared = prepare_instances(config, instances, named);
  // Before the solves, with the tables and the prepared instances resident: how many instances
  // the budget lets us solve at a time (solve_memory.hpp). `plumage check` runs the same plan.
  const std::size_t n_phi_o = full ? static_cast<std::size_t>(kFullCircleSamples)
                                   : cone_directions(sim.pattern_samples, sim.projected_samples);
  const double units = static_cast<double>(lambdas.size() * request.theta_deg.size() * request.phi_deg.size());
  const SolvePlan plan =
      plan_parallel_solves(config, lambdas, 1, n_phi_o, instances, far_field_bytes(units * instances, n_phi_o), "simulate");

  FarFieldSet set;
  set.metadata = set_metadata(config, instances, full);
  const std::size_t total = lambdas.size() * request.theta_deg.size() * request.phi_deg.size();
  if (callbacks.started) callbacks.started(total);
  std::size_t done = 0;
  for (double theta_deg : request.theta_deg) {
    const double theta = deg_to_rad(theta_deg);
    const DirectionSet pattern = pattern_directions(sim.pattern_samples);
    const DirectionSet projected = projected_directions(theta, sim.projected_samples);
    std::vector<double> phi_o = pattern.phi_o_rad;
    phi_o.insert(phi_o.end(), projected.phi_o_rad.begin(), projected.phi_o_rad.end());
    if (full) phi_o = full_circle_directions(kFullCircleSamples).phi_o_rad;
    for (double lambda : lambdas) {
      for (double phi_deg : request.phi_deg) {
        FarFieldUnit unit;
        unit.lambda_nm = lambda;
        unit.nominal = {theta, deg_to_rad(phi_deg)};
        unit.pattern_count = full ? 0 : pattern.phi_o_rad.size();
        unit.instances.resize(instances);
        run_with_plan(plan, [&] {
          tbb::parallel_for(0, instances, [&](int n) {
            const double phi_i[1] = {unit.nominal.phi_rad + jitter_rad(n, instances, sim.azimuth_jitter_deg)};
            const WarningSites scope;
            unit.instances[n] = config.solver->solve(*prepared[n], lambda, theta, phi_i, phi_o).front();
            named.add(scope.sites());
          });
        });
        set.units.push_back(std::move(unit));
        if (callbacks.progress) callbacks.progress(++done, total);
      }
    }
  }
  named.report(config, instances);
  // The run's warnings (plumage/diagnostics.hpp) go into the file's header, one line.
  if (!diagnostics().empty()) set.metadata["warnings"] = diagnostics().summary("; ");
  return set;
}

}  // namespace plumage
