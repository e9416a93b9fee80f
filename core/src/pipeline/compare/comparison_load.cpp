// Loading a comparison config (schema: docs/formats.md "Comparison configs"): the species and its
// barbule segment, the wavelengths and incident directions, and the methods with their solvers.
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "flow_yaml.hpp"
#include "plumage/comparison.hpp"
#include "plumage/config_document.hpp"
#include "plumage/conventions.hpp"

namespace plumage {

namespace {

namespace fs = std::filesystem;

// The segment width as YAML text: every digit of the double, so the generator reads it back.
std::string format_width(double x) {
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

// True when the dotted path names a key reached through maps only (what derive can replace).
bool has_path(const ParamView& base, const std::string& dotted) {
  ParamView at = base;
  for (std::size_t start = 0;;) {
    const std::size_t dot = dotted.find('.', start);
    const std::string part = dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!at.is_map() || !at.has(part)) return false;
    if (dot == std::string::npos) return true;
    at = at.node(part);
    start = dot + 1;
  }
}

// `a` is `b` or a section above it ("outline" above "outline.width_um").
bool covers(const std::string& a, const std::string& b) { return b == a || b.rfind(a + ".", 0) == 0; }

// The barbule segment: the species' generator with its outline width set to segment_um and the
// comparison's structure_overrides (further generator parameters by dotted path, replacing the
// species' values; each must exist in the species' structure section), derived as yaml-cpp nodes.
std::shared_ptr<const StructureGenerator> segment_generator(const ParamView& root, const Comparison& c,
                                                            const fs::path& species_file,
                                                            const PluginRegistry& registry) {
  const ParamView structure = c.species.root.child("structure");
  const std::string width_path = "outline.width_um";
  if (!has_path(structure, width_path)) {
    root.fail("segment_um", "the species' structure has no outline.width_um to set (" + species_file.string() + ")");
  }
  std::vector<ConfigDocument::Override> overrides{
      {.path = width_path, .yaml = format_width(c.segment_um), .source = root.mark_of("segment_um").str() + " segment_um"}};
  if (std::optional<ParamView> extra = root.child_if("structure_overrides")) {
    const std::vector<std::string> keys = extra->keys();
    for (const auto& key : keys) {
      const ParamView value = extra->node(key);
      if (covers(key, width_path)) extra->fail(key, "the width is segment_um");
      if (!has_path(structure, key)) extra->fail(key, "the species' structure has no parameter '" + key + "'");
      for (const auto& other : keys) {
        if (other != key && covers(other, key)) extra->fail(key, "overlaps the override of '" + other + "'");
      }
      overrides.push_back({.path = key, .yaml = detail::flow_yaml_text(value), .source = value.mark().str() + " " + value.path()});
    }
  }
  const ConfigDocument segment = ConfigDocument::derive(
      structure, overrides, species_file.parent_path(),
      species_file.string() + " (structure with outline.width_um = segment_um of " + c.file.string() + ")");
  auto generator = registry.create<StructureGenerator>(segment.root(), "generator",
                                                       registry.context(species_file.parent_path()));
  generator->bind(c.species.species, c.species.variant);
  return generator;
}

std::vector<double> parse_wavelengths(const ParamView& root) {
  if (!root.has("wavelengths_nm")) root.fail("wavelengths_nm", "missing required key 'wavelengths_nm'");
  std::vector<double> out;
  const ParamView node = root.node("wavelengths_nm");
  if (node.is_sequence()) {
    out = root.numbers("wavelengths_nm", Limits::wavelength_nm());
  } else if (node.is_map()) {
    const ParamView m = root.child("wavelengths_nm");
    const double from = m.number("from", Limits::wavelength_nm());
    const double to = m.number("to", Limits::wavelength_nm());
    const double step = m.number("step", Limits::positive());
    if (to < from) m.fail("to", "must be >= from");
    for (int k = 0; from + k * step <= to + 1e-9 * step; ++k) out.push_back(from + k * step);
  } else {
    root.fail("wavelengths_nm", "expected a list of wavelengths or {from, to, step}");
  }
  if (out.empty()) root.fail("wavelengths_nm", "no wavelengths");
  for (std::size_t i = 1; i < out.size(); ++i) {
    if (!(out[i] > out[i - 1])) root.fail("wavelengths_nm", "wavelengths must increase strictly");
  }
  return out;
}

std::vector<IncidentDirection> parse_incidents(const ParamView& root) {
  if (!root.has("incident_deg")) root.fail("incident_deg", "missing required key 'incident_deg'");
  std::vector<IncidentDirection> out;
  for (const auto& item : root.items("incident_deg")) {
    if (!item.is_sequence()) item.fail_here("expected [theta_i_deg, phi_i_deg]");
    const auto pair = item.items();
    if (pair.size() != 2) item.fail_here("expected [theta_i_deg, phi_i_deg] (two numbers)");
    const double theta = pair[0].scalar_number(Limits{0.0, 90.0, false, true});
    const double phi = pair[1].scalar_number(Limits{-90.0, 90.0, true, true});
    out.push_back({deg_to_rad(theta), deg_to_rad(phi)});
  }
  if (out.empty()) root.fail("incident_deg", "no incident directions");
  return out;
}

ComparisonMethod parse_method(const ParamView& m, const Comparison& c, const PluginContext& context,
                              const PluginRegistry& registry) {
  if (!m.is_map()) m.fail_here("expected {name: .., solver: {type: ..}, geometry: exact|reduced_layers}");
  ComparisonMethod method;
  method.geometry_mark = m.mark_of("geometry");
  method.geometry_field = m.path_of("geometry");
  method.name = m.text("name");
  if (method.name.empty() || method.name.find_first_of(",/\\ ") != std::string::npos) {
    m.fail("name", "a method name without spaces, commas or slashes");
  }
  for (const auto& other : c.methods) {
    if (other.name == method.name) m.fail("name", "duplicate method name '" + method.name + "'");
  }
  if (!m.has("solver")) m.fail("solver", "missing required key 'solver'");
  const ParamView solver = m.node("solver");
  if (solver.is_map()) {
    method.solver_type = solver.text("type");
    method.solver_options = detail::flow_yaml_text(solver);
    method.solver = registry.create<ScatteringSolver>(m.child("solver"), "type", context);
  } else {
    method.solver_type = m.text("solver");
    method.solver_options = method.solver_type;
    try {
      method.solver = registry.create_named<ScatteringSolver>(method.solver_type, ParamView{}, context);
    } catch (const PluginError& e) {
      m.fail("solver", e.what());
    }
  }
  static constexpr std::string_view kGeometry[] = {"exact", "reduced_layers"};
  method.geometry = m.choice_or("geometry", kGeometry, "exact") == "exact" ? ComparisonMethod::Geometry::exact
                                                                           : ComparisonMethod::Geometry::reduced_layers;
  if (m.has("reflection")) {
    method.reflection = registry.create<LocalReflection>(m.child("reflection"), "model", context);
    method.reflection_note = m.child("reflection").text("model");
  } else {
    method.reflection = c.species.reflection;
    method.reflection_note = "species";
  }
  m.finish();
  return method;
}

}  // namespace

const char* geometry_name(ComparisonMethod::Geometry geometry) {
  return geometry == ComparisonMethod::Geometry::exact ? "exact" : "reduced_layers";
}

Comparison load_comparison(const fs::path& file, const PluginRegistry& registry) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ParamView root = doc.root();
  Comparison c;
  c.file = file;
  c.name = root.text("comparison");
  if (c.name.empty() || c.name.find_first_of("/\\ ") != std::string::npos) {
    root.fail("comparison", "a name without spaces or slashes (it prefixes the output files)");
  }
  root.accept("description");
  const fs::path species_file = doc.directory() / root.text("species");
  if (!fs::exists(species_file)) root.fail("species", "no such file: " + species_file.string());
  c.species = load_species_config(species_file, registry, root.text_or("variant", ""));
  if (!c.species.structure) root.fail("species", species_file.string() + " has no `structure:` section");
  c.instance = static_cast<std::uint64_t>(root.integer_or("instance", 0, Limits::at_least(0)));
  c.segment_um = root.number_or("segment_um", 10.0, Limits::positive());
  c.generator = segment_generator(root, c, species_file, registry);

  c.lambdas = parse_wavelengths(root);
  c.incidents = parse_incidents(root);
  c.pattern_samples = static_cast<int>(root.integer_or("pattern_samples", 400, Limits::closed(8, 20000)));
  if (auto reduced = root.child_if("reduced_layers")) {
    static constexpr std::string_view kMixture[] = {"mean", "piecewise"};
    c.reduced.mixture = reduced->choice_or("mixture", kMixture, "mean") == "mean"
                            ? ReducedRegionOptions::Mixture::mean
                            : ReducedRegionOptions::Mixture::piecewise;
    c.reduced.piece_nm = reduced->number_or("piece_nm", 1000.0, Limits::positive());
  }

  const PluginContext context = registry.context(doc.directory());
  if (!root.has("methods")) root.fail("methods", "missing required key 'methods'");
  for (const auto& m : root.items("methods")) c.methods.push_back(parse_method(m, c, context, registry));
  if (c.methods.empty()) root.fail("methods", "no methods");
  const std::string reference = root.text_or("reference", c.methods.front().name);
  auto it = std::find_if(c.methods.begin(), c.methods.end(),
                         [&](const ComparisonMethod& m) { return m.name == reference; });
  if (it == c.methods.end()) root.fail("reference", "no method named '" + reference + "'");
  c.reference = static_cast<std::size_t>(it - c.methods.begin());
  root.finish();
  return c;
}

std::string describe_comparison(const Comparison& c) {
  std::ostringstream out;
  out << "comparison " << c.name << ", " << c.methods.size() << " methods (reference "
      << c.methods[c.reference].name << "), " << c.lambdas.size() << " wavelengths, " << c.incidents.size()
      << " incident directions";
  return out.str();
}

std::string check_comparison_config(const fs::path& file, const PluginRegistry& registry) {
  return describe_comparison(load_comparison(file, registry));
}

}  // namespace plumage
