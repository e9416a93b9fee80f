// What `plumage check FILE` does, as a library call (issue 22): recognise a configuration by its
// top-level key and load it the way the command that runs it would, without running anything.
// Bad input throws the same ConfigError (file, line, key) the run would throw.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "plumage/plugin_registry.hpp"

namespace plumage {

struct ConfigCheck {
  std::string kind;     // species | crystal | scene | comparison
  std::string summary;  // "species, 3 variants", "crystal mallard-green", "scene demo, 1 view(s), ..."
  // What the preparation step would still do for it (species: per variant, "variant: work");
  // checking builds nothing.
  std::vector<std::string> to_prepare;
};

ConfigCheck check_config_file(const std::filesystem::path& file, const PluginRegistry& registry);

}  // namespace plumage
