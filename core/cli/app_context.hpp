// State shared by the subcommands of the `plumage` executable.
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage::cli {

// Bad command-line input: printed without a stack of context, exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Output paths checked before any work (plumage/atomic_file.hpp; OutputPathError, exit status 2):
// a file flag's path must not be a symlink, device, FIFO, socket or folder, nor one of `inputs`
// (named as `role`: "shard", "species config");
// a folder flag's path must not exist as anything but a folder. An empty path (flag not given)
// passes.
void check_output_flag(std::string_view flag, const std::string& path, const std::vector<std::string>& inputs = {},
                       std::string_view role = "input");
void check_output_folder_flag(std::string_view flag, const std::string& path);

// A material's per-code warning lines (plumage/material_warnings.hpp) as characterize and merge
// print them after the fit summary: a heading, then each line indented; nothing if there are none.
std::string material_warnings_report(const std::string& warnings);

class AppContext {
 public:
  std::vector<std::filesystem::path> plugin_dirs;  // from --plugin-path
  bool quiet = false;
  std::string tables = "build";  // --tables: build | preview | never
  std::string max_memory;        // --max-memory SIZE ("" = the machine's, memory_budget.hpp)

  // After parsing: the process's memory budget from --max-memory (UsageError for a bad size) and
  // the step-progress sink that prints long library steps on stderr (none with --quiet).
  void apply_budget_and_progress() const;

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
