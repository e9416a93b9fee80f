// load_fit_spec (plumage/structure_fit.hpp): the fit spec's parameter tables, its parameters checked
// against the model's file, and its targets (a measured file or a list of reflectances).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "plumage/config_document.hpp"
#include "plumage/config_sections.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/measured_spectrum.hpp"
#include "plumage/param_table.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_fit.hpp"
#include "plumage/table_builder.hpp"
#include "yaml_state.hpp"

namespace plumage {

namespace {

struct ParameterOptions {
  std::string path;
  std::pair<double, double> bounds;
  std::optional<double> start;
};

struct PointOptions {
  double lambda_nm = 0, theta_deg = 0, reflectance = 0, sigma = 1;
  FitPolarization polarization = FitPolarization::unpolarized;
};

struct PeakOptions {
  double lambda_nm = 0, theta_deg = 0, sigma_nm = 2, window_nm = 40, step_nm = 5;
  FitPolarization polarization = FitPolarization::unpolarized;
};

struct TargetOptions {
  std::string measured;
  std::optional<double> theta_deg;
  std::optional<std::int64_t> column;
  std::optional<std::pair<double, double>> lambda_range_nm;
  double sigma = 1.0;
  FitPolarization polarization = FitPolarization::unpolarized;
  std::vector<PointOptions> points;
  std::vector<PeakOptions> peaks;
};

struct SpecOptions {
  FitModel model = FitModel::nominal_stack;
  std::string config, variant, fitted_name;
  int starts = 1, instances = 4;
  std::int64_t seed = 1;
  int max_iterations = 50;
  double relative_step = 1e-4;
  std::vector<ParameterOptions> parameters;
  TargetOptions target;
};

const std::vector<std::pair<std::string_view, FitPolarization>> kPolarizations{
    {"unpolarized", FitPolarization::unpolarized}, {"s", FitPolarization::s}, {"p", FitPolarization::p}};

const std::vector<std::pair<std::string_view, FitModel>> kModels{{"nominal_stack", FitModel::nominal_stack},
                                                                  {"crystal_table", FitModel::crystal_table},
                                                                  {"barbule", FitModel::barbule}};

const ParamTable<ParameterOptions>& parameter_table() {
  using P = ParameterOptions;
  static const auto t =
      ParamTable<P>{}
          .text("path", &P::path, required, "YAML path of a number in the model's file (a number indexes a list)")
          .interval("bounds", &P::bounds, "as the value", required, {}, "[lower, upper], lower < upper")
          .optional_number("start", &P::start, "as the value", "the file's value", {}, "first start, inside the bounds");
  return t;
}

const ParamTable<PointOptions>& point_table() {
  using P = PointOptions;
  static const auto t =
      ParamTable<P>{}
          .number("lambda_nm", &P::lambda_nm, "nm", required, Limits::wavelength_nm(), "vacuum wavelength")
          .number("theta_deg", &P::theta_deg, "deg", 0.0, Limits::closed(0.0, 89.0), "angle of incidence")
          .number("R", &P::reflectance, "1", required, Limits::unit_interval(), "target reflectance (fraction)")
          .number("sigma", &P::sigma, "1", 1.0, Limits::positive(), "its standard deviation (weight 1/sigma^2)")
          .choice("polarization", &P::polarization, kPolarizations, FitPolarization::unpolarized,
                  "unpolarized (R_s + R_p)/2, s or p");
  return t;
}

const ParamTable<PeakOptions>& peak_table() {
  using P = PeakOptions;
  static const auto t =
      ParamTable<P>{}
          .number("lambda_nm", &P::lambda_nm, "nm", required, Limits::wavelength_nm(),
                  "target wavelength of the reflectance maximum (the window's centre)")
          .number("theta_deg", &P::theta_deg, "deg", 0.0, Limits::closed(0.0, 89.0), "angle of incidence")
          .number("sigma_nm", &P::sigma_nm, "nm", 2.0, Limits::positive(), "standard deviation of the peak position")
          .number("window_nm", &P::window_nm, "nm", 40.0, Limits::closed(4.0, 300.0),
                  "width of the sampled window (narrower than the peak, so that a parabola describes it)")
          .number("step_nm", &P::step_nm, "nm", 5.0, Limits::closed(0.5, 50.0), "sampling step in the window")
          .choice("polarization", &P::polarization, kPolarizations, FitPolarization::unpolarized,
                  "unpolarized (R_s + R_p)/2, s or p");
  return t;
}

const ParamTable<TargetOptions>& target_table() {
  using T = TargetOptions;
  static const auto t =
      ParamTable<T>{}
          .text("measured", &T::measured, "", "measured spectrum file (CSV/TSV/spectrometer text), beside the spec")
          .optional_number("theta_deg", &T::theta_deg, "deg", "the file's angles, else 0", Limits::closed(0.0, 89.0),
                           "angle of incidence of the measurement; with angle columns, the one curve fitted")
          .custom("column", "integer", "1", "the reflectance column", "which sample column of a multi-sample file",
                  [](const ParamView& p, T& o) {
                    if (p.has("column")) o.column = p.integer("column", Limits::non_negative());
                  })
          .custom("lambda_range_nm", "interval", "nm", "all", "only measured wavelengths in [lo, hi]",
                  [](const ParamView& p, T& o) {
                    if (p.has("lambda_range_nm")) o.lambda_range_nm = p.interval("lambda_range_nm", Limits::wavelength_nm());
                  })
          .number("sigma", &T::sigma, "1", 1.0, Limits::positive(),
                  "standard deviation of each measured value (1: unweighted; the 1 sigma scale from the residuals)")
          .choice("polarization", &T::polarization, kPolarizations, FitPolarization::unpolarized,
                  "polarization of the measurement")
          .custom("points", "list", "-", "[]", "target reflectances instead of a measured file",
                  [](const ParamView& p, T& o) {
                    if (!p.has("points")) return;
                    for (const ParamView& item : p.items("points")) o.points.push_back(point_table().read(item));
                  })
          .nested_specs(point_table().specs())
          .custom("peaks", "list", "-", "[]", "peak positions to fit (with or without reflectances)",
                  [](const ParamView& p, T& o) {
                    if (!p.has("peaks")) return;
                    for (const ParamView& item : p.items("peaks")) o.peaks.push_back(peak_table().read(item));
                  })
          .nested_specs(peak_table().specs());
  return t;
}

const ParamTable<SpecOptions>& spec_table() {
  using S = SpecOptions;
  static const auto t =
      ParamTable<S>{}
          .choice("model", &S::model, kModels, required,
                  "forward model: a species' nominal_stack through its reflection, a crystal cell's table builder, or "
                  "the whole barbule through the species' solver (plumage simulate)")
          .text("config", &S::config, required, "species (nominal_stack, barbule) or crystal file (crystal_table), beside the spec")
          .text("variant", &S::variant, "", "species variant (default: the file's)")
          .custom("builder", "map", "-", "required for crystal_table",
                  "{type: <table_builder>, ...its own parameters} (e.g. {type: fdtd_periodic, fidelity: preview})",
                  [](const ParamView& p, S&) { p.accept("builder"); })
          .custom("parameters", "list", "-", "required", "the fitted numbers",
                  [](const ParamView& p, S& o) {
                    for (const ParamView& item : p.items("parameters")) o.parameters.push_back(parameter_table().read(item));
                    if (o.parameters.empty()) p.fail("parameters", "no parameter to fit");
                  })
          .nested_specs(parameter_table().specs())
          .section("target", &S::target, target_table(), "what to fit", true)
          .integer("instances", &S::instances, "1", 4, Limits::closed(0, 1000),
                   "barbule model: instances simulated per evaluation (0: the species' simulation.instances)")
          .integer("starts", &S::starts, "1", 1, Limits::closed(1, 1000), "starts: the spec's, then a Halton sequence")
          .integer("seed", &S::seed, "1", 1, Limits::non_negative(), "offset into the Halton sequence of starts")
          .integer("max_iterations", &S::max_iterations, "1", 50, Limits::closed(1, 10000), "per start")
          .number("relative_step", &S::relative_step, "1", 1e-4, Limits::closed(1e-9, 0.1),
                  "central-difference step relative to the value (above the model's numerical noise)")
          .text("fitted_name", &S::fitted_name, "", "name of the new variant/crystal (default <variant>_fit, <name>-fit)");
  return t;
}

const ConfigSectionRegistration kFitSpecSection{
    {"fit spec", "(top level)", "plumage fit: parameters, bounds, target, starts", [] { return spec_table().specs(); }}};

// The number at a dotted path of the document (a number part indexes a list); fails at the spec's
// `item` field `path` naming what is missing.
double number_at(const ParamView& root, const std::string& path, const ParamView& item, const std::string& file) {
  YAML::Node node = root.state()->node;
  std::string walked;
  for (std::size_t start = 0; start <= path.size();) {
    const std::size_t dot = std::min(path.find('.', start), path.size());
    const std::string part = path.substr(start, dot - start);
    walked += (walked.empty() ? "" : ".") + part;
    start = dot + 1;
    // Read through a const node and reset(): a non-const [] or `=` would write into the document.
    const YAML::Node& here = node;
    const bool index = !part.empty() && part.size() < 9 && std::all_of(part.begin(), part.end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)) != 0; });
    if (here.IsMap() && here[part]) {
      node.reset(here[part]);
    } else if (here.IsSequence() && index && std::stoul(part) < here.size()) {
      node.reset(here[std::stoul(part)]);
    } else {
      item.fail("path", "'" + walked + "' is not in " + file + (node.IsSequence() ? " (a list: index it from 0)" : ""));
    }
  }
  try {
    if (node.IsScalar()) return node.as<double>();
  } catch (const YAML::Exception&) {
  }
  item.fail("path", "'" + path + "' in " + file + " is not a number");
}

std::vector<FitTarget> measured_targets(const TargetOptions& t, const std::filesystem::path& file) {
  MeasuredSpectrumOptions options;
  if (t.column) options.sample_column = static_cast<std::size_t>(*t.column);
  const MeasuredSpectrum m = with_measurement_angle(read_measured_spectrum(file, options), t.theta_deg);
  std::vector<FitTarget> out;
  for (const MeasuredCurve& c : m.curves) {
    for (std::size_t i = 0; i < c.lambda_nm.size(); ++i) {
      if (t.lambda_range_nm && (c.lambda_nm[i] < t.lambda_range_nm->first || c.lambda_nm[i] > t.lambda_range_nm->second))
        continue;
      out.push_back({c.lambda_nm[i], *c.theta_deg, c.reflectance[i], t.sigma, t.polarization});
    }
  }
  return out;
}

void read_targets(const ParamView& root, const SpecOptions& o, FitSpec& spec) {
  const ParamView target = root.child("target");
  if (!o.target.measured.empty() && !o.target.points.empty())
    target.fail_here("give either `measured` (a file) or `points` (a list), not both");
  if (o.target.measured.empty() && o.target.points.empty() && o.target.peaks.empty())
    target.fail_here("give `measured` (a file), `points` (a list) or `peaks` (a list)");
  if (!o.target.measured.empty()) {
    spec.measured = spec.file.parent_path() / o.target.measured;
    spec.targets = measured_targets(o.target, spec.measured);
  } else {
    for (const PointOptions& p : o.target.points)
      spec.targets.push_back({p.lambda_nm, p.theta_deg, p.reflectance, p.sigma, p.polarization});
  }
  for (const PeakOptions& p : o.target.peaks) {
    if (p.step_nm * 2.0 > p.window_nm) target.fail_here("a peak's window_nm must hold at least 3 samples of step_nm");
    spec.targets.push_back({p.lambda_nm, p.theta_deg, 0.0, p.sigma_nm, p.polarization, FitTargetKind::peak,
                            p.window_nm, p.step_nm});
  }
  // As many values as parameters is a solve, not a fit: allowed (the worked magpie cells have one
  // reference reflectance each), with σ from the targets' stated σ (structure_solve.cpp).
  if (spec.targets.size() < spec.parameters.size())
    target.fail_here(std::to_string(spec.targets.size()) + " target values for " + std::to_string(spec.parameters.size()) +
                     " parameters: a fit needs at least as many values as parameters");
  for (const FitTarget& t : fit_model_samples(spec.targets)) {
    if (!Limits::wavelength_nm().admits(t.lambda_nm) || t.theta_deg < 0 || t.theta_deg > 89)
      target.fail_here("target at " + format_param_number(t.lambda_nm) + " nm, " + format_param_number(t.theta_deg) +
                       " deg: wavelength must be " + Limits::wavelength_nm().describe() + ", angle in [0, 89]");
  }
}

// The model's file loaded once as the model would (a species with its variant, a crystal cell), so
// that a bad file fails here, naming itself.
void check_model_file(const ParamView& root, FitSpec& spec, const PluginRegistry& registry) {
  if (spec.model != FitModel::crystal_table) {
    if (root.has("builder")) root.fail("builder", "only the crystal_table model has a table builder");
    const SpeciesConfig s = load_species_config(spec.config, registry, spec.variant);
    spec.variant = s.variant;
    if (spec.model == FitModel::barbule) {
      (void)required_structure(s);
    } else if (!s.reflection || (!s.nominal_stack && !s.nominal_stack_from_structure)) {
      root.fail("config", spec.config.string() + " has no nominal_stack and reflection to predict a spectrum from");
    }
  } else {
    // Looked at through yaml-cpp: a child view of `builder` would make finish() refuse its keys.
    if (!root.has("builder") || !root.state()->node["builder"].IsMap())
      root.fail("builder", "the crystal_table model needs a map {type: <table_builder>, ...}");
    if (!spec.variant.empty()) root.fail("variant", "a crystal file has no variants");
    (void)load_crystal_cell(spec.config);
    // A view of its own: the builder reads and checks its keys (its parameter table), not this spec.
    spec.builder = make_root_view(root.state()->node["builder"], spec.file.string());
    (void)registry.create<TableBuilder>(spec.builder, "type", registry.context());
  }
}

}  // namespace

FitSpec load_fit_spec(const std::filesystem::path& file, const PluginRegistry& registry) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ParamView root = doc.root();
  const SpecOptions o = spec_table().read(root);
  FitSpec spec;
  spec.file = file;
  spec.model = o.model;
  spec.config = file.parent_path() / o.config;
  spec.variant = o.variant;
  spec.starts = o.starts;
  spec.instances = o.instances;
  spec.seed = static_cast<std::uint64_t>(o.seed);
  spec.max_iterations = o.max_iterations;
  spec.relative_step = o.relative_step;
  check_model_file(root, spec, registry);
  root.finish();
  const ConfigDocument config = ConfigDocument::load(spec.config);
  const std::vector<ParamView> items = root.items("parameters");
  for (std::size_t i = 0; i < o.parameters.size(); ++i) {
    const ParameterOptions& p = o.parameters[i];
    if (!(p.bounds.first < p.bounds.second)) items[i].fail("bounds", "lower bound must be below the upper one");
    FitParameter f{p.path, p.bounds.first, p.bounds.second, p.start,
                   number_at(config.root(), p.path, items[i], spec.config.string()), items[i].mark_of("path"),
                   items[i].path_of("path")};
    const double start = p.start.value_or(f.file_value);
    if (start < f.lower || start > f.upper)
      items[i].fail(p.start ? "start" : "path", "start " + format_param_number(start) + (p.start ? "" : " (the file's value)") +
                                                    " is outside the bounds " + format_param_interval(p.bounds));
    for (std::size_t j = 0; j < i; ++j)
      if (o.parameters[j].path == p.path) items[i].fail("path", "'" + p.path + "' is fitted twice");
    spec.parameters.push_back(f);
  }
  read_targets(root, o, spec);
  spec.fitted_name = o.fitted_name;
  if (spec.fitted_name.empty()) {
    spec.fitted_name = spec.model != FitModel::crystal_table ? spec.variant + "_fit"
                                                             : load_crystal_cell(spec.config).name + "-fit";
  }
  return spec;
}

}  // namespace plumage
