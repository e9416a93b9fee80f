#include "plumage/species_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <optional>

#include "yaml_state.hpp"

namespace plumage {

namespace {

// Deep merge: maps merge key by key (recursively); anything else in `over` replaces `base`.
YAML::Node merged(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return over;
  // Key nodes are reused (force_insert) so that they keep their place in the file for messages.
  YAML::Node out(YAML::NodeType::Map);
  for (auto it = base.begin(); it != base.end(); ++it) {
    const YAML::Node& o = over[it->first.Scalar()];
    out.force_insert(it->first, o ? merged(it->second, o) : it->second);
  }
  for (auto it = over.begin(); it != over.end(); ++it) {
    if (!base[it->first.Scalar()]) out.force_insert(it->first, it->second);
  }
  return out;
}

std::vector<std::string> variant_names(const ParamView& root) {
  std::vector<std::string> names;
  if (root.has("variants")) {
    ParamView variants = root.child("variants");
    names = variants.keys();
    for (const auto& n : names) variants.accept(n);
  }
  return names;
}

// `solver: approximate` or `solver: {type: bem, ...}`; absent means approximate.
std::shared_ptr<const ScatteringSolver> create_solver(const ParamView& root, const PluginRegistry& registry,
                                                      const PluginContext& context, std::string& type) {
  if (!root.has("solver")) {
    type = "approximate";
    return registry.create_named<ScatteringSolver>(type, ParamView{}, context);
  }
  ParamView node = root.node("solver");
  if (node.is_map()) {
    type = node.text("type");
    return registry.create<ScatteringSolver>(node, "type", context);
  }
  type = root.text("solver");
  try {
    return registry.create_named<ScatteringSolver>(type, ParamView{}, context);
  } catch (const PluginError& e) {
    root.fail("solver", e.what());
  }
}

SimulationSettings parse_simulation(const ParamView& root) {
  SimulationSettings s;
  std::optional<ParamView> node = root.child_if("simulation");
  static constexpr std::string_view kFidelities[] = {"preview", "production", "reference"};
  if (node) s.fidelity = node->choice_or("fidelity", kFidelities, "production");
  // Presets: preview is for looking, production is the paper's grid, reference doubles it.
  double step = 6.0;
  if (s.fidelity == "preview") {
    s.instances = 10, step = 30.0, s.incident_grid = 5, s.pattern_samples = 200, s.projected_samples = 512;
  } else if (s.fidelity == "reference") {
    s.instances = 100, step = 3.0, s.pattern_samples = 800, s.projected_samples = 2048;
  }
  double from = 400.0, to = 694.0;
  if (node) {
    s.instances = static_cast<int>(node->integer_or("instances", s.instances, Limits::closed(1, 100000)));
    if (auto w = node->child_if("wavelengths_nm")) {
      from = w->number_or("from", from, Limits::closed(100, 5000));
      to = w->number_or("to", to, Limits::closed(100, 5000));
      step = w->number_or("step", step, Limits::positive());
      if (to < from) w->fail("to", "the wavelength range is inverted (to < from)");
    }
    s.incident_grid = static_cast<int>(node->integer_or("incident_grid", s.incident_grid, Limits::closed(1, 1000)));
    s.pattern_samples = static_cast<int>(node->integer_or("pattern_samples", s.pattern_samples, Limits::closed(2, 100000)));
    s.projected_samples = static_cast<int>(node->integer_or("projected_samples", s.projected_samples, Limits::closed(2, 100000)));
    s.azimuth_jitter_deg = node->number_or("azimuth_jitter_deg", s.azimuth_jitter_deg, Limits::closed(0, 45));
  }
  for (double l = from; l <= to + 1e-9; l += step) s.wavelengths_nm.push_back(l);
  return s;
}

}  // namespace

std::vector<std::string> species_variants(const std::filesystem::path& file) {
  auto doc = ConfigDocument::load(file);
  return variant_names(doc.root());
}

SpeciesConfig load_species_config(const std::filesystem::path& file, const PluginRegistry& registry,
                                  const std::string& requested_variant) {
  return load_species_config(ConfigDocument::load(file), registry, requested_variant);
}

void prepare_species(const SpeciesConfig& config, const PreparationOptions& options) {
  if (config.reflection) config.reflection->prepare(options);
}

std::string pending_preparation(const SpeciesConfig& config) {
  return config.reflection ? config.reflection->pending_preparation() : std::string();
}

SpeciesConfig load_species_config(const ConfigDocument& doc, const PluginRegistry& registry,
                                  const std::string& requested_variant) {
  const std::filesystem::path file = doc.path();
  ParamView raw = doc.root();

  SpeciesConfig config;
  config.file = file;
  config.content_hash = doc.content_hash();
  config.variants = variant_names(raw);
  const std::string default_variant = raw.text_or("variant", "");
  config.variant = requested_variant.empty() ? default_variant : requested_variant;

  // Build the merged tree of the chosen variant.
  YAML::Node tree = raw.state()->node;
  if (!config.variants.empty()) {
    if (config.variant.empty()) raw.fail("variant", "missing required key 'variant' (the default variant)");
    if (std::find(config.variants.begin(), config.variants.end(), config.variant) ==
        config.variants.end()) {
      std::string msg = "unknown variant '" + config.variant + "'";
      if (auto near = nearest_name(config.variant, config.variants)) {
        msg += " (did you mean '" + *near + "'?)";
      }
      std::string all;
      for (const auto& v : config.variants) all += (all.empty() ? "" : ", ") + v;
      raw.fail(requested_variant.empty() ? "variant" : "variants", msg + "; variants: " + all);
    }
    const YAML::Node& base = raw.state()->node;
    tree = merged(base, base["variants"][config.variant]);
  }
  ParamView root = make_root_view(tree, raw.file());
  root.accept("variants");
  root.accept("variant");
  config.root = root;

  config.species = root.text("species");
  config.common_name = root.text_or("common_name", config.species);
  root.accept("description");

  if (root.has("nominal_stack")) config.nominal_stack = parse_layer_profile(root.child("nominal_stack"));

  PluginContext context = registry.context(doc.directory());
  if (root.has("reflection")) {
    config.reflection = registry.create<LocalReflection>(root.child("reflection"), "model", context);
  }
  if (root.has("structure")) {
    auto generator = registry.create<StructureGenerator>(root.child("structure"), "generator", context);
    generator->bind(config.species, config.variant);
    config.structure = std::move(generator);
  }
  config.solver = create_solver(root, registry, context, config.solver_type);
  config.simulation = parse_simulation(root);
  root.finish();
  return config;
}

}  // namespace plumage
