#include "plumage/species_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <optional>

#include "pipeline/simulation_section.hpp"
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

void check_variant_name(const ParamView& raw, const std::string& name, const std::vector<std::string>& variants,
                        const char* key) {
  if (std::find(variants.begin(), variants.end(), name) != variants.end()) return;
  std::string msg = "unknown variant '" + name + "'";
  if (auto near = nearest_name(name, variants)) msg += " (did you mean '" + *near + "'?)";
  std::string all;
  for (const auto& v : variants) all += (all.empty() ? "" : ", ") + v;
  raw.fail(key, msg + "; variants: " + all);
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

}  // namespace

std::vector<std::string> species_variants(const std::filesystem::path& file) {
  auto doc = ConfigDocument::load(file);
  return variant_names(doc.root());
}

SpeciesConfig load_species_config(const std::filesystem::path& file, const PluginRegistry& registry,
                                  const std::string& requested_variant) {
  return load_species_config(ConfigDocument::load(file), registry, requested_variant);
}

const StructureGenerator& required_structure(const SpeciesConfig& config) {
  if (!config.structure) {
    throw ConfigError(config.root.mark_of("species"), "structure",
                      "no 'structure:' section (simulate, geometry and characterize need one to generate cross sections)");
  }
  return *config.structure;
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
  config.directory = doc.directory();
  config.content_hash = doc.content_hash();
  config.variants = variant_names(raw);
  const std::string default_variant = raw.text_or("variant", "");
  config.variant = requested_variant.empty() ? default_variant : requested_variant;

  // Build the merged tree of the chosen variant.
  YAML::Node tree = raw.state()->node;
  if (!config.variants.empty()) {
    if (default_variant.empty()) raw.fail("variant", "missing required key 'variant' (the default variant)");
    // The file's default is checked whichever variant is asked for, so that every command (and
    // `plumage check`, which loads each variant by name) refuses a default that names no variant.
    check_variant_name(raw, default_variant, config.variants, "variant");
    if (!requested_variant.empty()) check_variant_name(raw, requested_variant, config.variants, "variants");
    const YAML::Node& base = raw.state()->node;
    const YAML::Node& over = base["variants"][config.variant];
    tree = merged(base, over);
    config.nominal_stack_from_structure =
        over.IsMap() && over["structure"] && !over["nominal_stack"] && base["nominal_stack"];
  }
  ParamView root = make_root_view(tree, raw.file());
  root.accept("variants");
  root.accept("variant");
  config.root = root;

  config.species = root.text("species");
  config.common_name = root.text_or("common_name", config.species);
  root.accept("description");

  // Parsed (and so checked) either way; not used for a variant whose structure differs from it.
  if (root.has("nominal_stack")) config.nominal_stack = parse_layer_profile(root.child("nominal_stack"));
  if (config.nominal_stack_from_structure) config.nominal_stack.reset();

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
  config.simulation = read_simulation_section(root, "");
  root.finish();
  return config;
}

}  // namespace plumage
