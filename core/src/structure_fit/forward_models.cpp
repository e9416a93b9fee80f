// The fit's forward models (plumage/structure_fit.hpp): the model's file with the parameters
// replaced (ConfigDocument::derive), then a nominal-stack spectrum or a crystal table on the
// targets' tiny grid; and the fitted file written back as YAML.
#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/layer_profile.hpp"
#include "plumage/far_field_set.hpp"
#include "plumage/param_table.hpp"
#include "plumage/simulation.hpp"
#include "plumage/species_config.hpp"
#include "plumage/stack_spectra.hpp"
#include "plumage/structure_fit.hpp"
#include "plumage/table_builder.hpp"
#include "yaml_state.hpp"

namespace plumage {

namespace {

// Sorted distinct values (within 1e-9) and the index of each input in them.
std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end(), [](double a, double b) { return std::abs(a - b) <= 1e-9; }), v.end());
  return v;
}
std::size_t index_of(const std::vector<double>& axis, double x) {
  return static_cast<std::size_t>(std::lower_bound(axis.begin(), axis.end(), x - 1e-9) - axis.begin());
}

double polarized(FitPolarization p, double r_s, double r_p) {
  switch (p) {
    case FitPolarization::s: return r_s;
    case FitPolarization::p: return r_p;
    default: return 0.5 * (r_s + r_p);
  }
}

// The file derived with the values in, from a fresh copy of its tree: yaml-cpp merges the node
// memory of every tree a node is inserted into with the node's own, so deriving from the same
// document again and again would grow that document's memory by a tree per evaluation (and slow
// every later one: 0.45 ms per evaluation became 3 ms after 1500).
ConfigDocument derived(const ParamView& base, const std::vector<ConfigDocument::Override>& overrides,
                       const std::filesystem::path& directory, const std::string& name) {
  return ConfigDocument::derive(make_root_view(YAML::Clone(base.state()->node), base.file()), overrides, directory, name);
}

std::vector<ConfigDocument::Override> overrides_for(const FitSpec& spec, const std::vector<double>& values) {
  std::vector<ConfigDocument::Override> out;
  for (std::size_t i = 0; i < spec.parameters.size(); ++i)
    out.push_back({.path = spec.parameters[i].path, .yaml = format_param_number(values[i]),
                   .source = spec.file.string() + ": fitted parameters[" + std::to_string(i) + "]"});
  return out;
}

// nominal_stack: the species' nominal_stack (or the stack under the apex of a variant's own
// structure, as `plumage spectra` takes it) through its LocalReflection plug-in. When every path
// is in the selected variant's nominal_stack (`nominal_stack.…` or `variants.<variant>.nominal_stack.…`
// where the variant has one), only that stack is derived and parsed per evaluation (the species
// file is loaded once: loading it is ~15 ms of YAML, the stack's spectrum ~0.1 ms); otherwise the
// whole file is derived and loaded each time.
class NominalStackModel final : public StructureForwardModel {
 public:
  NominalStackModel(const FitSpec& spec, const PluginRegistry& registry)
      : spec_(spec), registry_(registry), base_(ConfigDocument::load(spec.config)),
        species_(load_species_config(spec.config, registry, spec.variant)) {
    std::vector<double> l, t;
    for (const FitTarget& x : spec.targets) l.push_back(x.lambda_nm), t.push_back(x.theta_deg);
    lambdas_ = distinct(l);
    thetas_ = distinct(t);
    const YAML::Node& raw = base_.root().state()->node;
    const bool variant_stack = raw["variants"] && raw["variants"][spec.variant] &&
                               raw["variants"][spec.variant].IsMap() && raw["variants"][spec.variant]["nominal_stack"];
    const std::string in_variant = "variants." + spec.variant + ".nominal_stack.", in_base = "nominal_stack.";
    fast_ = species_.nominal_stack.has_value() && species_.reflection != nullptr;
    for (const FitParameter& p : spec.parameters) {
      if (variant_stack && p.path.rfind(in_variant, 0) == 0) {
        stack_paths_.push_back(p.path.substr(in_variant.size()));
      } else if (!variant_stack && p.path.rfind(in_base, 0) == 0) {
        stack_paths_.push_back(p.path.substr(in_base.size()));
      } else {
        fast_ = false;
      }
    }
    if (fast_) {
      stack_ = species_.root.child("nominal_stack");
      prepare_species(species_, {});
    }
  }
  std::vector<double> predict(const std::vector<double>& values) const override {
    if (!fast_) return from_file(values);
    std::vector<ConfigDocument::Override> o = overrides_for(spec_, values);
    for (std::size_t i = 0; i < o.size(); ++i) o[i].path = stack_paths_[i];
    const ConfigDocument doc = derived(stack_, o, base_.directory(), spec_.config.string());
    const LayerProfile stack = parse_layer_profile(doc.root());
    std::vector<LocalReflection::Request> requests;
    for (const FitTarget& x : spec_.targets) requests.push_back({x.lambda_nm, {0.0, deg_to_rad(x.theta_deg)}, &stack});
    std::vector<JonesReflection> r(requests.size());
    species_.reflection->reflect(requests, r);
    std::vector<double> out;
    for (std::size_t i = 0; i < r.size(); ++i)
      out.push_back(polarized(spec_.targets[i].polarization, std::norm(r[i].ss), std::norm(r[i].pp)));
    return out;
  }
  std::string description() const override {
    return "nominal_stack of " + spec_.config.string() + " (variant " + spec_.variant + ") on " +
           std::to_string(lambdas_.size()) + " wavelengths x " + std::to_string(thetas_.size()) + " angles" +
           (fast_ ? "" : " (the whole species file loaded per evaluation)");
  }

 private:
  // The general path: the whole file derived and loaded, its spectrum as `plumage spectra` makes it.
  std::vector<double> from_file(const std::vector<double>& values) const {
    const ConfigDocument doc =
        derived(base_.root(), overrides_for(spec_, values), base_.directory(), spec_.config.string());
    const SpeciesConfig species = load_species_config(doc, registry_, spec_.variant);
    const std::vector<StackSpectrum> spectra = nominal_stack_spectra({species}, lambdas_, thetas_, {});
    if (spectra.empty()) throw Error(spec_.config.string() + ": no nominal_stack/reflection to predict from");
    std::vector<double> out;
    for (const FitTarget& x : spec_.targets) {
      const StackSpectrumPoint& p = spectra[0].points[index_of(thetas_, x.theta_deg) * lambdas_.size() + index_of(lambdas_, x.lambda_nm)];
      out.push_back(polarized(x.polarization, p.r_s, p.r_p));
    }
    return out;
  }

  const FitSpec& spec_;
  const PluginRegistry& registry_;
  ConfigDocument base_;
  SpeciesConfig species_;
  std::vector<double> lambdas_, thetas_;
  std::vector<std::string> stack_paths_;
  ParamView stack_;  // the merged variant's nominal_stack (fast path)
  bool fast_ = false;
};

// crystal_table: the cell through a TableBuilder on the grid λ × cos θ × {cos φ = 1} of the
// targets (incidence in the plane across the rods): the specular order's Jones reflection,
// R_s = |r_ss|², R_p = |r_pp|² (reflection_table.hpp's basis).
class CrystalTableModel final : public StructureForwardModel {
 public:
  CrystalTableModel(const FitSpec& spec, const PluginRegistry& registry)
      : spec_(spec), base_(ConfigDocument::load(spec.config)),
        builder_(registry.create<TableBuilder>(spec.builder, "type", registry.context())) {
    std::vector<double> l, c;
    for (const FitTarget& x : spec.targets) l.push_back(x.lambda_nm), c.push_back(std::cos(deg_to_rad(x.theta_deg)));
    grid_.lambda_nm = distinct(l);
    grid_.cos_theta = distinct(c);
    grid_.cos_phi = {1.0};
    type_ = spec.builder.text("type");
  }
  std::vector<double> predict(const std::vector<double>& values) const override {
    const ConfigDocument doc =
        derived(base_.root(), overrides_for(spec_, values), base_.directory(), spec_.config.string());
    const CrystalCell cell = parse_crystal_cell(doc.root().child("crystal"));
    const ReflectionTable table = builder_->build(cell, grid_, {});
    std::vector<double> out;
    for (const FitTarget& x : spec_.targets) {
      const JonesReflection& j = table.at(index_of(grid_.lambda_nm, x.lambda_nm),
                                          index_of(grid_.cos_theta, std::cos(deg_to_rad(x.theta_deg))), 0);
      out.push_back(polarized(x.polarization, std::norm(j.ss), std::norm(j.pp)));
    }
    return out;
  }
  std::string description() const override {
    return "crystal_table of " + spec_.config.string() + " by " + type_ + " on " +
           std::to_string(grid_.lambda_nm.size()) + " wavelengths x " + std::to_string(grid_.cos_theta.size()) +
           " angles";
  }

 private:
  const FitSpec& spec_;
  ConfigDocument base_;
  std::unique_ptr<TableBuilder> builder_;
  TableGrid grid_;
  std::string type_;
};

// barbule: `plumage simulate` of the species with the values in, at θ_i = 0 and φ_i = each target
// θ, on the targets' wavelengths; R = the instance-mean Eq. 10 density integrated over the pattern
// directions (midpoint rule on their uniform bins over (−90°, 90°)).
class BarbuleModel final : public StructureForwardModel {
 public:
  BarbuleModel(const FitSpec& spec, const PluginRegistry& registry)
      : spec_(spec), registry_(registry), base_(ConfigDocument::load(spec.config)) {
    std::vector<double> l, t;
    for (const FitTarget& x : spec.targets) l.push_back(x.lambda_nm), t.push_back(x.theta_deg);
    request_.lambdas_nm = distinct(l);
    request_.theta_deg = {0.0};
    request_.phi_deg = distinct(t);
    request_.instances = spec.instances;
  }
  std::vector<double> predict(const std::vector<double>& values) const override {
    const ConfigDocument doc =
        derived(base_.root(), overrides_for(spec_, values), base_.directory(), spec_.config.string());
    const SpeciesConfig species = load_species_config(doc, registry_, spec_.variant);
    const FarFieldSet set = simulate(species, request_);
    std::vector<double> out;
    for (const FitTarget& x : spec_.targets) {
      const FarFieldUnit* unit = nullptr;
      for (const FarFieldUnit& u : set.units)
        if (std::abs(u.lambda_nm - x.lambda_nm) <= 1e-9 && std::abs(rad_to_deg(u.nominal.phi_rad) - x.theta_deg) <= 1e-6)
          unit = &u;
      if (!unit || unit->pattern_count == 0) throw Error("fit: simulate returned no unit at " + format_param_number(x.lambda_nm) + " nm");
      const double bin = M_PI / static_cast<double>(unit->pattern_count);
      double r[2] = {0.0, 0.0};
      for (int pol = 0; pol < 2; ++pol) {
        const std::vector<double> density = mean_reflectance_density(*unit, pol);
        for (std::size_t d = 0; d < unit->pattern_count; ++d) r[pol] += density[d] * bin;
      }
      out.push_back(polarized(x.polarization, r[0], r[1]));
    }
    return out;
  }
  std::string description() const override {
    return "barbule (simulate) of " + spec_.config.string() + " (variant " + spec_.variant + ", " +
           (spec_.instances > 0 ? std::to_string(spec_.instances) : std::string("the config's")) + " instances) on " +
           std::to_string(request_.lambdas_nm.size()) + " wavelengths x " + std::to_string(request_.phi_deg.size()) +
           " angles";
  }

 private:
  const FitSpec& spec_;
  const PluginRegistry& registry_;
  ConfigDocument base_;
  SimulationRequest request_;
};

std::string emit_yaml(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return out.c_str();
}

std::unique_ptr<StructureForwardModel> make_reflectance_model(const FitSpec& spec, const PluginRegistry& registry) {
  if (spec.model == FitModel::nominal_stack) return std::make_unique<NominalStackModel>(spec, registry);
  if (spec.model == FitModel::barbule) return std::make_unique<BarbuleModel>(spec, registry);
  return std::make_unique<CrystalTableModel>(spec, registry);
}

// Peak targets: the reflectance model runs on the window samples (a spec of its own, which it
// refers to), and each peak's prediction is reduced from its window (peak_targets.cpp).
class PeakTargetModel final : public StructureForwardModel {
 public:
  PeakTargetModel(const FitSpec& spec, const PluginRegistry& registry)
      : targets_(spec.targets), samples_(with_samples(spec)), inner_(make_reflectance_model(samples_, registry)) {}
  std::vector<double> predict(const std::vector<double>& values) const override {
    return fit_target_predictions(targets_, inner_->predict(values));
  }
  std::string description() const override {
    return inner_->description() + " (" + std::to_string(samples_.targets.size()) + " samples for " +
           std::to_string(targets_.size()) + " targets with peaks)";
  }

 private:
  static FitSpec with_samples(const FitSpec& spec) {
    FitSpec s = spec;
    s.targets = fit_model_samples(spec.targets);
    return s;
  }
  std::vector<FitTarget> targets_;
  FitSpec samples_;
  std::unique_ptr<StructureForwardModel> inner_;
};

}  // namespace

std::unique_ptr<StructureForwardModel> make_forward_model(const FitSpec& spec, const PluginRegistry& registry) {
  const bool peaks = std::any_of(spec.targets.begin(), spec.targets.end(),
                                 [](const FitTarget& t) { return t.kind == FitTargetKind::peak; });
  if (peaks) return std::make_unique<PeakTargetModel>(spec, registry);
  return make_reflectance_model(spec, registry);
}

std::string fitted_config_yaml(const FitSpec& spec, const std::vector<double>& values) {
  const ConfigDocument base = ConfigDocument::load(spec.config);
  std::vector<ConfigDocument::Override> o = overrides_for(spec, values);
  const std::string source = spec.file.string() + ": fitted";
  if (spec.model == FitModel::crystal_table) {
    o.push_back({.path = "crystal.name", .yaml = spec.fitted_name, .source = source});
  } else {
    const YAML::Node& root = base.root().state()->node;
    const std::string from = "variants." + spec.variant + ".";
    if (root["variants"] && root["variants"][spec.variant]) {
      // The new variant first (a copy of the fitted one), then its values, then the default.
      o.insert(o.begin(), {.path = "variants." + spec.fitted_name, .yaml = emit_yaml(root["variants"][spec.variant]),
                           .create = true, .source = source});
      for (auto& x : o)
        if (x.path.rfind(from, 0) == 0) x.path = "variants." + spec.fitted_name + "." + x.path.substr(from.size());
      o.push_back({.path = "variant", .yaml = spec.fitted_name, .create = true, .source = source});
    }
  }
  const ConfigDocument fitted = ConfigDocument::derive(base.root(), o, base.directory(), spec.config.string());
  return emit_yaml(fitted.root().state()->node) + "\n";
}

}  // namespace plumage
