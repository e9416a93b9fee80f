// `plumage simulate CONFIG`: geometry → far fields of every instance for each work unit
// (λ, ω_i) → a FarFieldSet file, plus optional Eq. 10 CSV and a Fig. 7-style picture.
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "plumage/charts.hpp"
#include "commands.hpp"
#include "plumage/diagnostics.hpp"
#include "grid_parse.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/colour.hpp"
#include "plumage/cross_section.hpp"
#include "plumage/data_paths.hpp"
#include "plumage/far_field_set.hpp"
#include "plumage/species_config.hpp"
#include "plumage/version.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string config;
  std::string variant;
  std::string lambda_nm;  // default: the config's simulation wavelengths
  std::string theta_deg = "0";
  std::string phi_deg = "0";
  int instances = 0;  // default: the config's
  std::string out;
  std::string pattern;
  std::string csv;
  std::string directions = "pattern";  // pattern (pattern + projected sets) | full
};

// Full-circle far fields (`--directions full`, validation bodies): 1° steps over (−180°, 180°].
constexpr int kFullCircleSamples = 360;

// Azimuth offset of instance n of N: spread linearly over ±jitter (spec §1.1).
double jitter_rad(int n, int count, double jitter_deg) {
  if (count < 2 || jitter_deg == 0.0) return 0.0;
  return deg_to_rad(-jitter_deg + 2.0 * jitter_deg * n / (count - 1));
}

// `--directions full`: the instance mean of the 2D differential scattering width.
//   dσ/dφ_o = cos θ_i |𝓔(φ_o)|²   (nm per radian)
// is the scattered power per unit barbule length and per radian of φ_o divided by the incident
// irradiance |E_i|²/(2η0) of the unit-amplitude plane wave (far_field.hpp: cos θ_i |𝓔|²/(2η0)
// is the power per unit length per radian); it integrates over the full circle to the scattering
// width C_sca (B&H; tests/oracles/cylinder_series.hpp). σ_2D = 2π dσ/dφ_o is the "echo width"
// convention, lim 2πρ |E_s|²/|E_i|² at θ_i = 0.
void write_full_circle_csv(const FarFieldSet& set, const std::string& file) {
  std::ostringstream out;
  out << std::setprecision(9)
      << "# 2D differential scattering width over the full circle of outgoing azimuths (1 deg steps),\n"
      << "# instance mean, for a unit-amplitude (1 V/m) incident plane wave:\n"
      << "#   dsigma_dphi_nm = cos(theta_i) |E_far(phi_o)|^2  [nm per radian of phi_o]: scattered power per unit\n"
      << "#     barbule length and per radian divided by the incident irradiance |E_i|^2/(2 eta0); its integral\n"
      << "#     over phi_o is the total scattering width C_sca [nm];\n"
      << "#   sigma_2d_nm = 2 pi dsigma_dphi_nm [nm] (= lim 2 pi rho |E_s|^2/|E_i|^2 at theta_i = 0, 'echo width').\n"
      << "# E_far: far-field amplitude, E ~ exp(i gamma0 rho) rho^(-1/2) E_far (far_field.hpp), V/m*sqrt(nm).\n"
      << "# Only meaningful for plane-wave incidence (bem: incidence: plane_wave); a solver that\n"
      << "# illuminates with a beam gives E_far for a beam of unit peak amplitude instead.\n"
      << "# phi_o from +z (the macro normal) toward +x; pol: 1, 2, or mean = (pol1 + pol2)/2.\n"
      << "lambda_nm,theta_i_deg,phi_i_deg,pol,phi_o_deg,dsigma_dphi_nm,sigma_2d_nm\n";
  for (const auto& u : set.units) {
    const auto& phi = u.instances.front().phi_o_rad;
    const double ct = std::cos(u.nominal.theta_rad);
    std::array<std::vector<double>, 2> width{std::vector<double>(phi.size(), 0.0), std::vector<double>(phi.size(), 0.0)};
    for (const auto& ff : u.instances) {
      for (int p = 0; p < 2; ++p) {
        for (std::size_t j = 0; j < phi.size(); ++j) {
          const auto& f = ff.field[p][j];
          width[p][j] += ct * (std::norm(f[0]) + std::norm(f[1]) + std::norm(f[2])) /
                         static_cast<double>(u.instances.size());
        }
      }
    }
    for (int p = 0; p < 3; ++p) {
      for (std::size_t j = 0; j < phi.size(); ++j) {
        const double v = p < 2 ? width[p][j] : 0.5 * (width[0][j] + width[1][j]);
        out << u.lambda_nm << ',' << rad_to_deg(u.nominal.theta_rad) << ',' << rad_to_deg(u.nominal.phi_rad)
            << ',' << (p == 2 ? "mean" : std::to_string(p + 1)) << ',' << rad_to_deg(phi[j]) << ',' << v
            << ',' << 2.0 * kPi * v << '\n';
      }
    }
  }
  write_text_atomically(file, out.str());
}

void write_csv(const FarFieldSet& set, const std::string& file) {
  std::ostringstream out;
  out << std::setprecision(9)
      << "# Instance-mean reflectance density per radian of phi_o (paper Eq. 10):\n"
      << "#   U = mean_n cos(theta_i) |E_far|^2 / (2 eta0 Phi_i), with Phi_i the incident power on\n"
      << "#   the lit, windowed top surface (Eq. 9); integrating U over phi_o gives the reflected\n"
      << "#   fraction. pol: 1, 2, or mean = (pol1 + pol2)/2. Pattern direction set only.\n"
      << "lambda_nm,theta_i_deg,phi_i_deg,pol,phi_o_deg,density_per_rad\n";
  for (const auto& u : set.units) {
    const auto d1 = mean_reflectance_density(u, 0), d2 = mean_reflectance_density(u, 1);
    const auto& phi = u.instances.front().phi_o_rad;
    for (int p = 0; p < 3; ++p) {
      for (std::size_t j = 0; j < u.pattern_count; ++j) {
        const double v = p == 0 ? d1[j] : p == 1 ? d2[j] : 0.5 * (d1[j] + d2[j]);
        out << u.lambda_nm << ',' << rad_to_deg(u.nominal.theta_rad) << ','
            << rad_to_deg(u.nominal.phi_rad) << ',' << (p == 2 ? "mean" : std::to_string(p + 1))
            << ',' << rad_to_deg(phi[j]) << ',' << v << '\n';
      }
    }
  }
  write_text_atomically(file, out.str());
}

// Fig. 7: colour along the cone (spectrum of the density → XYZ under D65 → sRGB, one common
// exposure so strips compare) for the instance mean and three instances, and the mean density
// at a few wavelengths. Drawn by scripts/plot_pattern.py from two CSV files.
void draw_pattern(const FarFieldSet& set, const std::string& png, const std::string& title) {
  std::vector<double> lambdas;
  std::vector<const FarFieldUnit*> units;
  for (const auto& u : set.units) {
    if (!units.empty() && (u.nominal.theta_rad != units.front()->nominal.theta_rad ||
                           u.nominal.phi_rad != units.front()->nominal.phi_rad)) {
      continue;  // one incident direction per picture: the first one
    }
    units.push_back(&u);
    lambdas.push_back(u.lambda_nm);
  }
  if (lambdas.size() < 2) throw UsageError("--pattern needs at least two wavelengths");
  const std::size_t dirs = units.front()->pattern_count;
  const int shown = std::min<int>(3, static_cast<int>(units.front()->instances.size()));
  // rows: 0 = mean, 1..3 = instances; spectra[row][direction][λ]
  std::vector<std::vector<std::vector<double>>> spectra(1 + shown,
      std::vector<std::vector<double>>(dirs, std::vector<double>(lambdas.size())));
  for (std::size_t l = 0; l < units.size(); ++l) {
    const auto mean = mean_reflectance_density(*units[l], -1);
    for (std::size_t j = 0; j < dirs; ++j) {
      spectra[0][j][l] = mean[j];
      for (int n = 0; n < shown; ++n) {
        const auto& ff = units[l]->instances[n];
        spectra[1 + n][j][l] = 0.5 * (ff.reflectance_density(0, j) + ff.reflectance_density(1, j));
      }
    }
  }
  SpectralToXyz to_xyz(lambdas);
  double peak = 0;
  std::vector<std::vector<Xyz>> xyz(spectra.size(), std::vector<Xyz>(dirs));
  for (std::size_t r = 0; r < spectra.size(); ++r) {
    for (std::size_t j = 0; j < dirs; ++j) {
      xyz[r][j] = to_xyz.apply(spectra[r][j]);
      if (r == 0) peak = std::max(peak, xyz[r][j].y);
    }
  }
  const double exposure = peak > 0 ? 1.0 / peak : 1.0;  // brightest mean direction at Y = 1
  const std::filesystem::path base(png);
  const auto strips_csv = std::filesystem::path(png).concat(".strips.csv.tmp");
  const auto lines_csv = std::filesystem::path(png).concat(".lines.csv.tmp");
  {
    std::ofstream s(strips_csv);
    s << "row,phi_o_deg,r,g,b\n";
    const auto& phi = units.front()->instances.front().phi_o_rad;
    for (std::size_t r = 0; r < xyz.size(); ++r) {
      for (std::size_t j = 0; j < dirs; ++j) {
        const Xyz c{xyz[r][j].x * exposure, xyz[r][j].y * exposure, xyz[r][j].z * exposure};
        const Rgb8 rgb = to_srgb8(c, GamutMapping::desaturate);
        s << (r == 0 ? std::string("mean of ") + std::to_string(units.front()->instances.size())
                     : "instance " + std::to_string(r))
          << ',' << rad_to_deg(phi[j]) << ',' << int(rgb.r) << ',' << int(rgb.g) << ',' << int(rgb.b) << '\n';
      }
    }
    std::ofstream l(lines_csv);
    l << "lambda_nm,phi_o_deg,density\n";
    const std::size_t picks[] = {0, units.size() / 3, 2 * units.size() / 3, units.size() - 1};
    for (std::size_t pick : picks) {
      for (std::size_t j = 0; j < dirs; ++j) {
        l << lambdas[pick] << ',' << rad_to_deg(phi[j]) << ',' << spectra[0][j][pick] << '\n';
      }
    }
  }
  draw_script_chart("plot_pattern.py", {strips_csv.string(), lines_csv.string()}, png, title);
  std::filesystem::remove(strips_csv);
  std::filesystem::remove(lines_csv);
}

void run(AppContext& context, const Options& o) {
  const SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
  if (!config.structure) throw UsageError(o.config + ": no `structure:` section to simulate");
  const auto& sim = config.simulation;
  const auto lambdas = o.lambda_nm.empty() ? sim.wavelengths_nm : parse_samples(o.lambda_nm, "--lambda-nm");
  const auto thetas = parse_samples(o.theta_deg, "--theta-deg");
  const auto phis = parse_samples(o.phi_deg, "--phi-deg");
  for (double t : thetas) {
    if (t < 0 || t >= 90) throw UsageError("--theta-deg: angles must be in [0, 90)");
  }
  for (double p : phis) {
    if (std::abs(p) >= 90) throw UsageError("--phi-deg: azimuths must be in (-90, 90)");
  }
  for (double l : lambdas) {
    if (!(l > 0)) throw UsageError("--lambda-nm: wavelengths must be positive");
  }
  const int instances = o.instances > 0 ? o.instances : sim.instances;
  const bool full = o.directions == "full";
  if (full && config.solver_type == "approximate") {
    throw UsageError(o.config + ": --directions full needs a full-wave solver (e.g. `solver: {type: bem, "
                     "incidence: plane_wave}`): the approximate solver radiates only the reflected field of "
                     "the lit top surface, which is meaningful on the upper half of the cone alone "
                     "(--directions pattern)");
  }
  if (full && !o.pattern.empty()) {
    throw UsageError("--pattern draws the reflection pattern on (-90, 90) deg; it is not available with "
                     "--directions full (use --csv)");
  }

  prepare_species(config, context.preparation());  // the explicit preparation step (crystal tables)

  // Geometry and instance-only preparation, once per instance (reused by every unit).
  // An invalid instance (e.g. a segment narrower than the generator's valid range, where
  // platelets cross each other and the outline) would be meshed as given and solved without
  // complaint by a full-wave solver, so it is refused here, as `plumage geometry` refuses it.
  std::vector<std::shared_ptr<const ScatteringSolver::Prepared>> prepared(instances);
  std::vector<std::string> invalid(instances);
  tbb::parallel_for(0, instances, [&](int n) {
    const CrossSection cs = config.structure->generate(static_cast<std::uint64_t>(n));
    if (const auto problems = validate(cs); !problems.empty()) {
      invalid[n] = problems.front() + (problems.size() > 1 ? " (and more)" : "");
      return;
    }
    prepared[n] = config.solver->prepare(cs, config.reflection);
  });
  for (int n = 0; n < instances; ++n) {
    if (!invalid[n].empty()) {
      throw Error(o.config + ": instance " + std::to_string(n) + " is geometrically invalid: " + invalid[n] +
                  " (`plumage geometry " + o.config + " --first " + std::to_string(n) + "` lists every problem)");
    }
  }

  FarFieldSet set;
  set.metadata = {{"producer", std::string("plumage ") + kVersionString},
                  {"config", o.config},
                  {"config_hash", config.content_hash},
                  {"species", config.species},
                  {"variant", config.variant},
                  {"solver", config.solver_type},
                  {"instances", std::to_string(instances)},
                  {"azimuth_jitter_deg", std::to_string(sim.azimuth_jitter_deg)},
                  {"field_units", "V/m*sqrt(nm) for a 1 V/m incident plane wave, e^{-i omega t}"},
                  {"power_units", "W*nm/m^2 (per unit barbule length, nm)"},
                  {"directions", full ? "full_circle: 360 azimuths -180, -179, ..., 179 deg (pattern_count 0)"
                                      : "pattern+projected"}};
  Progress progress("work units", lambdas.size() * thetas.size() * phis.size(), context.quiet);
  std::size_t done = 0;
  for (double theta_deg : thetas) {
    const double theta = deg_to_rad(theta_deg);
    const DirectionSet pattern = pattern_directions(sim.pattern_samples);
    const DirectionSet projected = projected_directions(theta, sim.projected_samples);
    std::vector<double> phi_o = pattern.phi_o_rad;
    phi_o.insert(phi_o.end(), projected.phi_o_rad.begin(), projected.phi_o_rad.end());
    if (full) phi_o = full_circle_directions(kFullCircleSamples).phi_o_rad;
    for (double lambda : lambdas) {
      for (double phi_deg : phis) {
        FarFieldUnit unit;
        unit.lambda_nm = lambda;
        unit.nominal = {theta, deg_to_rad(phi_deg)};
        unit.pattern_count = full ? 0 : pattern.phi_o_rad.size();
        unit.instances.resize(instances);
        tbb::parallel_for(0, instances, [&](int n) {
          const double phi_i[1] = {unit.nominal.phi_rad + jitter_rad(n, instances, sim.azimuth_jitter_deg)};
          unit.instances[n] = config.solver->solve(*prepared[n], lambda, theta, phi_i, phi_o).front();
        });
        set.units.push_back(std::move(unit));
        progress.advance(++done);
      }
    }
  }
  // The run's warnings (plumage/diagnostics.hpp) go into the file's header, one line.
  if (!diagnostics().empty()) set.metadata["warnings"] = diagnostics().summary("; ");
  write_far_field_set(set, o.out);
  if (!context.quiet) std::cerr << "wrote " << o.out << "\n";
  if (!o.csv.empty()) {
    if (full) write_full_circle_csv(set, o.csv);
    else write_csv(set, o.csv);
    if (!context.quiet) std::cerr << "wrote " << o.csv << "\n";
  }
  if (!o.pattern.empty()) {
    std::ostringstream title;
    title << config.common_name << " (" << config.variant << "), θi = " << thetas.front()
          << "°, φi = " << phis.front() << "°";
    draw_pattern(set, o.pattern, title.str());
    if (!context.quiet) std::cerr << "wrote " << o.pattern << "\n";
  }
}

}  // namespace

void add_simulate_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("simulate", "Far fields of every instance of a species (paper §4)");
  cmd->add_option("config", o->config, "Species YAML file")->required();
  cmd->add_option("--variant", o->variant, "Variant (default: the file's)");
  cmd->add_option("--lambda-nm", o->lambda_nm, "Wavelengths (default: the config's simulation grid)");
  cmd->add_option("--theta-deg", o->theta_deg, "Incident θ_i in degrees (list or range)")->capture_default_str();
  cmd->add_option("--phi-deg", o->phi_deg, "Incident φ_i in degrees (list or range)")->capture_default_str();
  cmd->add_option("--instances", o->instances, "Barbule instances (default: the config's)");
  cmd->add_option("--out", o->out, "FarFieldSet file to write (.ffs)")->required();
  cmd->add_option("--pattern", o->pattern, "Draw a Fig. 7-style picture to this PNG");
  cmd->add_option("--csv", o->csv,
                  "Write the instance-mean Eq. 10 patterns as CSV (with --directions full: the 2D "
                  "differential scattering width, normalisation in the header)");
  cmd->add_option("--directions", o->directions,
                  "Outgoing directions: pattern (400 bins on (-90, 90) deg plus the projected set) or "
                  "full (the full circle in 1 deg steps, for validation bodies and full-wave solvers)")
      ->check(CLI::IsMember({"pattern", "full"}))
      ->capture_default_str();
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
