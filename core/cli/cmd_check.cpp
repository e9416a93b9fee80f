// `plumage check FILE...`: validates configurations without running anything
// (plumage/config_check.hpp).
#include <iostream>

#include "commands.hpp"
#include "plumage/config_check.hpp"

namespace plumage::cli {

void add_check_command(CLI::App& app, AppContext& context) {
  auto* cmd = app.add_subcommand("check", "Validate configuration files (exit 2 on the first error)");
  auto files = std::make_shared<std::vector<std::string>>();
  cmd->add_option("files", *files, "Species, crystal, scene or comparison YAML files")->required();
  cmd->callback([&context, files] {
    for (const auto& file : *files) {
      const ConfigCheck check = check_config_file(file, context.registry());
      if (context.quiet) continue;
      std::cout << file << ": ok (" << check.summary << ")\n";
      for (const auto& work : check.to_prepare) std::cout << "  to prepare: " << work << "\n";
    }
  });
}

}  // namespace plumage::cli
