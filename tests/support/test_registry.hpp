// Shared test support: the plug-in registry every test of species configs needs (core's
// built-in types plus the plug-ins of this build tree, loaded once per test program), and
// small helpers used by several suites.
#pragma once

#include <string>

#include "plumage/cross_section.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/species_config.hpp"

namespace plumage::testing {

const PluginRegistry& registry();

// configs/species/<name>.yaml of this source tree, loaded with registry().
SpeciesConfig species(const std::string& name, const std::string& variant = "");

// Distance from p to a polyline monotone in x, looking only at segments within `reach` in x.
double distance_to(const Polyline& line, Vec2 p, double reach = 1500.0);

}  // namespace plumage::testing
