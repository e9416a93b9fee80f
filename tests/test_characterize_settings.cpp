// The fidelity presets (plumage/fidelity.hpp), a species file's `simulation:` section over them
// and the settings of a characterisation (plumage/characterize_settings.hpp): one definition of
// each preset, used by the species loader and the characterisation alike.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "plumage/characterize_settings.hpp"
#include "plumage/fidelity.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::registry;

const fs::path kRockDove = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / "rockdove.yaml";

// The rock dove with `simulation:` text appended (a fresh file in a scratch folder).
fs::path rockdove_with(const std::string& simulation, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-characterize-settings";
  fs::create_directories(dir);
  std::ifstream in(kRockDove);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path file = dir / name;
  std::ofstream(file) << text << "\n" << simulation << "\n";
  return file;
}

CharacterizeOverrides overrides_from(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "overrides");
  return characterize_overrides_table().read(doc.root());
}

}  // namespace

TEST_CASE("fidelity presets: preview is what the shipped preview materials were made with", "[characterize][fidelity]") {
  const FidelityPreset& preview = fidelity_preset("preview");
  CHECK(preview.instances == 10);
  CHECK(preview.incident_grid == 10);
  CHECK(preview.pattern_samples == 400);
  CHECK(preview.projected_samples == 1024);
  CHECK(preview.azimuth_jitter_deg == 2.0);
  std::vector<double> lambda;
  for (int k = 0; k < 10; ++k) lambda.push_back(400.0 + 30.0 * k);
  CHECK(preview.wavelengths_nm.samples() == lambda);
  const FidelityPreset& production = fidelity_preset("production");
  CHECK(production.instances == 50);
  CHECK(production.incident_grid == 20);
  CHECK(production.wavelengths_nm.samples().size() == 50);
  CHECK(production.wavelengths_nm.samples().back() == 694.0);
  CHECK(fidelity_names() == std::vector<std::string>{"preview", "production", "reference"});
  CHECK_THROWS_WITH(fidelity_preset("prevue"), Catch::Contains("preview, production, reference"));
}

TEST_CASE("the species loader and the characterisation read one preview", "[characterize][fidelity]") {
  // A species file asking for preview gets the characterisation's preview (not a second one).
  const SpeciesConfig config = load_species_config(rockdove_with("simulation: {fidelity: preview}", "preview.yaml"), registry());
  const FidelityPreset& p = fidelity_preset("preview");
  CHECK(config.simulation.fidelity == "preview");
  CHECK(config.simulation.instances == p.instances);
  CHECK(config.simulation.incident_grid == p.incident_grid);
  CHECK(config.simulation.pattern_samples == p.pattern_samples);
  CHECK(config.simulation.wavelengths_nm == p.wavelengths_nm.samples());
  const CharacterizeSettings s = characterize_settings(config, registry(), "preview");
  CHECK(s.instances == config.simulation.instances);
  CHECK(s.grid == config.simulation.incident_grid);
  CHECK(s.lambda_nm == config.simulation.wavelengths_nm);
  CHECK(s.bin_width_nm == 30.0);
  CHECK(s.sigma == 0.04);
  CHECK(s.noise_functions == 512);
}

TEST_CASE("a species' simulation keys override whichever preset is asked for", "[characterize][fidelity]") {
  const SpeciesConfig config = load_species_config(
      rockdove_with("simulation: {pattern_samples: 300, wavelengths_nm: {step: 60}}", "keys.yaml"), registry());
  // Its own fidelity is production (the default) ...
  CHECK(config.simulation.fidelity == "production");
  CHECK(config.simulation.instances == 50);
  CHECK(config.simulation.pattern_samples == 300);
  CHECK(config.simulation.wavelengths_nm == std::vector<double>{400, 460, 520, 580, 640});
  // ... and a preview characterisation keeps the preview values the file does not set.
  const CharacterizeSettings s = characterize_settings(config, registry(), "preview");
  CHECK(s.fidelity == "preview");
  CHECK(s.instances == 10);
  CHECK(s.grid == 10);
  CHECK(s.pattern_samples == 300);
  CHECK(s.lambda_nm == std::vector<double>{400, 460, 520, 580, 640});
  CHECK(s.bin_width_nm == 60.0);
}

TEST_CASE("characterisation overrides: one table reads, checks and defaults them", "[characterize][fidelity]") {
  const SpeciesConfig config = load_species_config(kRockDove, registry());
  const CharacterizeSettings s = characterize_settings(
      config, registry(), "production", overrides_from("{instances: 3, grid: 4, lambda_nm: ['400:500:50', 620], noise_functions: 8, sigma: 0.05}"));
  CHECK(s.instances == 3);
  CHECK(s.grid == 4);
  CHECK(s.lambda_nm == std::vector<double>{400, 450, 500, 620});
  CHECK(s.bin_width_nm == 50.0);
  CHECK(s.noise_functions == 8);
  CHECK(s.sigma == 0.05);
  CHECK(s.pattern_samples == 400);  // not overridable: the preset's
  const CharacterizeOverrides defaults = characterize_overrides_table().defaults();
  CHECK(defaults.noise_functions == 512);
  CHECK(defaults.sigma == 0.04);
  CHECK_THROWS_AS(overrides_from("{instances: 1}"), ConfigError);
  CHECK_THROWS_WITH(overrides_from("{lambda_nm: [500, 400]}"), Catch::Contains("positive and ascending"));
  CHECK_THROWS_WITH(overrides_from("{lambda_nm: ['400:x:5']}"), Catch::Contains("not a number"));
  CHECK_THROWS_AS(overrides_from("{sigma: 0}"), ConfigError);
  // A count the characterisation cannot use, from the species file, is refused at its key.
  const SpeciesConfig one = load_species_config(rockdove_with("simulation: {instances: 1}", "one.yaml"), registry());
  CHECK_THROWS_WITH(characterize_settings(one, registry(), "preview"), Catch::Contains("simulation.instances"));
}
