// `plumage spectra CONFIG...`: reflectance spectra of each species' nominal local layer stack,
// through the species' own LocalReflection plug-in (plumage/stack_spectra.hpp).
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "grid_parse.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/measured_spectrum.hpp"
#include "plumage/stack_spectra.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::vector<std::string> configs;
  std::string variant;
  std::string lambda_nm = "400:700:5";
  std::string theta_deg = "0,30,60";
  std::string csv;
  std::string plot;
  std::string measured;
  std::optional<double> measured_theta_deg;
  std::optional<std::size_t> measured_column;
};

void run(AppContext& context, const Options& o) {
  const auto lambdas = parse_wavelengths(o.lambda_nm, "--lambda-nm");
  const auto thetas = parse_samples(o.theta_deg, "--theta-deg");
  for (double t : thetas) {
    if (t < 0 || t > 90) throw UsageError("--theta-deg: angles must be in [0, 90]");
  }
  // Validate everything before computing or writing anything.
  check_output_flag("--plot", o.plot, o.configs, "species config");
  check_output_flag("--csv", o.csv, o.configs, "species config");
  if (!o.measured.empty()) {
    check_output_flag("--plot", o.plot, {o.measured}, "measured spectrum");
    check_output_flag("--csv", o.csv, {o.measured}, "measured spectrum");
  }
  // The measurement is read before any computation: a bad file fails fast (exit 2, file:line).
  std::optional<MeasuredSpectrum> measured;
  if (!o.measured.empty()) {
    measured = with_measurement_angle(read_measured_spectrum(o.measured, {o.measured_column}), o.measured_theta_deg);
    for (const auto& c : measured->curves) {
      if (*c.theta_deg < 0 || *c.theta_deg > 90)
        throw UsageError(o.measured + ": " + c.label + ": the angle of incidence must be in [0, 90] (--measured-theta-deg)");
    }
    if (!context.quiet) {
      for (const auto& note : measured->notes) std::cerr << "note: " << o.measured << ": " << note << "\n";
    }
  }
  std::vector<SpeciesConfig> species;
  for (const auto& file : o.configs) species.push_back(load_species_config(file, context.registry(), o.variant));

  std::vector<std::filesystem::path> skipped;
  const auto spectra = nominal_stack_spectra(
      species, lambdas, measured ? with_measured_angles(thetas, *measured) : thetas, context.preparation(), &skipped);
  if (!context.quiet) {
    for (const auto& file : skipped) std::cerr << "note: " << file.string() << ": no nominal_stack/reflection; skipped\n";
  }
  if (spectra.empty()) throw UsageError("none of the configs has a nominal_stack to draw");
  const MeasuredSpectrum* m = measured ? &*measured : nullptr;
  // The numbers go to stderr, beside the notes: stdout may be the CSV.
  if (m) std::cerr << measured_comparison_text(compare_stack_spectra(spectra, *m));
  if (!o.plot.empty()) {
    draw_stack_spectra(spectra, o.plot, m);
    if (!context.quiet) std::cerr << "wrote " << o.plot << "\n";
  }
  const std::string csv = stack_spectra_csv(spectra, m);
  if (!o.csv.empty()) {
    write_text_atomically(o.csv, csv);
    if (!context.quiet) std::cerr << "wrote " << o.csv << "\n";
  } else {
    std::cout << csv;
  }
}

}  // namespace

void add_spectra_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("spectra", "Reflectance spectra of species' nominal layer stacks");
  cmd->add_option("configs", o->configs, "Species YAML files")->required();
  cmd->add_option("--variant", o->variant, "Variant (default: each file's own default)");
  cmd->add_option("--lambda-nm", o->lambda_nm, "Wavelengths, from:to:step or a,b,c")->capture_default_str();
  cmd->add_option("--theta-deg", o->theta_deg, "Angles of incidence in degrees")->capture_default_str();
  cmd->add_option("--csv", o->csv, "Write the table here (default: stdout)");
  cmd->add_option("--plot", o->plot, "Draw the spectra to this PNG");
  cmd->add_option("--measured", o->measured,
                  "A measured reflectance spectrum (CSV/TSV/spectrometer text) to compare with");
  cmd->add_option("--measured-theta-deg", o->measured_theta_deg,
                  "Angle of incidence of the measurement (default: from the file, else 0)");
  cmd->add_option("--measured-column", o->measured_column,
                  "Which reflectance column of a multi-sample file (0 = the first; default: the one named reflectance, "
                  "else the first)");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
