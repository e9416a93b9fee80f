// What a comparison run (comparison.hpp) reports: each method against the reference per incident
// direction, wavelength and polarization (pattern_metrics.hpp: pattern correlation, relative L2
// difference, reflected fractions, Eqs. 8–10), the CSV files of `plumage compare`
// (<name>-metrics.csv, -patterns.csv, -times.csv; docs/formats.md) and its figures (Figs. 8–9).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "plumage/comparison.hpp"
#include "plumage/pattern_metrics.hpp"

namespace plumage {

// One row of the metrics: method `method` against the reference at incident `incident`,
// wavelength `lambda`, polarization `pol` (0, 1; 2 = unpolarised mean).
struct ComparisonRow {
  std::size_t method = 0, incident = 0, lambda = 0;
  int pol = 0;
  PatternComparison metrics;
};

// Per method over the unpolarised rows.
struct MethodSummary {
  double correlation_min = 1e300, correlation_mean = 0.0;
  double rel_l2_mean = 0.0, rel_l2_max = 0.0;
  double abs_dR_max = 0.0;
};

struct ComparisonMetrics {
  std::vector<ComparisonRow> rows;      // method, incident, wavelength, polarization order
  std::vector<MethodSummary> summary;   // one per method
};

ComparisonMetrics compare_methods(const Comparison& comparison, const std::vector<MethodRun>& runs);

// The files' text (also what the writer below writes).
std::string comparison_metrics_csv(const Comparison& comparison, const ComparisonMetrics& metrics);
std::string comparison_patterns_csv(const Comparison& comparison, const std::vector<MethodRun>& runs);
std::string comparison_times_csv(const Comparison& comparison, const std::vector<MethodRun>& runs);

struct ComparisonFiles {
  std::filesystem::path metrics, patterns, times;
};
// Writes <out_dir>/<name>-metrics.csv, -patterns.csv and -times.csv atomically (out_dir is
// created).
ComparisonFiles write_comparison_tables(const Comparison& comparison, const std::vector<MethodRun>& runs,
                                        const ComparisonMetrics& metrics, const std::filesystem::path& out_dir);

// The figures beside the tables: error against cost (one point per method), and per incident
// direction the unpolarised patterns of all methods overlaid per wavelength and colour strips
// along the cone (spectrum → XYZ under D65 → sRGB, one exposure shared by all methods). `wrote`
// is called with each file as it is written. Throws Error when matplotlib fails.
void draw_comparison_figures(const Comparison& comparison, const std::vector<MethodRun>& runs,
                             const ComparisonFiles& tables,
                             const std::function<void(const std::filesystem::path&)>& wrote = {});

}  // namespace plumage
