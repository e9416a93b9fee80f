#include "app_context.hpp"

#include <iostream>
#include <memory>

#include "plumage/atomic_file.hpp"
#include "plumage/builtin_plugins.hpp"
#include "progress.hpp"

namespace plumage::cli {

void check_output_flag(std::string_view flag, const std::string& path, const std::vector<std::string>& inputs,
                       std::string_view role) {
  if (path.empty()) return;
  check_output_path(path, flag);
  for (const std::string& input : inputs) check_output_not_input(path, flag, input, role);
}

void check_output_folder_flag(std::string_view flag, const std::string& path) { check_output_directory(path, flag); }

const PluginRegistry& AppContext::registry() {
  if (!registry_) {
    registry_ = std::make_unique<PluginRegistry>();
    register_builtin_plugins(*registry_);
    registry_->load_search_path(PluginRegistry::search_path(plugin_dirs));
  }
  return *registry_;
}

PreparationOptions AppContext::preparation() const {
  PreparationOptions options;
  options.tables = tables == "preview" ? PreparationOptions::Tables::preview
                   : tables == "never" ? PreparationOptions::Tables::never
                                       : PreparationOptions::Tables::build;
  if (quiet) return options;
  // A status line for total 0, else one progress bar per kind of work.
  struct Bar {
    std::string what;
    std::unique_ptr<Progress> progress;
  };
  options.progress = [bar = std::make_shared<Bar>()](std::size_t done, std::size_t total, std::string_view what) {
    if (total == 0) {
      std::cerr << what << "\n";
      return;
    }
    if (!bar->progress || bar->what != what) {
      bar->what = std::string(what);
      bar->progress = std::make_unique<Progress>(bar->what, total, false);
    }
    bar->progress->advance(done);
  };
  return options;
}

void AppContext::warn_about_problems() const {
  if (!registry_ || quiet) return;
  for (const auto& p : registry_->problems()) std::cerr << "warning: " << p.message << "\n";
}

}  // namespace plumage::cli
