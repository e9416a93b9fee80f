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
#include "plumage/fidelity.hpp"
#include "plumage/layer_profile.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/scattering_solver.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

// How much to simulate (DESIGN §7): a species file's `simulation:` section. Its `fidelity` picks a
// preset (fidelity.hpp: preview | production | reference, default production) and its other keys
// override the preset's values; parameter table: docs/parameters.md, "species: simulation".
//   simulation: {fidelity: production, instances: 50, wavelengths_nm: {from: 400, to: 694, step: 6},
//                incident_grid: 20, pattern_samples: 400, projected_samples: 1024,
//                azimuth_jitter_deg: 2}
struct SimulationSettings {
  std::string fidelity;
  int instances = 0;
  SampleRange wavelength_range;        // the section's wavelengths_nm: {from, to, step}
  std::vector<double> wavelengths_nm;  // its samples
  int incident_grid = 0;               // (cos θ_i, cos φ_i) = (a, b)/grid, a, b = 1..grid
  int pattern_samples = 0;             // bin centres in φ_o on (−90°, 90°)
  int projected_samples = 0;           // uniform in ω_o,x, for noise statistics
  // Instance n of N sees φ_i + δ_n with δ spread linearly over ±jitter (reference behaviour:
  // smears the per-instance specular direction).
  double azimuth_jitter_deg = 0.0;
};

struct SpeciesConfig {
  std::filesystem::path file;
  std::filesystem::path directory;  // where the names of files it references resolve
  std::string content_hash;  // of the whole file; cache keys add the variant name
  std::string species;
  std::string common_name;
  std::string variant;                // the selected variant
  std::vector<std::string> variants;  // all variants in the file, in file order
  ParamView root;                     // the merged view of the selected variant
  std::optional<LayerProfile> nominal_stack;
  // The selected variant overrides `structure:` but not `nominal_stack:`: the file's nominal_stack
  // describes the base structure, not this one, so it is not used (nominal_stack stays empty) and
  // `plumage spectra` takes the stack under the apex of the variant's own instance 0 (issue 23).
  bool nominal_stack_from_structure = false;
  std::shared_ptr<const LocalReflection> reflection;
  std::shared_ptr<const StructureGenerator> structure;
  std::shared_ptr<const ScatteringSolver> solver;  // `solver:` (default: approximate)
  std::string solver_type;
  SimulationSettings simulation;  // the `simulation:` section over its own fidelity preset
};

// The species' structure generator. A species without `structure:` is refused with one message
// for every command that needs one and for `plumage check` (ConfigError at the file's top, field
// `structure`).
const StructureGenerator& required_structure(const SpeciesConfig& config);

// Loads, merges the chosen variant (default: the file's `variant`) and validates every section,
// creating the plug-ins it names. Throws ConfigError on any problem.
SpeciesConfig load_species_config(const std::filesystem::path& file, const PluginRegistry& registry,
                                  const std::string& variant = "");
// The same from a document in memory (e.g. ConfigDocument::derive of a species file with the
// outline width replaced); relative file names resolve against doc.directory().
SpeciesConfig load_species_config(const ConfigDocument& doc, const PluginRegistry& registry,
                                  const std::string& variant = "");

// The `simulation:` section of a loaded species read over the preset `fidelity` (its explicit
// keys override that preset; "" takes the section's own `fidelity`, as config.simulation does).
SimulationSettings simulation_settings(const SpeciesConfig& config, std::string_view fidelity);

// A barbule segment of a chosen width (benchmarks and accuracy ladders): the species file with
// structure.outline.width_um = width_um and, where the file sets it, structure.outline.corner_um =
// min(1, width_um/10) (narrow segments keep their corners inside the outline), derived as
// yaml-cpp nodes (ConfigDocument::derive) before the variant is merged, then loaded. Both values
// are written as std::to_string writes them (6 decimals), so a segment's geometry is the one its
// benchmark has always measured. Throws ConfigError if the file has no structure.outline.width_um.
SpeciesConfig load_species_segment(const std::filesystem::path& file, double width_um, const PluginRegistry& registry,
                                   const std::string& variant = "");

// The explicit preparation step (issue 22): does every model's pending one-time work (a crystal
// reflection table to build or load) with progress, before any simulation. Idempotent.
void prepare_species(const SpeciesConfig& config, const PreparationOptions& options);
// What prepare_species would do, one line per model ("" for none).
std::string pending_preparation(const SpeciesConfig& config);

// The variant names declared in a species file (for `plumage check`, which validates each).
std::vector<std::string> species_variants(const std::filesystem::path& file);

}  // namespace plumage
