// What a species variant's feather materials depend on besides the characterisation settings
// (issue 22, "complete cache keys"): the merged variant as canonical text (comments, layout and
// key order do not matter), every file the variant names (a crystal config, a reflection table:
// any scalar value that names an existing file relative to the species file's folder, YAML files
// by their canonical text and the files they name in turn, others by their bytes), and the
// plug-in types and versions that model it. With the fit revision and the settings it is the
// material's key (characterize_settings.hpp), stored in the .plm header.
#pragma once

#include <string>
#include <vector>

#include "plumage/plugin_registry.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

struct MaterialInputs {
  std::string species;  // fnv1a_hex of the merged variant's canonical text (without `variants`, `variant`)
  struct File {
    std::string where;   // the dotted config path that names it, e.g. "reflection.crystal"
    std::string digest;  // fnv1a_hex of its canonical text (YAML) or bytes
  };
  std::vector<File> files;  // in config order
  struct Model {
    std::string kind, type, version;
  };
  std::vector<Model> models;  // structure generator, local reflection, scattering solver

  // One part per line: "species <digest>", "file <where> <digest>", "model <kind> <type> <version>".
  std::string text() const;
};

MaterialInputs material_inputs(const SpeciesConfig& config, const PluginRegistry& registry);

// The comment-independent identity of a species variant's configuration: fnv1a_hex of the
// `species` and `file` lines of MaterialInputs::text() (models excluded).
std::string config_digest(const std::string& inputs_text);

}  // namespace plumage
