// Accuracy ladder "approximate" (issue 9): the approximate 2.5D solver against the full-wave BEM
// on a real barbule (a rock-dove segment, its exact generated geometry), and the BEM itself at
// coarser meshes against its own finer one (16 ppw). Metric: relative L2 of the unpolarised reflectance
// density (Eq. 10) over the 400 pattern directions, mean over ω_i = (0°, 0°) and (0°, −30°) — the
// metric of `plumage compare` (docs/validation.md "Full-wave comparison").
//
// The approximate solver's rungs are its own fidelity options (local reflection sub-samples per
// segment, chunked or exact far field) for both current options; the ladder shows how much of
// its error is model error that no option removes. It drives both solvers through the registry
// (the BEM is a plug-in, created by name; core never includes it) on a species config of the tree.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "plumage/accuracy_ladder.hpp"
#include "plumage/config_document.hpp"
#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/far_field.hpp"
#include "plumage/param_table.hpp"
#include "plumage/pattern_metrics.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/scattering_solver.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

namespace {

class ApproximateLadder final : public AccuracyLadder {
 public:
  ApproximateLadder(const PluginRegistry& registry, std::string species) : registry_(registry), species_(std::move(species)) {}

  std::vector<LadderPoint> run(const Options& options) const override {
    const double width_um = options.quick ? 3.0 : 10.0;
    const double lambda_nm = 550.0, theta = 0.0;
    // 16 ppw: above the bem plug-in's 14-ppw warning level (plugins/bem/NOTES.md §6).
    const double reference_ppw = 16.0;
    const std::vector<double> bem_rungs = options.quick ? std::vector<double>{8, 12} : std::vector<double>{6, 8, 10, 12};
    if (!std::filesystem::exists(species_)) {
      throw Error("accuracy ladder 'approximate': " + species_ +
                  " not found (run `plumage bench ladder` from the source tree's top folder)");
    }
    const SpeciesConfig config = load_species_segment(species_, width_um, registry_);
    prepare_species(config, {});
    const CrossSection cs = config.structure->generate(0);
    if (const auto problems = validate(cs); !problems.empty()) {
      throw Error("accuracy ladder 'approximate': " + species_ + " at " + std::to_string(width_um) +
                  " um is not a valid cross section: " + problems.front());
    }
    const std::vector<double> phi_i = {0.0, deg_to_rad(-30.0)};
    const auto phi_o = pattern_directions(400).phi_o_rad;
    char case_name[128];
    std::snprintf(case_name, sizeof case_name, "%s %g um segment, 550 nm", config.common_name.c_str(), width_um);

    auto solve = [&](const std::string& type, const std::string& params, std::vector<FarField>& out) {
      const ConfigDocument doc = ConfigDocument::parse(params, "ladder solver options");
      auto solver = registry_.create_named<ScatteringSolver>(type, doc.root(), registry_.context());
      return measure_rung([&] {
        const auto prepared = solver->prepare(cs, config.reflection);
        out = solver->solve(*prepared, lambda_nm, theta, phi_i, phi_o);
      });
    };
    auto bem_params = [](double ppw) {
      std::ostringstream p;
      p << "incidence: beam\nmethod: dense\npoints_per_wavelength: " << ppw << "\n";
      return p.str();
    };
    auto error_against = [&](const std::vector<FarField>& a, const std::vector<FarField>& ref) {
      double e = 0.0;
      for (std::size_t k = 0; k < ref.size(); ++k) e += unpolarised_relative_l2(a[k], ref[k]);
      return e / static_cast<double>(ref.size());
    };

    if (options.progress) options.progress(std::string("reference: bem at ") + std::to_string(int(reference_ppw)) + " ppw on the " + case_name);
    std::vector<FarField> reference;
    const RungCost reference_cost = solve("bem", bem_params(reference_ppw), reference);
    if (options.progress) {
      char line[96];
      std::snprintf(line, sizeof line, "reference solved in %.3g s", reference_cost.wall_s);
      options.progress(line);
    }

    std::vector<LadderPoint> points;
    auto add = [&](const std::string& backend, const std::string& curve, const std::string& setting, double fidelity,
                   const std::string& reference_name, const std::vector<FarField>& result, const RungCost& cost) {
      LadderPoint pt;
      pt.backend = backend;
      pt.case_name = curve;
      pt.setting = setting;
      pt.fidelity = fidelity;
      pt.reference = reference_name;
      pt.metric = "rel. L2 of the unpolarised pattern, mean of 2 incidences";
      pt.error = error_against(result, reference);
      pt.wall_s = cost.wall_s;
      pt.cpu_s = cost.cpu_s;
      if (options.progress) {
        char line[200];
        std::snprintf(line, sizeof line, "%s %s: error %.3g, %.3g s", curve.c_str(), setting.c_str(), pt.error, pt.wall_s);
        options.progress(line);
      }
      points.push_back(pt);
    };
    const std::string bem_reference = "bem, " + std::to_string(int(reference_ppw)) + " ppw, exact geometry";
    for (const char* currents : {"reflected", "incident_and_reflected"}) {
      int rung = 0;
      for (int samples : {1, 4}) {
        for (const char* far_field : {"chunked", "exact"}) {
          std::ostringstream p;
          p << "currents: " << currents << "\nreflection_samples: " << samples << "\nfar_field: " << far_field << "\n";
          std::vector<FarField> result;
          const RungCost cost = solve("approximate", p.str(), result);
          add("approximate", std::string(case_name) + ", currents " + currents,
              "samples=" + std::to_string(samples) + " " + far_field, ++rung, bem_reference, result, cost);
        }
      }
    }
    for (double ppw : bem_rungs) {
      std::vector<FarField> result;
      const RungCost cost = solve("bem", bem_params(ppw), result);
      char setting[32];
      std::snprintf(setting, sizeof setting, "ppw=%g", ppw);
      add("bem (real barbule)", case_name, setting, ppw, bem_reference, result, cost);
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
      "species config of the barbule (relative to the working folder: run from the source tree)");
  return table;
}

}  // namespace

void register_approximate_ladder(PluginRegistry& registry) {
  registry.builtin_registrar().add<AccuracyLadder>(
      {.type = "approximate",
       .version = "1.0.0",
       .summary = "accuracy ladder: the approximate solver's options against the BEM on a rock-dove segment "
                  "(3 um quick, 10 um full), and the BEM at 6-12 ppw against its 16 ppw",
       .params = ladder_params().specs()},
      [](const ParamView& params, const PluginContext& context) {
        if (!context.registry) throw Error("accuracy ladder 'approximate': needs a registry in its context");
        return std::make_unique<ApproximateLadder>(*context.registry, ladder_params().read(params).species);
      });
}

}  // namespace plumage
