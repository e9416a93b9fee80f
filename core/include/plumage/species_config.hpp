// A species configuration (configs/species/<name>.yaml): one barbule species, its colour
// variants, and the plug-ins that model it. A species is data, not code.
//
//   species: rockdove            identifier (enters seeds and file names)
//   common_name: Rock dove
//   variant: forest              the default variant
//   variants:                    per-variant overrides, deep-merged over the rest of the file
//     forest: {}                 (maps merge key by key; lists and scalars replace)
//     jade: {nominal_stack: ...}
//   nominal_stack: {...}         the mean local layer stack (LayerProfile), for quick spectra
//   reflection: {model: multilayer, ...}   the LocalReflection plug-in and its parameters
//   structure: {generator: layered_barbule, ...}   the StructureGenerator plug-in and its
//                                parameters (bound to species and variant, which seed it)
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plumage/config_document.hpp"
#include "plumage/layer_profile.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

struct SpeciesConfig {
  std::filesystem::path file;
  std::string content_hash;  // of the whole file; cache keys add the variant name
  std::string species;
  std::string common_name;
  std::string variant;                // the selected variant
  std::vector<std::string> variants;  // all variants in the file, in file order
  ParamView root;                     // the merged view of the selected variant
  std::optional<LayerProfile> nominal_stack;
  std::shared_ptr<const LocalReflection> reflection;
  std::shared_ptr<const StructureGenerator> structure;
};

// Loads, merges the chosen variant (default: the file's `variant`) and validates every section,
// creating the plug-ins it names. Throws ConfigError on any problem.
SpeciesConfig load_species_config(const std::filesystem::path& file, const PluginRegistry& registry,
                                  const std::string& variant = "");

// The variant names declared in a species file (for `plumage check`, which validates each).
std::vector<std::string> species_variants(const std::filesystem::path& file);

}  // namespace plumage
