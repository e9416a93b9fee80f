// check_config_file (plumage/config_check.hpp): each kind of configuration loaded by the loader its
// command uses, so that `plumage check` and a run agree on what is valid.
#include "plumage/config_check.hpp"

#include "plumage/comparison.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/error.hpp"
#include "plumage/render_job.hpp"
#include "plumage/species_config.hpp"
#include "plumage/table_builder.hpp"

namespace plumage {

namespace {

ConfigCheck check_species(const std::filesystem::path& file, const PluginRegistry& registry) {
  ConfigCheck c{"species", "species", {}};
  auto variants = species_variants(file);
  if (!variants.empty()) c.summary += ", " + std::to_string(variants.size()) + " variants";
  if (variants.empty()) variants.push_back("");
  for (const auto& v : variants) {
    const std::string work = pending_preparation(load_species_config(file, registry, v));
    if (!work.empty()) c.to_prepare.push_back((v.empty() ? "" : v + ": ") + work);
  }
  return c;
}

// The scene is created as `plumage render` creates it (the renderer's own table checks its
// section), and each feather material's species file must load with its variant; an error there
// points at the scene's material entry as well as into the species file.
ConfigCheck check_scene(const std::filesystem::path& file, const PluginRegistry& registry) {
  const RenderJob job(file, {}, registry);
  const SceneConfig& scene = job.config();
  std::size_t species_checked = 0;
  for (const auto& request : scene.feather_requests) {
    if (!request || request->species_config.empty()) continue;
    try {
      load_species_config(request->species_config.string(), registry, request->variant);
    } catch (const Error& e) {
      throw ConfigError(request->where, "species", std::string("the species config does not load: ") + e.what());
    }
    ++species_checked;
  }
  return {"scene",
          "scene " + scene.name + ", " + std::to_string(scene.views.size()) + " view(s), " +
              std::to_string(scene.materials.size()) + " materials, " + std::to_string(species_checked) +
              " species checked",
          {}};
}

// A crystal cell and each table builder's own section of it (CrystalCell::builder_sections).
ConfigCheck check_crystal(const std::filesystem::path& file, const PluginRegistry& registry) {
  const CrystalCell cell = load_crystal_cell(file);
  std::string summary = "crystal " + cell.name;
  for (const std::string& section : check_builder_sections(cell, registry)) summary += ", " + section + " section checked";
  return {"crystal", summary, {}};
}

}  // namespace

ConfigCheck check_config_file(const std::filesystem::path& file, const PluginRegistry& registry) {
  const auto doc = ConfigDocument::load(file);
  const ParamView root = doc.root();
  // `comparison` before `species`, which a comparison names too.
  if (root.has("comparison")) return {"comparison", check_comparison_config(file, registry), {}};
  if (root.has("species")) return check_species(file, registry);
  if (root.has("crystal")) return check_crystal(file, registry);
  if (root.has("scene") || root.has("objects")) return check_scene(file, registry);
  throw ConfigError(root.mark(), "",
                    "not a plumage configuration: expected a top-level 'species', 'crystal', 'scene' or 'comparison' key");
}

}  // namespace plumage
