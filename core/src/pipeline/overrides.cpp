// The overrides of a characterisation over its fidelity preset (`plumage characterize
// --instances/--grid/--lambda-nm/--noise-functions/--sigma`), declared once
// (characterize_settings.hpp), and the settings of a species variant at a fidelity.
#include <cmath>
#include <string>

#include "plumage/characterize_settings.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/config_sections.hpp"
#include "plumage/lobe_model.hpp"
#include "plumage/material_key.hpp"
#include "plumage/param_table.hpp"

namespace plumage {

namespace {

// "400" or "400:700:30" (from:to:step, inclusive, as the command line's sample lists).
void append_samples(const ParamView& item, std::vector<double>& out) {
  const std::string text = item.scalar_text();
  const auto c1 = text.find(':');
  if (c1 == std::string::npos) {
    out.push_back(item.scalar_number(Limits::wavelength_nm()));
    return;
  }
  const auto c2 = text.find(':', c1 + 1);
  char* end = nullptr;
  auto number = [&](std::size_t from, std::size_t to) {
    const std::string part = text.substr(from, to == std::string::npos ? std::string::npos : to - from);
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(v)) item.fail_here("'" + part + "' in '" + text + "' is not a number");
    return v;
  };
  if (c2 == std::string::npos) item.fail_here("a range is written from:to:step, got '" + text + "'");
  SampleRange r{number(0, c1), number(c1 + 1, c2), number(c2 + 1, std::string::npos)};
  if (!(r.step > 0) || r.to < r.from) item.fail_here("range '" + text + "' needs from <= to and step > 0");
  if ((r.to - r.from) / r.step > 1e6) item.fail_here("range '" + text + "' has too many samples");
  for (double v : r.samples()) out.push_back(v);
}

void read_wavelengths(const ParamView& section, CharacterizeOverrides& o) {
  if (!section.has("lambda_nm")) return;
  const ParamView list = section.node("lambda_nm");
  std::vector<double> lambda;
  if (list.is_sequence()) {
    for (const ParamView& item : list.items()) append_samples(item, lambda);
  } else {
    append_samples(list, lambda);
  }
  const Limits range = Limits::wavelength_nm();
  for (std::size_t k = 0; k < lambda.size(); ++k) {
    if (!range.admits(lambda[k]))
      section.fail("lambda_nm", "wavelength " + format_param_number(lambda[k]) + " nm is out of range: must be " + range.describe());
    if (k && lambda[k] <= lambda[k - 1]) section.fail("lambda_nm", "wavelengths must be positive and ascending");
  }
  if (lambda.empty()) section.fail("lambda_nm", "no wavelengths");
  o.lambda_nm = std::move(lambda);
}

const ConfigSectionRegistration kOverridesSection{
    {"command line", "characterize",
     "Overrides of a characterisation over its fidelity preset (`plumage characterize --name value`).",
     [] { return characterize_overrides_table().specs(); }}};

// A characterisation needs two instances and two nodes per axis; the values that came from the
// species file's `simulation:` section are refused there.
void check_counts(const SpeciesConfig& config, const CharacterizeSettings& s) {
  auto fail = [&](const char* key, const std::string& message) {
    if (auto section = config.root.child_if("simulation"); section && section->has(key)) section->fail(key, message);
    throw ConfigError({config.file.string(), 0, 0}, key, message);
  };
  if (s.instances < 2) fail("instances", "a characterisation needs at least 2 instances (the statistics need a variance)");
  if (s.grid < 2) fail("incident_grid", "a characterisation needs at least 2 incident nodes per axis");
}

// Work budget (issue 23, plumage/memory_budget.hpp): `--grid 100000` asks for 1e10 fit units per
// wavelength. The preset grids need at most ~1e5 fits and solves (production: 50 x 20 x 20 units,
// 50 x 20 x 50 solves); anything past kMaxWorkUnits (1e8) is a typo, refused before any work.
void check_work_bounds(const CharacterizeSettings& s) {
  const double lambdas = static_cast<double>(s.lambda_nm.size()), grid = s.grid, instances = s.instances;
  const std::string counts = " (" + std::to_string(s.lambda_nm.size()) + " wavelengths, grid " + std::to_string(s.grid) +
                             ", " + std::to_string(s.instances) + " instances)";
  check_work(lambdas * grid * grid, "characterize " + s.label + ": wavelengths x grid^2 fit units" + counts,
             "--grid / simulation.incident_grid or --lambda-nm / simulation.wavelengths_nm");
  check_work(lambdas * grid * instances, "characterize " + s.label + ": wavelengths x grid x instances solves" + counts,
             "--instances / simulation.instances, --grid or --lambda-nm");
}

}  // namespace

const ParamTable<CharacterizeOverrides>& characterize_overrides_table() {
  using O = CharacterizeOverrides;
  static const auto table =
      ParamTable<O>{}
          .integer("instances", &O::instances, "1", 0, Limits::at_least(2),
                   "barbule instances (at least 2: the statistics need a variance)")
          .default_text("the preset's")
          .integer("grid", &O::grid, "1", 0, Limits::at_least(2), "incident nodes per axis G")
          .default_text("the preset's")
          .custom("lambda_nm", "list", "nm", "the preset's",
                  "wavelengths, ascending, in [100, 5000] nm: numbers or from:to:step ranges (e.g. 400,500 or 400:700:30)", read_wavelengths)
          .integer("noise_functions", &O::noise_functions, "1", 512, Limits::closed(1, 65536),
                   "noise pool size (spec 4.8; instance k uses functions 2k and 2k + 1)")
          .number("sigma", &O::sigma, "1", kLobeSigma, Limits::positive(), "D_y spread of both lobes (spec 4.3)");
  return table;
}

CharacterizeSettings characterize_settings(const SpeciesConfig& config, const PluginRegistry& registry,
                                           std::string_view fidelity, const CharacterizeOverrides& o) {
  const SimulationSettings sim = simulation_settings(config, fidelity);
  CharacterizeSettings s;
  s.label = config.species + "/" + config.variant;
  s.config_hash = config.content_hash;
  s.variant = config.variant;
  s.inputs = material_inputs(config, registry).text();
  s.fidelity = sim.fidelity;
  s.pattern_samples = sim.pattern_samples;
  s.projected_samples = sim.projected_samples;
  s.jitter_deg = sim.azimuth_jitter_deg;
  s.instances = o.instances > 0 ? o.instances : sim.instances;
  s.grid = o.grid > 0 ? o.grid : sim.incident_grid;
  s.lambda_nm = o.lambda_nm.empty() ? sim.wavelengths_nm : o.lambda_nm;
  const CharacterizeOverrides defaults = characterize_overrides_table().defaults();
  s.sigma = o.sigma > 0 ? o.sigma : defaults.sigma;
  s.noise_functions = o.noise_functions > 0 ? o.noise_functions : defaults.noise_functions;
  s.bin_width_nm = s.lambda_nm.size() > 1 ? s.lambda_nm[1] - s.lambda_nm[0] : 6.0;
  check_counts(config, s);
  check_work_bounds(s);
  return s;
}

}  // namespace plumage
