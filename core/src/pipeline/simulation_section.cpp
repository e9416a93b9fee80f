// A species file's `simulation:` section (species_config.hpp): a fidelity preset (fidelity.hpp)
// and explicit keys that override it, declared once in a parameter table.
#include "simulation_section.hpp"

#include "plumage/config_sections.hpp"
#include "plumage/fidelity.hpp"
#include "plumage/param_table.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

namespace {

const ParamTable<SampleRange>& wavelength_table() {
  const FidelityPreset& p = fidelity_preset("production");
  static const auto table =
      ParamTable<SampleRange>{}
          .number("from", &SampleRange::from, "nm", p.wavelengths_nm.from, Limits::wavelength_nm(), "first wavelength")
          .number("to", &SampleRange::to, "nm", p.wavelengths_nm.to, Limits::wavelength_nm(),
                  "last wavelength (inclusive when on the step)")
          .number("step", &SampleRange::step, "nm", p.wavelengths_nm.step, Limits::positive(), "wavelength step")
          .default_text(per_preset_text([](const FidelityPreset& f) { return format_param_number(f.wavelengths_nm.step); }));
  return table;
}

const ParamTable<SimulationSettings>& simulation_table() {
  const FidelityPreset& p = fidelity_preset("production");
  static const auto table = [&p] {
    std::vector<std::pair<std::string_view, std::string>> presets;
    for (const FidelityPreset& f : fidelity_presets()) presets.emplace_back(f.name, std::string(f.name));
    auto per_preset = [](int FidelityPreset::*field) {
      return per_preset_text([field](const FidelityPreset& f) { return std::to_string(f.*field); });
    };
    using S = SimulationSettings;
    return ParamTable<S>{}
        .choice("fidelity", &S::fidelity, presets, std::string(p.name),
                "the preset (fidelity.hpp) whose values the other keys override")
        .integer("instances", &S::instances, "1", p.instances, Limits::closed(1, 100000),
                 "barbule instances (the statistics are taken across them)")
        .default_text(per_preset(&FidelityPreset::instances))
        .custom("wavelengths_nm", "map", "nm", "the preset's", "wavelengths from, from + step, ..., to",
                [](const ParamView& section, S& s) {
                  if (!section.has("wavelengths_nm")) return;
                  const ParamView w = section.child("wavelengths_nm");
                  wavelength_table().read_into(w, s.wavelength_range);
                  if (s.wavelength_range.to < s.wavelength_range.from)
                    w.fail("to", "the wavelength range is inverted (to < from)");
                })
        .nested_specs(wavelength_table().specs())
        .integer("incident_grid", &S::incident_grid, "1", p.incident_grid, Limits::closed(1, 1000),
                 "G: incident nodes (cos theta_i, cos phi_i) = (a, b)/G, a, b = 1..G")
        .default_text(per_preset(&FidelityPreset::incident_grid))
        .integer("pattern_samples", &S::pattern_samples, "1", p.pattern_samples, Limits::closed(2, 100000),
                 "outgoing bin centres in phi_o on (-90, 90) deg (spec 0.4)")
        .default_text(per_preset(&FidelityPreset::pattern_samples))
        .integer("projected_samples", &S::projected_samples, "1", p.projected_samples, Limits::closed(2, 100000),
                 "outgoing directions uniform in omega_o,x, for the noise statistics")
        .default_text(per_preset(&FidelityPreset::projected_samples))
        .number("azimuth_jitter_deg", &S::azimuth_jitter_deg, "deg", p.azimuth_jitter_deg, Limits::closed(0, 45),
                "instance n of N sees phi_i + delta_n, delta spread linearly over +-jitter (spec 0.3)");
  }();
  return table;
}

const ConfigSectionRegistration kSimulationSection{
    {"species", "simulation", "How much to simulate: a fidelity preset and explicit keys that override it.",
     [] { return simulation_table().specs(); }}};

SimulationSettings preset_simulation(const FidelityPreset& p) {
  SimulationSettings s;
  s.fidelity = std::string(p.name);
  s.instances = p.instances;
  s.wavelength_range = p.wavelengths_nm;
  s.incident_grid = p.incident_grid;
  s.pattern_samples = p.pattern_samples;
  s.projected_samples = p.projected_samples;
  s.azimuth_jitter_deg = p.azimuth_jitter_deg;
  return s;
}

}  // namespace

SimulationSettings read_simulation_section(const ParamView& root, std::string_view fidelity) {
  const std::optional<ParamView> section = root.child_if("simulation");
  std::string name = fidelity.empty() ? std::string("production") : std::string(fidelity);
  if (fidelity.empty() && section) name = simulation_table().read(*section).fidelity;
  SimulationSettings s = preset_simulation(fidelity_preset(name));
  if (section) simulation_table().read_into(*section, s);
  s.fidelity = name;
  s.wavelengths_nm = s.wavelength_range.samples();
  return s;
}

SimulationSettings simulation_settings(const SpeciesConfig& config, std::string_view fidelity) {
  return read_simulation_section(config.root, fidelity);
}

}  // namespace plumage
