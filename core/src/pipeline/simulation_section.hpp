// Private to core: reading a species file's `simulation:` section (simulation_section.cpp).
#pragma once

#include <string_view>

#include "plumage/species_config.hpp"

namespace plumage {

// `root`'s `simulation:` section over the preset `fidelity` ("" : the section's own `fidelity`,
// default production).
SimulationSettings read_simulation_section(const ParamView& root, std::string_view fidelity);

}  // namespace plumage
