// The fidelity presets, declared once (fidelity.hpp).
#include "plumage/fidelity.hpp"

#include <cmath>

#include "plumage/error.hpp"

namespace plumage {

namespace {

constexpr FidelityPreset kPresets[] = {
    {"preview", "for looking: 10 instances, 10 wavelengths of 30 nm, 10 x 10 incident nodes", 10,
     {400.0, 694.0, 30.0}, 10, 400, 1024, 2.0},
    {"production", "the paper's grid: 50 instances, 50 wavelengths of 6 nm, 20 x 20 incident nodes", 50,
     {400.0, 694.0, 6.0}, 20, 400, 1024, 2.0},
    {"reference", "production with twice the instances, wavelengths and direction samples", 100,
     {400.0, 694.0, 3.0}, 20, 800, 2048, 2.0},
};

}  // namespace

std::vector<double> SampleRange::samples() const {
  std::vector<double> out;
  const long n = std::lround(std::floor((to - from) / step + 1e-9));
  for (long k = 0; k <= n; ++k) out.push_back(from + static_cast<double>(k) * step);
  return out;
}

std::span<const FidelityPreset> fidelity_presets() { return kPresets; }

const FidelityPreset& fidelity_preset(std::string_view name) {
  for (const FidelityPreset& p : kPresets)
    if (p.name == name) return p;
  std::string all;
  for (const FidelityPreset& p : kPresets) all += (all.empty() ? "" : ", ") + std::string(p.name);
  throw Error("no fidelity preset '" + std::string(name) + "' (presets: " + all + ")");
}

std::vector<std::string> fidelity_names() {
  std::vector<std::string> out;
  for (const FidelityPreset& p : kPresets) out.emplace_back(p.name);
  return out;
}

std::string per_preset_text(const std::function<std::string(const FidelityPreset&)>& value) {
  std::string out;
  for (const FidelityPreset& p : kPresets) out += (out.empty() ? "" : ", ") + std::string(p.name) + ": " + value(p);
  return out;
}

}  // namespace plumage
