// The plug-in registry every test of species configs needs: core's built-in types plus the
// plug-ins of this build tree (lib/plumage/plugins), loaded once per test program.
#pragma once

#include "plumage/plugin_registry.hpp"

namespace plumage::testing {

const PluginRegistry& registry();

}  // namespace plumage::testing
