// What a characterisation of one species variant computes (spec geometry-and-brdf §4): the
// incident grid, wavelengths, instances, direction sampling and fit settings. Two runs (or
// shards, MPI ranks, a resumed journal) combine only if their settings agree; the settings'
// fingerprint heads every journal and shard file (characterize_records.hpp).
//
// The settings of a variant at a fidelity: the species file's `simulation:` section read over
// that preset (fidelity.hpp; the section's explicit keys override it), then the overrides of the
// characterisation (CharacterizeOverrides, one parameter table: `plumage characterize
// --instances/--grid/--lambda-nm/--noise-functions/--sigma`, docs/parameters.md).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/lobe_model.hpp"
#include "plumage/param_table.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

struct CharacterizeSettings {
  std::string label;        // species/variant
  std::string config_hash;  // of the species file's bytes (informative: not part of the key)
  std::string variant;
  std::string inputs;       // MaterialInputs::text() of the variant (material_key.hpp)
  std::string fidelity;
  int instances = 0;
  int grid = 0;
  std::vector<double> lambda_nm;
  double bin_width_nm = 6.0;
  int pattern_samples = 400, projected_samples = 1024;
  double jitter_deg = 2.0;
  double sigma = kLobeSigma;
  int noise_functions = 0;

  // Work groups (λ bin w, cos θ_i row a): g = w · grid + (a − 1).
  std::size_t group_count() const { return lambda_nm.size() * static_cast<std::size_t>(grid); }
  // Everything a material's numbers depend on, one part per line: the label, the inputs, the fit
  // revision (fitter.hpp kFitRevision), the fidelity and every setting (hex floats). Comments
  // and layout of the species file do not enter; the file's content, the files it names and
  // the models' plug-in versions do.
  std::string key_text() const;
  std::string key() const;  // fnv1a_hex(key_text()): the material's key, in its .plm header
  // One line heading journals and shard files: the key and the settings (exact, hex floats).
  std::string fingerprint() const;
  // The inverse of fingerprint() with the journal's config hash and inputs (a merge rebuilds the
  // settings from shard headers). Throws Error for records of another fit revision or a
  // fingerprint whose key does not match its inputs.
  static CharacterizeSettings from_fingerprint(const std::string& line, const std::string& config_hash,
                                               const std::string& inputs);
};

// What a characterisation may change of its preset (0 / empty: the preset's value).
struct CharacterizeOverrides {
  int instances = 0;
  int grid = 0;                   // incident nodes per axis
  std::vector<double> lambda_nm;  // ascending
  int noise_functions = 0;        // the table's default
  double sigma = 0.0;             // the table's default
};
const ParamTable<CharacterizeOverrides>& characterize_overrides_table();

// The settings of `config`'s variant at the preset `fidelity` with `overrides` (default: the
// table's defaults); `registry` names the versions of the plug-ins that model it. ConfigError for counts a characterisation cannot use (fewer than 2
// instances or incident nodes), at the species file's key when they came from there.
CharacterizeSettings characterize_settings(const SpeciesConfig& config, const PluginRegistry& registry,
                                           std::string_view fidelity,
                                           const CharacterizeOverrides& overrides = characterize_overrides_table().defaults());

}  // namespace plumage
