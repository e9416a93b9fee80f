// For the YAML-config harnesses: a copy of the repository's configs/ in the scratch folder, so
// that an input written to <scratch>/configs/<kind>/fuzz-input.yaml resolves the relative file
// names the real configs use (../crystals/mallard-green.yaml, ../species/rockdove.yaml), and a
// plug-in registry with core's built-in structure and solver types plus the multilayer and photonic_crystal plug-ins
// compiled in (the species configs name their types; a registry without them would refuse every
// real species at its first section).
#pragma once

#include <filesystem>

#include "fuzz_common.hpp"
#include "plumage/plugin_registry.hpp"
#include "solver/approximate_solver.hpp"

// The plug-ins' entry points, renamed per plug-in when compiled into the harness (fuzz/CMakeLists.txt).
namespace plumage_plugin_exports_multilayer {
void register_plugin(::plumage::Registrar& registrar);
}
namespace plumage_plugin_exports_photonic_crystal {
void register_plugin(::plumage::Registrar& registrar);
}

namespace plumage {
void register_validation_shape(PluginRegistry& registry);  // core/src/geometry/validation_shape.cpp
}

namespace plumage::fuzz {

inline std::filesystem::path config_input(const char* kind) {
  static const bool copied = [] {
    std::filesystem::copy(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs", scratch() / "configs",
                          std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
    return true;
  }();
  (void)copied;
  return scratch() / "configs" / kind / "fuzz-input.yaml";
}

inline const PluginRegistry& registry() {
  static const PluginRegistry instance = [] {
    PluginRegistry r;
    // The two built-in types configs name (register_builtin_plugins would add the ladders and
    // benchmarks too, and with them half of core to compile).
    register_validation_shape(r);
    register_approximate_solver(r);
    plumage_plugin_exports_multilayer::register_plugin(r.builtin_registrar());
    plumage_plugin_exports_photonic_crystal::register_plugin(r.builtin_registrar());
    return r;
  }();
  return instance;
}

}  // namespace plumage::fuzz
