// Plug-in types implemented by core itself (no library to load):
//   structure_generator "validation_shape"   circle, coated circle, flat layered slab
//   scattering_solver   "approximate"        paper §4 (local reflection, Eq. 2 currents, far field)
//   accuracy_ladder     "approximate"        the approximate solver's options against the BEM
//                       "fit"                instance count of the fitted lobe
//   benchmark           "simulate"           one work unit of the approximate solver
//                       "geometry"           generation time per species
//                       "ladder"             every registered accuracy ladder: CSV, chart, table
// Call once on every registry that should offer them (the CLI and the tests do).
#pragma once

#include "plumage/plugin_registry.hpp"

namespace plumage {

void register_builtin_plugins(PluginRegistry& registry);

}  // namespace plumage
