// Fig. 7: colour along the cone (spectrum of the density → XYZ under D65 → sRGB, one common
// exposure so strips compare) for the instance mean and three instances, and the mean density
// at a few wavelengths. Drawn by scripts/plot_pattern.py from two CSV files.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include "plumage/atomic_file.hpp"
#include "plumage/charts.hpp"
#include "plumage/colour.hpp"
#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/simulation.hpp"

namespace plumage {

namespace {

namespace fs = std::filesystem;

// The units of the set's first incident direction, in wavelength order.
std::vector<const FarFieldUnit*> first_direction_units(const FarFieldSet& set) {
  std::vector<const FarFieldUnit*> units;
  for (const auto& u : set.units) {
    if (!units.empty() && (u.nominal.theta_rad != units.front()->nominal.theta_rad ||
                           u.nominal.phi_rad != units.front()->nominal.phi_rad)) {
      continue;
    }
    units.push_back(&u);
  }
  return units;
}

// Rows 0 = mean, 1..shown = instances: spectra[row][direction][λ] of the unpolarised density.
std::vector<std::vector<std::vector<double>>> cone_spectra(const std::vector<const FarFieldUnit*>& units, int shown) {
  const std::size_t dirs = units.front()->pattern_count;
  std::vector<std::vector<std::vector<double>>> spectra(
      1 + shown, std::vector<std::vector<double>>(dirs, std::vector<double>(units.size())));
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
  return spectra;
}

void write_inputs(const std::vector<const FarFieldUnit*>& units, const fs::path& strips_csv,
                  const fs::path& lines_csv) {
  std::vector<double> lambdas;
  for (const auto* u : units) lambdas.push_back(u->lambda_nm);
  const std::size_t dirs = units.front()->pattern_count;
  const int shown = std::min<int>(3, static_cast<int>(units.front()->instances.size()));
  const auto spectra = cone_spectra(units, shown);
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
    for (std::size_t j = 0; j < dirs; ++j) l << lambdas[pick] << ',' << rad_to_deg(phi[j]) << ',' << spectra[0][j][pick] << '\n';
  }
}

}  // namespace

void draw_cone_colours(const FarFieldSet& set, const fs::path& png, const std::string& title) {
  const auto units = first_direction_units(set);
  if (units.size() < 2) throw Error("the colour along the cone needs at least two wavelengths");
  check_output_path(png);  // before the temporaries beside it
  const auto strips_csv = fs::path(png).concat(".strips.csv.tmp");
  const auto lines_csv = fs::path(png).concat(".lines.csv.tmp");
  try {
    write_inputs(units, strips_csv, lines_csv);
    draw_script_chart("plot_pattern.py", {strips_csv.string(), lines_csv.string()}, png, title);
  } catch (...) {
    fs::remove(strips_csv);
    fs::remove(lines_csv);
    throw;
  }
  fs::remove(strips_csv);
  fs::remove(lines_csv);
}

}  // namespace plumage
