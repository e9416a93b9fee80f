// make_materials (material_batch.hpp): the variants of species files through the material store.
#include "plumage/material_batch.hpp"

#include <sstream>
#include <iomanip>
#include <utility>

#include "plumage/species_config.hpp"

namespace plumage {

namespace fs = std::filesystem;

MaterialBatchSummary make_materials(const MaterialStore& store, const PluginRegistry& registry,
                                    const std::vector<fs::path>& species_files, const std::string& fidelity,
                                    const std::function<void(const MaterialBatchItem&)>& on_start,
                                    const std::function<void(const MaterialBatchItem&)>& on_item) {
  // Every variant loaded first: a typo in the last file fails now, not after hours of work.
  std::vector<SpeciesConfig> configs;
  for (const fs::path& file : species_files) {
    SpeciesConfig first = load_species_config(file, registry);  // its default variant
    const std::vector<std::string> variants = first.variants;   // empty: a file without `variants:`
    if (variants.empty()) configs.push_back(std::move(first));
    for (const std::string& variant : variants) configs.push_back(load_species_config(file, registry, variant));
  }
  MaterialBatchSummary summary;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    MaterialBatchItem item;
    item.index = i + 1;
    item.total = configs.size();
    const CharacterizeSettings s = store.settings(configs[i], fidelity);
    item.label = s.label;
    item.file = store.canonical_path(s);
    if (on_start) on_start(item);
    const ResolvedMaterial r = store.make(configs[i], fidelity);
    item.file = r.file;
    item.made = r.characterised;
    item.wall_s = r.characterise_wall_s;
    item.cpu_s = r.characterise_cpu_s;
    (item.made ? summary.made : summary.skipped) += 1;
    summary.wall_s += item.wall_s;
    summary.cpu_s += item.cpu_s;
    if (on_item) on_item(item);
  }
  return summary;
}

namespace {

std::string seconds(double s) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << s << " s";
  return o.str();
}

}  // namespace

std::string material_batch_item_tag(const MaterialBatchItem& item) {
  return "[" + std::to_string(item.index) + "/" + std::to_string(item.total) + "] " + item.label;
}

std::string material_batch_item_line(const MaterialBatchItem& item) {
  std::string line = material_batch_item_tag(item);
  line += item.made ? ": done in " + seconds(item.wall_s) + " wall, " + seconds(item.cpu_s) + " CPU -> "
                    : std::string(": skipped (current) ");
  return line + item.file.string();
}

std::string material_batch_summary_line(const MaterialBatchSummary& sum, const std::string& fidelity,
                                        const std::filesystem::path& folder) {
  return "materials (" + fidelity + ") in " + folder.string() + ": " + std::to_string(sum.made + sum.skipped) +
         " variants, " + std::to_string(sum.made) + " made, " + std::to_string(sum.skipped) + " skipped (current); " +
         seconds(sum.wall_s) + " wall, " + seconds(sum.cpu_s) + " CPU characterising";
}

bool explains_characterisation(std::string_view line) {
  for (std::string_view word : {"stale", "damaged", "resuming"})
    if (line.find(word) != std::string_view::npos) return true;
  return false;
}

}  // namespace plumage

