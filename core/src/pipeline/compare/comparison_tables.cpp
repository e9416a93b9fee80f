// The metrics of a comparison (each method against the reference, pattern_metrics.hpp) and its
// three CSV files (docs/formats.md "compare outputs").
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/comparison_report.hpp"
#include "plumage/conventions.hpp"
#include "plumage/version.hpp"

namespace plumage {

namespace {

namespace fs = std::filesystem;

// Bin width of the pattern directions: pattern_samples bins over (−90°, 90°).
double bin_rad(const Comparison& c) { return kPi / c.pattern_samples; }

std::string pol_name(int p) { return p == 2 ? "mean" : std::to_string(p + 1); }

// "method,theta_i_deg,phi_i_deg,lambda_nm,pol" cells shared by the rows of both CSV files
// (with `reference` after the method in the metrics).
void row_key(std::ostream& out, const Comparison& c, std::size_t i, std::size_t l, int p) {
  out << rad_to_deg(c.incidents[i].theta_rad) << ',' << rad_to_deg(c.incidents[i].phi_rad) << ',' << c.lambdas[l]
      << ',' << pol_name(p) << ',';
}

}  // namespace

ComparisonMetrics compare_methods(const Comparison& c, const std::vector<MethodRun>& runs) {
  ComparisonMetrics out;
  out.summary.resize(c.methods.size());
  const double bin = bin_rad(c);
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    double corr_sum = 0.0, l2_sum = 0.0;
    int n = 0;
    MethodSummary& s = out.summary[mi];
    for (std::size_t i = 0; i < c.incidents.size(); ++i) {
      for (std::size_t l = 0; l < c.lambdas.size(); ++l) {
        for (int p = 0; p < 3; ++p) {
          const auto a = polarised_density(runs[mi].results[i][l], p);
          const auto b = polarised_density(runs[c.reference].results[i][l], p);
          const PatternComparison m = compare_patterns(a, b, bin);
          out.rows.push_back({mi, i, l, p, m});
          if (p != 2) continue;
          s.correlation_min = std::min(s.correlation_min, m.correlation);
          corr_sum += m.correlation;
          s.rel_l2_max = std::max(s.rel_l2_max, m.rel_l2);
          l2_sum += m.rel_l2;
          s.abs_dR_max = std::max(s.abs_dR_max, std::abs(m.total - m.total_ref));
          ++n;
        }
      }
    }
    s.correlation_mean = corr_sum / n;
    s.rel_l2_mean = l2_sum / n;
  }
  return out;
}

std::string comparison_metrics_csv(const Comparison& c, const ComparisonMetrics& metrics) {
  const ComparisonMethod& ref = c.methods[c.reference];
  std::ostringstream out;
  out << std::setprecision(9) << "# plumage compare " << c.file.string() << " (" << kVersionString
      << "): " << c.species.common_name << " (" << c.species.variant << "), instance " << c.instance
      << ", segment " << c.segment_um << " um\n"
      << "# Each method against the reference '" << ref.name << "', per incident direction, wavelength and\n"
      << "# polarization (1, 2, mean = unpolarised), on " << c.pattern_samples
      << " outgoing azimuths phi_o on (-90, 90) deg of the specular cone:\n"
      << "#   correlation: Pearson correlation of the reflectance densities U(phi_o) (Eq. 10, per radian);\n"
      << "#   rel_l2: ||U_method - U_reference||_2 / ||U_reference||_2;\n"
      << "#   R = integral of U over phi_o (midpoint rule), the reflected fraction (Eq. 8 over Eq. 9);\n"
      << "#   dR = R_method - R_reference (absolute).\n"
      << "method,reference,theta_i_deg,phi_i_deg,lambda_nm,pol,correlation,rel_l2,R_method,R_reference,dR\n";
  for (const ComparisonRow& row : metrics.rows) {
    const PatternComparison& m = row.metrics;
    out << c.methods[row.method].name << ',' << ref.name << ',';
    row_key(out, c, row.incident, row.lambda, row.pol);
    out << m.correlation << ',' << m.rel_l2 << ',' << m.total << ',' << m.total_ref << ',' << m.total - m.total_ref
        << '\n';
  }
  return out.str();
}

std::string comparison_patterns_csv(const Comparison& c, const std::vector<MethodRun>& runs) {
  const DirectionSet directions = pattern_directions(c.pattern_samples);
  std::ostringstream out;
  out << std::setprecision(9) << "# Reflectance density U(phi_o) per radian (Eq. 10) of every method; pol 1, 2, mean.\n"
      << "method,theta_i_deg,phi_i_deg,lambda_nm,pol,phi_o_deg,density_per_rad\n";
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    for (std::size_t i = 0; i < c.incidents.size(); ++i) {
      for (std::size_t l = 0; l < c.lambdas.size(); ++l) {
        for (int p = 0; p < 3; ++p) {
          const auto a = polarised_density(runs[mi].results[i][l], p);
          for (std::size_t j = 0; j < a.size(); ++j) {
            out << c.methods[mi].name << ',';
            row_key(out, c, i, l, p);
            out << rad_to_deg(directions.phi_o_rad[j]) << ',' << a[j] << '\n';
          }
        }
      }
    }
  }
  return out.str();
}

std::string comparison_times_csv(const Comparison& c, const std::vector<MethodRun>& runs) {
  std::ostringstream out;
  out << std::setprecision(6)
      << "# Wall time of each method on this machine (prepare: instance-only work such as meshing;\n"
      << "# solve: all wavelengths and incident directions, both polarizations).\n"
      << "method,solver,options,geometry,reflection,regions,prepare_s,solve_s,total_s,solve_s_per_wavelength\n";
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const ComparisonMethod& m = c.methods[mi];
    const MethodRun& r = runs[mi];
    // One CSV cell: the options' commas and double quotes become ';' and '\''.
    std::string options = m.solver_options;
    std::replace(options.begin(), options.end(), ',', ';');
    std::replace(options.begin(), options.end(), '"', '\'');
    out << m.name << ',' << m.solver_type << ',' << options << ',' << geometry_name(m.geometry) << ','
        << m.reflection_note << ',' << r.regions << ',' << r.prepare_s << ',' << r.solve_s << ','
        << r.prepare_s + r.solve_s << ',' << (r.solve_s / static_cast<double>(c.lambdas.size())) << '\n';
  }
  return out.str();
}

ComparisonFiles write_comparison_tables(const Comparison& c, const std::vector<MethodRun>& runs,
                                        const ComparisonMetrics& metrics, const fs::path& out_dir) {
  // All text made before anything is written.
  const std::string metrics_text = comparison_metrics_csv(c, metrics);
  const std::string patterns_text = comparison_patterns_csv(c, runs);
  const std::string times_text = comparison_times_csv(c, runs);
  create_output_directory(out_dir);
  const fs::path base = out_dir / c.name;
  ComparisonFiles files{fs::path(base).concat("-metrics.csv"), fs::path(base).concat("-patterns.csv"),
                        fs::path(base).concat("-times.csv")};
  write_text_atomically(files.metrics, metrics_text);
  write_text_atomically(files.patterns, patterns_text);
  write_text_atomically(files.times, times_text);
  return files;
}

}  // namespace plumage
