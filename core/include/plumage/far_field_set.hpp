// FarFieldSet: the simulated far fields of every instance of a variant, per work unit
// (λ, ω_i), both polarizations, with the incident powers Φ_i (paper Eqs. 8–10).
// File format "PLUMFFS" (docs/formats.md): header, units, FNV-1a checksum; written atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "plumage/far_field.hpp"

namespace plumage {

struct FarFieldUnit {
  double lambda_nm = 0.0;
  IncidentDirection nominal;         // the unit's ω_i before per-instance jitter
  std::size_t pattern_count = 0;     // the first pattern_count directions are the pattern set,
                                     // the rest the projected set
  std::vector<FarField> instances;   // all on the same φ_o list
};

struct FarFieldSet {
  // producer, config, config_hash, species, variant, solver, ... (free-form, one line each)
  std::map<std::string, std::string> metadata;
  std::vector<FarFieldUnit> units;
};

inline constexpr std::uint32_t kFarFieldSetVersion = 1;

// Throws Error on I/O failure; the target is replaced only by a complete file.
void write_far_field_set(const FarFieldSet& set, const std::filesystem::path& file);
// Throws Error naming the file for a wrong magic, version, truncation or checksum mismatch.
FarFieldSet read_far_field_set(const std::filesystem::path& file);

// Instance mean of the reflectance density (Eq. 10) per direction: pol 0, pol 1, or −1 for
// the unpolarized mean ½(P¹ + P²).
std::vector<double> mean_reflectance_density(const FarFieldUnit& unit, int pol);

}  // namespace plumage
