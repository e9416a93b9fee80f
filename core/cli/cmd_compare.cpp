// `plumage compare CONFIG`: the paper's accuracy comparison (§6.1, Figs. 8–9) of scattering-solver
// methods on one barbule segment, through the library (plumage/comparison.hpp: schema, runs;
// plumage/comparison_report.hpp: metrics, CSV files, figures). Schema: docs/formats.md.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "plumage/comparison.hpp"
#include "plumage/comparison_report.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

namespace fs = std::filesystem;

struct Options {
  std::string config;
  std::string out;
  bool no_pictures = false;
  ComparisonSelection selection;
};

void print_header(const Comparison& c, const ComparisonSegment& segment) {
  std::cerr << "compare " << c.name << ": " << c.species.common_name << " (" << c.species.variant << "), instance "
            << c.instance << ", segment " << c.segment_um << " um (" << segment.exact.regions.size() << " exact regions"
            << (segment.reduced ? ", " + std::to_string(segment.reduced->regions.size()) + " reduced" : std::string())
            << "), " << c.methods.size() << " methods x " << c.lambdas.size() << " wavelengths x "
            << c.incidents.size() << " incident directions\n";
}

// The unpolarised summary per method on stdout.
void print_summary(const Comparison& c, const std::vector<MethodRun>& runs, const ComparisonMetrics& metrics,
                   const ComparisonFiles& files) {
  std::cout << std::left << std::setw(30) << "method" << std::setw(16) << "geometry" << std::right << std::setw(10)
            << "time_s" << std::setw(12) << "corr_min" << std::setw(12) << "corr_mean" << std::setw(12) << "l2_mean"
            << std::setw(12) << "l2_max" << std::setw(12) << "|dR|_max" << "\n";
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const MethodSummary& s = metrics.summary[mi];
    std::cout << std::left << std::setw(30) << c.methods[mi].name << std::setw(16) << geometry_name(c.methods[mi].geometry)
              << std::right << std::fixed << std::setprecision(3) << std::setw(10)
              << runs[mi].prepare_s + runs[mi].solve_s << std::setprecision(5) << std::setw(12) << s.correlation_min
              << std::setw(12) << s.correlation_mean << std::setw(12) << s.rel_l2_mean << std::setw(12)
              << s.rel_l2_max << std::setw(12) << s.abs_dR_max << std::defaultfloat
              << (mi == c.reference ? "  (reference)" : "") << "\n";
  }
  std::cout << "(unpolarised; per wavelength and polarization in " << files.metrics.string() << ")\n";
}

void run(AppContext& context, const Options& o) {
  check_output_folder_flag("--out", o.out);
  Comparison c = load_comparison(o.config, context.registry());
  select_in_comparison(c, o.selection);
  const fs::path out_dir = o.out.empty() ? fs::path(c.name + "-compare") : fs::path(o.out);
  const ComparisonSegment segment = make_comparison_segment(c);
  if (!context.quiet) print_header(c, segment);
  prepare_comparison(c, context.preparation());

  Progress progress("method-wavelength solves", comparison_solve_count(c), context.quiet);
  const auto runs = run_comparison(c, segment, [&](std::size_t done, std::size_t, double remaining_s) {
    progress.advance(done, remaining_s);
  });
  const ComparisonMetrics metrics = compare_methods(c, runs);
  const ComparisonFiles files = write_comparison_tables(c, runs, metrics, out_dir);
  print_summary(c, runs, metrics, files);
  if (o.no_pictures) return;
  draw_comparison_figures(c, runs, files, [&](const fs::path& file) {
    if (!context.quiet) std::cerr << "wrote " << file.string() << "\n";
  });
}

}  // namespace

void add_compare_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "compare", "Accuracy comparison of scattering solvers on one barbule segment (paper §6.1, Figs. 8-9)");
  cmd->add_option("config", o->config, "Comparison YAML (configs/compare/*.yaml; docs/formats.md)")->required();
  cmd->add_option("--out", o->out, "Output folder (default: <comparison>-compare)");
  cmd->add_flag("--no-pictures", o->no_pictures, "Write the CSV files only");
  cmd->add_option("--only", o->selection.only, "Run only these methods (comma-separated; the reference always runs)")
      ->delimiter(',');
  cmd->add_option("--reference", o->selection.reference, "Compare against this method instead of the config's reference");
  cmd->add_option("--wavelengths", o->selection.wavelengths_nm,
                  "Run only these of the config's wavelengths (nm, comma-separated)")
      ->delimiter(',');
  cmd->add_option("--instance", o->selection.instance, "Barbule instance to compare on instead of the config's `instance`");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
