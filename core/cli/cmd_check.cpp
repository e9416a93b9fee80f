// `plumage check FILE...`: validates configurations without running anything.
#include <iostream>

#include "commands.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

namespace {

void check_file(AppContext& context, const std::string& file) {
  auto doc = ConfigDocument::load(file);
  ParamView root = doc.root();
  if (root.has("species")) {
    auto variants = species_variants(file);
    if (variants.empty()) variants.push_back("");
    for (const auto& v : variants) load_species_config(file, context.registry(), v);
    if (!context.quiet) {
      std::cout << file << ": ok (species";
      if (!variants.front().empty()) std::cout << ", " << variants.size() << " variants";
      std::cout << ")\n";
    }
    return;
  }
  if (root.has("crystal")) {
    const CrystalCell cell = load_crystal_cell(file);
    if (!context.quiet) std::cout << file << ": ok (crystal " << cell.name << ")\n";
    return;
  }
  throw ConfigError(root.mark(), "",
                    "not a plumage configuration: expected a top-level 'species' or 'crystal' key");
}

}  // namespace

void add_check_command(CLI::App& app, AppContext& context) {
  auto* cmd = app.add_subcommand("check", "Validate configuration files (exit 2 on the first error)");
  auto files = std::make_shared<std::vector<std::string>>();
  cmd->add_option("files", *files, "Species, crystal or scene YAML files")->required();
  cmd->callback([&context, files] {
    for (const auto& f : *files) check_file(context, f);
  });
}

}  // namespace plumage::cli
