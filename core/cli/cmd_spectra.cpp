// `plumage spectra CONFIG...`: reflectance spectra of each species' nominal local layer stack,
// through the species' own LocalReflection plug-in: the quick look at what colour a species'
// structure selects, before any geometry or far-field simulation.
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "plumage/charts.hpp"
#include "commands.hpp"
#include "grid_parse.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::vector<std::string> configs;
  std::string variant;
  std::string lambda_nm = "400:700:5";
  std::string theta_deg = "0,30,60";
  std::string csv;
  std::string plot;
};

void run(AppContext& context, const Options& o) {
  const auto lambdas = parse_samples(o.lambda_nm, "--lambda-nm");
  const auto thetas = parse_samples(o.theta_deg, "--theta-deg");
  for (double t : thetas) {
    if (t < 0 || t > 90) throw UsageError("--theta-deg: angles must be in [0, 90]");
  }
  // Validate everything before computing or writing anything.
  std::vector<SpeciesConfig> species;
  for (const auto& file : o.configs) species.push_back(load_species_config(file, context.registry(), o.variant));

  std::ostringstream csv;
  csv << "# unpolarized R = (R_s + R_p)/2 of each species' nominal_stack; theta = angle of "
         "incidence on the stack\n"
      << "species,variant,theta_deg,lambda_nm,R_s,R_p,R\n"
      << std::setprecision(10);
  LineChart chart;
  chart.title = "Reflectance of the nominal layer stack (unpolarized)";
  chart.x_label = "wavelength (nm)";
  chart.y_label = "reflectance";
  int used = 0;
  for (const auto& s : species) {
    if (!s.nominal_stack || !s.reflection) {
      if (!context.quiet) {
        std::cerr << "note: " << s.file.string() << ": no nominal_stack/reflection; skipped\n";
      }
      continue;
    }
    prepare_species(s, context.preparation());
    ++used;
    std::vector<LocalReflection::Request> requests;
    for (double t : thetas) {
      for (double l : lambdas) requests.push_back({l, {0.0, deg_to_rad(t)}, &*s.nominal_stack});
    }
    std::vector<JonesReflection> out(requests.size());
    s.reflection->reflect(requests, out);
    const std::string panel = s.common_name + (s.variant.empty() ? "" : " (" + s.variant + ")");
    for (std::size_t i = 0; i < requests.size(); ++i) {
      const double theta = rad_to_deg(requests[i].incidence.phi_local_rad);
      const double rs = std::norm(out[i].ss), rp = std::norm(out[i].pp);
      csv << s.species << ',' << s.variant << ',' << theta << ',' << requests[i].lambda_nm << ','
          << rs << ',' << rp << ',' << 0.5 * (rs + rp) << '\n';
      std::ostringstream series;
      series << "θ = " << theta << "°";
      chart.points.push_back({panel, series.str(), requests[i].lambda_nm, 0.5 * (rs + rp)});
    }
  }
  if (used == 0) throw UsageError("none of the configs has a nominal_stack to draw");
  if (!o.plot.empty()) {
    draw_line_chart(chart, o.plot);
    if (!context.quiet) std::cerr << "wrote " << o.plot << "\n";
  }
  if (!o.csv.empty()) {
    write_text_atomically(o.csv, csv.str());
    if (!context.quiet) std::cerr << "wrote " << o.csv << "\n";
  } else {
    std::cout << csv.str();
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
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
