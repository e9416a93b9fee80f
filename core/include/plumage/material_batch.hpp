// Every variant of a set of species files made into feather materials of one fidelity in a
// material store's folder (`plumage materials`, `make materials`, issue 26). Resumable at two
// levels: a variant whose material is current (its key, material_store.hpp) is skipped, and an
// interrupted characterisation resumes from its journal (characterize.hpp); a material is
// written atomically, so a killed run leaves no half-written .plm.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/material_store.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage {

// One variant's outcome, reported as soon as it is known.
struct MaterialBatchItem {
  std::size_t index = 0, total = 0;  // 1-based position among all variants of the batch
  std::string label;                 // species/variant
  std::filesystem::path file;        // the material in the store's folder
  bool made = false;                 // characterised now (false: current, skipped)
  double wall_s = 0, cpu_s = 0;      // of the characterisation (0 when skipped)
};

struct MaterialBatchSummary {
  std::size_t made = 0, skipped = 0;
  double wall_s = 0, cpu_s = 0;  // of the characterisations made
};

// The variants of `species_files` in file order, each file's variants in its order; before any
// work every file is loaded (a bad file is a ConfigError, nothing made). `on_start` is called
// before a variant's lookup, `on_item` after it; either may be empty.
MaterialBatchSummary make_materials(const MaterialStore& store, const PluginRegistry& registry,
                                    const std::vector<std::filesystem::path>& species_files,
                                    const std::string& fidelity,
                                    const std::function<void(const MaterialBatchItem&)>& on_start,
                                    const std::function<void(const MaterialBatchItem&)>& on_item);

// The progress lines of `plumage materials`: "[i/N] species/variant: done in X s wall, Y s CPU ->
// file" or "...: skipped (current) file", and the batch's summary.
std::string material_batch_item_line(const MaterialBatchItem& item);
std::string material_batch_item_tag(const MaterialBatchItem& item);  // "[i/N] species/variant"
std::string material_batch_summary_line(const MaterialBatchSummary& summary, const std::string& fidelity,
                                        const std::filesystem::path& folder);

// Whether a material store status line explains a characterisation (a stale or damaged file, a
// resumed journal): the ones a batch shows.
bool explains_characterisation(std::string_view status_line);

}  // namespace plumage
