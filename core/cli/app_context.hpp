// State shared by the subcommands of the `plumage` executable.
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage::cli {

// Bad command-line input: printed without a stack of context, exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AppContext {
 public:
  std::vector<std::filesystem::path> plugin_dirs;  // from --plugin-path
  bool quiet = false;
  std::string tables = "build";  // --tables: build | preview | never

  // How the preparation step (prepare_species) may get a model's tables (--tables), with a
  // progress line on stderr unless --quiet.
  PreparationOptions preparation() const;

  // The registry, loaded on first use from the search path.
  const PluginRegistry& registry();
  // Problems met while loading (printed by `plumage plugins`, and as warnings elsewhere).
  void warn_about_problems() const;

 private:
  std::unique_ptr<PluginRegistry> registry_;
};

}  // namespace plumage::cli
