// The figures of a comparison: error against cost (scripts/plot_error_cost.py), and per incident
// direction the patterns of all methods (Fig. 8) and colour strips along the cone (Fig. 9,
// scripts/plot_pattern.py).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/charts.hpp"
#include "plumage/colour.hpp"
#include "plumage/comparison_report.hpp"
#include "plumage/conventions.hpp"

namespace plumage {

namespace {

namespace fs = std::filesystem;

// "theta0_phim30" for (0°, −30°): a file-name tag.
std::string incident_tag(const IncidentDirection& d) {
  std::ostringstream s;
  s << "theta" << rad_to_deg(d.theta_rad) << "_phi" << rad_to_deg(d.phi_rad);
  std::string t = s.str();
  std::replace(t.begin(), t.end(), '-', 'm');
  std::replace(t.begin(), t.end(), '.', 'p');
  return t;
}

std::string segment_title(const Comparison& c) {
  std::ostringstream title;
  title << c.species.common_name << ", " << c.segment_um << " um segment";
  return title.str();
}

// The unpolarised patterns of all methods at incident i, one panel per wavelength.
void draw_patterns(const Comparison& c, const std::vector<MethodRun>& runs, std::size_t i, const std::string& title,
                   const fs::path& png) {
  const DirectionSet directions = pattern_directions(c.pattern_samples);
  LineChart chart;
  chart.title = title;
  chart.x_label = "outgoing azimuth phi_o (deg)";
  chart.y_label = "reflectance per rad (Eq. 10), unpolarised";
  for (std::size_t l = 0; l < c.lambdas.size(); ++l) {
    std::ostringstream panel;
    panel << "lambda = " << c.lambdas[l] << " nm";
    for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
      const auto d = unpolarised_density(runs[mi].results[i][l]);
      for (std::size_t j = 0; j < d.size(); ++j) {
        chart.points.push_back({panel.str(), c.methods[mi].name, rad_to_deg(directions.phi_o_rad[j]), d[j]});
      }
    }
  }
  draw_line_chart(chart, png);
}

// Colour strips of every method at incident i (one exposure shared by all methods, so strips
// compare) and the reference pattern at up to four wavelengths under them, as the two CSV inputs
// of scripts/plot_pattern.py.
void write_strip_inputs(const Comparison& c, const std::vector<MethodRun>& runs, std::size_t i,
                        const fs::path& strips_csv, const fs::path& lines_csv) {
  const DirectionSet directions = pattern_directions(c.pattern_samples);
  SpectralToXyz to_xyz(c.lambdas);
  const std::size_t dirs = directions.phi_o_rad.size();
  std::vector<std::vector<Xyz>> xyz(c.methods.size(), std::vector<Xyz>(dirs));
  double peak = 0.0;
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    std::vector<std::vector<double>> per_lambda;
    for (std::size_t l = 0; l < c.lambdas.size(); ++l) per_lambda.push_back(unpolarised_density(runs[mi].results[i][l]));
    std::vector<double> spectrum(c.lambdas.size());
    for (std::size_t j = 0; j < dirs; ++j) {
      for (std::size_t l = 0; l < c.lambdas.size(); ++l) spectrum[l] = per_lambda[l][j];
      xyz[mi][j] = to_xyz.apply(spectrum);
      peak = std::max(peak, xyz[mi][j].y);
    }
  }
  const double exposure = peak > 0.0 ? 1.0 / peak : 1.0;
  std::ofstream s(strips_csv);
  s << "row,phi_o_deg,r,g,b\n";
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    for (std::size_t j = 0; j < dirs; ++j) {
      const Xyz v{xyz[mi][j].x * exposure, xyz[mi][j].y * exposure, xyz[mi][j].z * exposure};
      const Rgb8 rgb = to_srgb8(v, GamutMapping::desaturate);
      s << c.methods[mi].name << ',' << rad_to_deg(directions.phi_o_rad[j]) << ',' << int(rgb.r) << ','
        << int(rgb.g) << ',' << int(rgb.b) << '\n';
    }
  }
  std::ofstream ln(lines_csv);
  ln << "lambda_nm,phi_o_deg,density\n";
  std::set<std::size_t> picks;
  for (std::size_t q = 0; q < 4; ++q) picks.insert(q * (c.lambdas.size() - 1) / 3);
  for (std::size_t l : picks) {
    const auto d = unpolarised_density(runs[c.reference].results[i][l]);
    for (std::size_t j = 0; j < dirs; ++j) ln << c.lambdas[l] << ',' << rad_to_deg(directions.phi_o_rad[j]) << ',' << d[j] << '\n';
  }
}

void draw_strips(const Comparison& c, const std::vector<MethodRun>& runs, std::size_t i, const std::string& title,
                 const fs::path& png) {
  check_output_path(png);  // before the temporaries beside it
  const fs::path strips_csv = fs::path(png).concat(".strips.csv.tmp");
  const fs::path lines_csv = fs::path(png).concat(".lines.csv.tmp");
  try {
    write_strip_inputs(c, runs, i, strips_csv, lines_csv);
    draw_script_chart("plot_pattern.py", {strips_csv.string(), lines_csv.string()}, png,
                      title + " (lines: reference " + c.methods[c.reference].name + ")");
  } catch (...) {
    fs::remove(strips_csv);
    fs::remove(lines_csv);
    throw;
  }
  fs::remove(strips_csv);
  fs::remove(lines_csv);
}

}  // namespace

void draw_comparison_figures(const Comparison& c, const std::vector<MethodRun>& runs, const ComparisonFiles& tables,
                             const std::function<void(const fs::path&)>& wrote) {
  const auto report = [&](const fs::path& file) {
    if (wrote) wrote(file);
  };
  const fs::path base = tables.metrics.parent_path() / c.name;
  {
    // Error against the reference versus cost, one point per method.
    const fs::path png = fs::path(base).concat("-error-vs-cost.png");
    draw_script_chart("plot_error_cost.py", {}, png,
                      segment_title(c) + ": error against " + c.methods[c.reference].name + " versus cost",
                      {"--run", c.name, tables.metrics.string(), tables.times.string()});
    report(png);
  }
  for (std::size_t i = 0; i < c.incidents.size(); ++i) {
    std::ostringstream title;
    title << segment_title(c) << ", theta_i = " << rad_to_deg(c.incidents[i].theta_rad)
          << " deg, phi_i = " << rad_to_deg(c.incidents[i].phi_rad) << " deg";
    const fs::path pattern_png = fs::path(base).concat("-patterns-" + incident_tag(c.incidents[i]) + ".png");
    draw_patterns(c, runs, i, title.str(), pattern_png);
    report(pattern_png);
    if (c.lambdas.size() < 2) continue;  // colour needs a spectrum
    const fs::path strips_png = fs::path(base).concat("-colours-" + incident_tag(c.incidents[i]) + ".png");
    draw_strips(c, runs, i, title.str(), strips_png);
    report(strips_png);
  }
}

}  // namespace plumage
