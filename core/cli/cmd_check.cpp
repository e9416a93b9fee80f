// `plumage check FILE...`: validates configurations without running anything
// (plumage/config_check.hpp), reporting every error of every file; `--resolved` prints what a
// configuration means (each merged variant with every default filled in).
#include <iostream>

#include "commands.hpp"
#include "plumage/config_check.hpp"

namespace plumage::cli {

void add_check_command(CLI::App& app, AppContext& context) {
  auto* cmd = app.add_subcommand("check", "Validate configuration files (every error of every file; exit 2 if any)");
  auto files = std::make_shared<std::vector<std::string>>();
  auto resolved = std::make_shared<bool>(false);
  cmd->add_option("files", *files, "Species, crystal, scene or comparison YAML files")->required();
  cmd->add_flag("--resolved", *resolved,
                "Print each file as the commands see it: every merged variant, every default filled in (YAML)");
  cmd->callback([&context, files, resolved] {
    std::size_t errors = 0, bad_files = 0;
    for (const auto& file : *files) {
      const ConfigCheck check = check_config_file(file, context.registry());
      for (const auto& e : check.errors) std::cerr << "error: " << e << "\n";
      errors += check.errors.size();
      bad_files += check.errors.empty() ? 0 : 1;
      if (!check.errors.empty()) continue;
      if (*resolved) std::cout << resolved_config_yaml(file, context.registry());
      if (context.quiet) continue;
      (*resolved ? std::cerr : std::cout) << file << ": ok (" << check.summary << ")\n";
      for (const auto& work : check.to_prepare) (*resolved ? std::cerr : std::cout) << "  to prepare: " << work << "\n";
    }
    if (errors > 0) {
      throw UsageError("check: " + std::to_string(errors) + " error(s) in " + std::to_string(bad_files) + " of " +
                       std::to_string(files->size()) + " file(s)");
    }
  });
}

}  // namespace plumage::cli
