// load_species_segment (species_config.hpp): a species file with its outline width replaced.
#include <algorithm>
#include <string>

#include "plumage/config_document.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

SpeciesConfig load_species_segment(const std::filesystem::path& file, double width_um, const PluginRegistry& registry,
                                   const std::string& variant) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ParamView root = doc.root();
  if (!root.has("structure") || !root.node("structure").is_map() || !root.child("structure").has("outline") ||
      !root.child("structure").node("outline").is_map() || !root.child("structure").child("outline").has("width_um")) {
    throw ConfigError(root.mark(), "structure.outline.width_um",
                      "missing: a segment of a chosen width needs the species' outline width to replace");
  }
  const std::string source = "segment of width " + std::to_string(width_um) + " um";
  std::vector<ConfigDocument::Override> overrides{
      {.path = "structure.outline.width_um", .yaml = std::to_string(width_um), .source = source}};
  if (root.child("structure").child("outline").has("corner_um")) {
    overrides.push_back(
        {.path = "structure.outline.corner_um", .yaml = std::to_string(std::min(1.0, 0.1 * width_um)), .source = source});
  }
  const ConfigDocument segment = ConfigDocument::derive(
      root, overrides, doc.directory(), file.string() + " (outline width_um = " + std::to_string(width_um) + ")");
  return load_species_config(segment, registry, variant);
}

}  // namespace plumage
