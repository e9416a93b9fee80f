// The fidelity presets (DESIGN §7): how much a species variant is simulated. Declared once
// (src/pipeline/fidelity.cpp) and used by both places that need one: a species file's
// `simulation:` section (its `fidelity` picks the preset its other keys override,
// species_config.hpp) and a characterisation (characterize_settings.hpp), which reads the same
// section over the preset it was asked for.
//
//   preset      instances  wavelengths (nm)          incident grid  pattern / projected samples
//   preview     10         400, 430, …, 670 (10)     10 × 10        400 / 1024
//   production  50         400, 406, …, 694 (50)     20 × 20        400 / 1024   (the paper's grid)
//   reference   100        400, 403, …, 694 (99)     20 × 20        800 / 2048
//
// Every preset jitters the instances' azimuth by ±2° (spec §0.3). The preview preset is the one
// every shipped preview material and the demo were made with.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace plumage {

// from, from + step, …, up to `to` (inclusive within 1e-9 steps): sample k = from + k · step.
struct SampleRange {
  double from = 0.0;
  double to = 0.0;
  double step = 1.0;
  std::vector<double> samples() const;
};

struct FidelityPreset {
  std::string_view name;
  std::string_view summary;
  int instances = 0;
  SampleRange wavelengths_nm;
  int incident_grid = 0;
  int pattern_samples = 0;
  int projected_samples = 0;
  double azimuth_jitter_deg = 0.0;
};

std::span<const FidelityPreset> fidelity_presets();
// The preset of that name; Error listing the presets for an unknown one.
const FidelityPreset& fidelity_preset(std::string_view name);
std::vector<std::string> fidelity_names();  // in declaration order
// "preview: 10, production: 50, reference: 100": a value per preset, for documentation.
std::string per_preset_text(const std::function<std::string(const FidelityPreset&)>& value);

}  // namespace plumage
