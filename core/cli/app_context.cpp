#include "app_context.hpp"

#include <iostream>

#include "plumage/builtin_plugins.hpp"

namespace plumage::cli {

const PluginRegistry& AppContext::registry() {
  if (!registry_) {
    registry_ = std::make_unique<PluginRegistry>();
    register_builtin_plugins(*registry_);
    registry_->load_search_path(PluginRegistry::search_path(plugin_dirs));
  }
  return *registry_;
}

void AppContext::warn_about_problems() const {
  if (!registry_ || quiet) return;
  for (const auto& p : registry_->problems()) std::cerr << "warning: " << p.message << "\n";
}

}  // namespace plumage::cli
