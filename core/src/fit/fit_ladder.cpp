// Accuracy ladder "fit" (issue 9): the characterisation's fidelity knob — how many barbule
// instances are simulated and averaged before the mean lobe is fitted (preview 10, production
// 50) — against the simulated patterns themselves: the energy-matched fitted lobe Ĝ (fitter.hpp,
// Eqs. 11–12) of N instances against the mean pattern U of a larger independent set of
// instances (seeds not used by any rung). The error therefore contains both the lobe model's
// misfit (the floor) and the sampling noise of N instances (what the rungs reduce). Cost: the
// approximate solver's simulation of the N instances plus the fit.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "plumage/accuracy_ladder.hpp"
#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "plumage/param_table.hpp"
#include "plumage/pattern_metrics.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/scattering_solver.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

namespace {

class FitLadder final : public AccuracyLadder {
 public:
  FitLadder(const PluginRegistry& registry, std::string species) : registry_(registry), species_(std::move(species)) {}

  std::vector<LadderPoint> run(const Options& options) const override {
    if (!std::filesystem::exists(species_)) {
      throw Error("accuracy ladder 'fit': " + species_ + " not found (run `plumage bench ladder` from the source tree's top folder)");
    }
    const SpeciesConfig config = load_species_config(species_, registry_);
    if (!config.structure || !config.solver) throw Error("accuracy ladder 'fit': " + species_ + " has no structure or solver");
    prepare_species(config, {});
    const std::vector<int> ladder = options.quick ? std::vector<int>{2, 5, 10} : std::vector<int>{2, 5, 10, 20, 50};
    const int reference_instances = options.quick ? 40 : 200;
    const int max_rung = ladder.back();
    struct Incidence {
      const char* name;
      double theta_deg, phi_deg;
    };
    const std::vector<Incidence> incidences = {{"normal incidence", 0.0, 0.0}, {"(30, 30) deg", 30.0, 30.0}};
    const double lambda_nm = 550.0;
    std::vector<LadderPoint> points;
    for (const auto& inc : incidences) {
      const double theta = deg_to_rad(inc.theta_deg), phi = deg_to_rad(inc.phi_deg);
      const DirectionSet pattern = pattern_directions(400);
      std::vector<double> phi_o = pattern.phi_o_rad;
      const auto projected = projected_directions(theta, 1024).phi_o_rad;
      phi_o.insert(phi_o.end(), projected.begin(), projected.end());
      auto simulate = [&](std::uint64_t instance) {
        const CrossSection cs = config.structure->generate(instance);
        const auto prepared = config.solver->prepare(cs, config.reflection);
        const double phi_i[1] = {phi};
        return config.solver->solve(*prepared, lambda_nm, theta, phi_i, phi_o).front();
      };
      auto unit = [&](std::span<const FarField> instances) {
        UnitInput in;
        in.lambda_nm = lambda_nm;
        in.theta_i_rad = theta;
        in.phi_i_rad = phi;
        in.pattern_count = pattern.phi_o_rad.size();
        in.instances = instances;
        return fit_unit(in);
      };
      // Reference: the mean pattern of instances the rungs never use.
      std::vector<FarField> reference_set;
      for (int n = 0; n < reference_instances; ++n) reference_set.push_back(simulate(static_cast<std::uint64_t>(max_rung + n)));
      const std::vector<double> reference = unit(reference_set).mean_pattern;
      char case_name[96];
      std::snprintf(case_name, sizeof case_name, "%s, 550 nm, %s", config.common_name.c_str(), inc.name);
      for (int count : ladder) {
        UnitFit fit;
        const RungCost cost = measure_rung([&] {
          std::vector<FarField> set;
          for (int n = 0; n < count; ++n) set.push_back(simulate(static_cast<std::uint64_t>(n)));
          fit = unit(set);
        });
        LadderPoint pt;
        pt.backend = "fit";
        pt.case_name = case_name;
        pt.setting = "instances=" + std::to_string(count);
        pt.fidelity = count;
        pt.reference = "mean simulated pattern of " + std::to_string(reference_instances) + " other instances";
        pt.metric = "rel. L2 of the fitted mean lobe on the cone";
        pt.error = relative_l2(fit.fit_pattern, reference);
        pt.wall_s = cost.wall_s;
        pt.cpu_s = cost.cpu_s;
        if (options.progress) {
          char line[200];
          std::snprintf(line, sizeof line, "%s, %s: error %.3g (own fit %.3g), %.3g s", case_name, pt.setting.c_str(),
                        pt.error, fit.rel_l2_eff, pt.wall_s);
          options.progress(line);
        }
        points.push_back(pt);
      }
    }
    return points;
  }

 private:
  const PluginRegistry& registry_;
  std::string species_;
};

struct LadderParams {
  std::string species;
};

const ParamTable<LadderParams>& ladder_params() {
  static const auto table = ParamTable<LadderParams>{}.text(
      "species", &LadderParams::species, "configs/species/rockdove.yaml",
      "species config of the barbules (relative to the working folder: run from the source tree)");
  return table;
}

}  // namespace

void register_fit_ladder(PluginRegistry& registry) {
  registry.builtin_registrar().add<AccuracyLadder>(
      {.type = "fit",
       .version = "1.0.0",
       .summary = "accuracy ladder: the mean lobe fitted to 2-50 simulated instances against the mean pattern of "
                  "40 (quick) or 200 other instances (rock dove, 550 nm)",
       .params = ladder_params().specs()},
      [](const ParamView& params, const PluginContext& context) {
        if (!context.registry) throw Error("accuracy ladder 'fit': needs a registry in its context");
        return std::make_unique<FitLadder>(*context.registry, ladder_params().read(params).species);
      });
}

}  // namespace plumage
