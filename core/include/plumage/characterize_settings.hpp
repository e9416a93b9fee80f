// What a characterisation of one species variant computes (spec geometry-and-brdf §4): the
// incident grid, wavelengths, instances, direction sampling and fit settings. Two runs (or
// shards, MPI ranks, a resumed journal) combine only if their settings agree; the settings'
// fingerprint heads every journal and shard file (characterize_records.hpp).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/species_config.hpp"

namespace plumage {

struct CharacterizeSettings {
  std::string label;        // species/variant
  std::string config_hash;
  std::string variant;
  std::string fidelity;
  int instances = 0;
  int grid = 0;
  std::vector<double> lambda_nm;
  double bin_width_nm = 6.0;
  int pattern_samples = 400, projected_samples = 1024;
  double jitter_deg = 2.0;
  double sigma = 0.04;
  int noise_functions = 512;

  // Work groups (λ bin w, cos θ_i row a): g = w · grid + (a − 1).
  std::size_t group_count() const { return lambda_nm.size() * static_cast<std::size_t>(grid); }
  std::string fingerprint() const;  // one line, exact (hex floats)
  // The inverse of fingerprint() (a merge rebuilds the settings from shard headers). Throws Error
  // for records of another fit revision (fitter.hpp kFitRevision).
  static CharacterizeSettings from_fingerprint(const std::string& line);
};

// Fidelity presets. production: the config's simulation grid (50 λ, 20 × 20, 50 instances).
// preview: 10 instances, λ = 400, 430, …, 670 nm (10 bins of 30 nm), 10 × 10 incident nodes;
// same direction sampling and fits.
CharacterizeSettings preset_settings(const SpeciesConfig& config, const std::string& fidelity, double sigma = 0.04);

}  // namespace plumage
