// Parameter tables of core's own config sections (a species file's `simulation:`, a scene's
// `render:`, a crystal cell, the characterisation settings ...), listed beside the plug-ins' tables
// in `plumage plugins describe --markdown` and docs/parameters.md. A core source file that
// declares a ParamTable for a config section registers it once at namespace scope:
//
//   const ConfigSectionRegistration kSimulationSection{
//       {"species", "simulation", "how much to simulate", [] { return simulation_table().specs(); }}};
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "plumage/plugin.hpp"

namespace plumage {

struct ConfigSection {
  std::string file_kind;  // species | crystal | scene | comparison | command line
  std::string path;       // the section's key path in that file, e.g. "simulation"
  std::string summary;    // one line
  std::function<std::vector<ParamSpec>()> specs;
};

class ConfigSectionRegistration {
 public:
  explicit ConfigSectionRegistration(ConfigSection section);
};

// Every registered section, sorted by (file_kind, path).
std::vector<ConfigSection> config_sections();

class PluginRegistry;
// docs/parameters.md: every config section of core and every plug-in type of the registry, each
// with its parameter table (name, type, unit, default, range, condition, meaning).
std::string parameters_markdown(const PluginRegistry& registry);

}  // namespace plumage
