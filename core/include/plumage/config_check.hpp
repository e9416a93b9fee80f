// What `plumage check FILE` does, as a library call (issues 22, 23): recognise a configuration by
// its top-level key and load it the way the commands that run it would, without running anything:
// every variant of a species (each merged variant, not only the default), every plug-in section,
// every declared range. Bad input is collected, not thrown: one entry per failing unit (variant,
// scene material, builder section), each the same ConfigError text (file:line:col: field:
// message) the run would print.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "plumage/plugin_registry.hpp"

namespace plumage {

struct ConfigCheck {
  std::string kind;     // species | crystal | scene | comparison ("" when not recognised)
  std::string summary;  // "species, 3 variants", "crystal mallard-green", "scene demo, 1 view(s), ..."
  // What the preparation step would still do for it (species: per variant, "variant: work");
  // checking builds nothing.
  std::vector<std::string> to_prepare;
  // Every error found, each once, in the order found (empty: the file is ok).
  std::vector<std::string> errors;
};

// Never throws for bad input (ConfigError, PluginError): those are in `errors`.
ConfigCheck check_config_file(const std::filesystem::path& file, const PluginRegistry& registry);

// `plumage check --resolved`: the configuration as the commands see it, in YAML — a species as each
// merged variant (one document per variant) with every parameter the declarations read, defaults
// filled in and marked, unit and doc as comments. Other kinds: the file's own tree with the same
// comments. Throws ConfigError (or PluginError) like the run when the file does not load.
std::string resolved_config_yaml(const std::filesystem::path& file, const PluginRegistry& registry);

}  // namespace plumage
