#include "test_registry.hpp"

#include "plumage/builtin_plugins.hpp"

namespace plumage::testing {

const PluginRegistry& registry() {
  static const PluginRegistry instance = [] {
    PluginRegistry r;
    register_builtin_plugins(r);  // species configs name core's solver and validation shapes
    r.load_directory(PLUMAGE_TEST_PLUGIN_DIR);
    return r;
  }();
  return instance;
}

}  // namespace plumage::testing
