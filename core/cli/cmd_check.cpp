// `plumage check FILE...`: validates configurations without running anything.
#include <iostream>

#include "commands.hpp"
#include "plumage/comparison.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/scene_config.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

namespace {

void check_file(AppContext& context, const std::string& file) {
  auto doc = ConfigDocument::load(file);
  ParamView root = doc.root();
  if (root.has("comparison")) {  // before `species`, which a comparison names too
    const std::string what = check_comparison_config(file, context.registry());
    if (!context.quiet) std::cout << file << ": ok (" << what << ")\n";
    return;
  }
  if (root.has("species")) {
    auto variants = species_variants(file);
    if (variants.empty()) variants.push_back("");
    std::vector<std::string> pending;  // what the preparation step would do (check builds nothing)
    for (const auto& v : variants) {
      const std::string work = pending_preparation(load_species_config(file, context.registry(), v));
      if (!work.empty()) pending.push_back((v.empty() ? "" : v + ": ") + work);
    }
    if (!context.quiet) {
      std::cout << file << ": ok (species";
      if (!variants.front().empty()) std::cout << ", " << variants.size() << " variants";
      std::cout << ")\n";
      for (const auto& work : pending) std::cout << "  to prepare: " << work << "\n";
    }
    return;
  }
  if (root.has("crystal")) {
    const CrystalCell cell = load_crystal_cell(file);
    if (!context.quiet) std::cout << file << ": ok (crystal " << cell.name << ")\n";
    return;
  }
  if (root.has("scene") || root.has("objects")) {
    const SceneConfig scene = load_scene_config(file);
    // A feather material names a species file and variant: that file must load with that variant,
    // and the error points at the scene's material entry as well as into the species file.
    std::size_t species_checked = 0;
    for (const auto& request : scene.feather_requests) {
      if (!request || request->species_config.empty()) continue;
      try {
        load_species_config(request->species_config.string(), context.registry(), request->variant);
      } catch (const Error& e) {
        throw ConfigError(request->where, "species", std::string("the species config does not load: ") + e.what());
      }
      ++species_checked;
    }
    if (!context.quiet)
      std::cout << file << ": ok (scene " << scene.name << ", " << scene.views.size() << " view(s), " << scene.materials.size()
                << " materials, " << species_checked << " species checked)\n";
    return;
  }
  throw ConfigError(root.mark(), "",
                    "not a plumage configuration: expected a top-level 'species', 'crystal', 'scene' or 'comparison' key");
}

}  // namespace

void add_check_command(CLI::App& app, AppContext& context) {
  auto* cmd = app.add_subcommand("check", "Validate configuration files (exit 2 on the first error)");
  auto files = std::make_shared<std::vector<std::string>>();
  cmd->add_option("files", *files, "Species, crystal, scene or comparison YAML files")->required();
  cmd->callback([&context, files] {
    for (const auto& f : *files) check_file(context, f);
  });
}

}  // namespace plumage::cli
