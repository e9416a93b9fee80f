// `plumage table build|query|plot`: photonic-crystal reflection tables (issue 5).
//   table build CONFIG --fidelity preview|production --out FILE   (table_builder plug-in;
//     resumable: finished runs are kept in FILE.partial until the table is written)
//   table query FILE --lambda-nm 500 --theta-deg 30 --phi-deg 10 [--format text|json]
//   table plot FILE --out PNG                                      (|r|² over λ and angle)
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <memory>

#include "commands.hpp"
#include "plumage/error.hpp"
#include "plumage/table_build.hpp"
#include "plumage/table_report.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct BuildOptions {
  TableBuildRequest request;
  std::string config, out;
  std::optional<double> resolution_nm, k_step;
};

struct QueryOptions {
  std::string file;
  double lambda_nm = 550, theta_deg = 0, phi_deg = 0;
  std::string format = "text";
};

struct PlotOptions {
  std::string file;
  std::string out;
};

void build(AppContext& context, BuildOptions o) {
  check_output_flag("--out", o.out, {o.config}, "crystal config");
  o.request.crystal_config = o.config;
  o.request.out = o.out;
  o.request.resolution_nm = o.resolution_nm;
  o.request.k_step_per_um = o.k_step;
  std::unique_ptr<Progress> bar;
  const TableBuildResult r = build_table_file(o.request, context.registry(),
                                              [&](std::size_t done, std::size_t total, std::string_view what) {
                                                if (!bar) bar = std::make_unique<Progress>(std::string(what), total, context.quiet);
                                                bar->advance(done);
                                              });
  if (!context.quiet) {
    std::cerr << "wrote " << o.out << ": " << r.crystal << ", " << r.grid.n_lambda << " x " << r.grid.n_theta << " x "
              << r.grid.n_phi << " entries, resolution " << r.resolution_nm << " nm\n  " << r.notes << "\n";
  }
}

// A table file given on the command line is user input: a missing or damaged file is exit 2.
ReflectionTable load_input_table(const std::string& file) {
  try {
    return ReflectionTable::load(file);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

void query(const QueryOptions& o) {
  const ReflectionTable t = load_input_table(o.file);
  std::cout << table_query_report(t, o.file, o.lambda_nm, o.theta_deg, o.phi_deg,
                                  o.format == "json" ? TableQueryFormat::json : TableQueryFormat::text);
}

void plot(const PlotOptions& o) {
  check_output_flag("--out", o.out, {o.file}, "table");
  draw_table_overview(load_input_table(o.file), o.file, o.out);
}

}  // namespace

void add_table_command(CLI::App& app, AppContext& context) {
  auto* table = app.add_subcommand("table", "Photonic-crystal reflection tables: build, query, plot");
  table->require_subcommand(1);

  auto b = std::make_shared<BuildOptions>();
  auto* cb = table->add_subcommand("build", "Build a table for a crystal config with a table_builder plug-in");
  cb->add_option("config", b->config, "Crystal config (configs/crystals/*.yaml)")->required();
  cb->add_option("--fidelity", b->request.fidelity, "preview or production")
      ->check(CLI::IsMember({"preview", "production"}))->capture_default_str();
  cb->add_option("--out", b->out, "Table file to write (.plt)")->required();
  cb->add_option("--builder", b->request.builder, "table_builder plug-in")->capture_default_str();
  cb->add_option("--lambda-min", b->request.lambda_min_nm, "Shortest wavelength (nm)")->capture_default_str();
  cb->add_option("--lambda-max", b->request.lambda_max_nm, "Longest wavelength (nm)")->capture_default_str();
  const auto count = [](const char* what, int production, int preview) {
    return std::string(what) + " (default by fidelity: " + std::to_string(production) + " / " + std::to_string(preview) + ")";
  };
  cb->add_option("--n-lambda", b->request.grid.n_lambda, count("Wavelengths", kProductionTableGrid.n_lambda, kPreviewTableGrid.n_lambda))->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cb->add_option("--n-theta", b->request.grid.n_theta, count("cos theta nodes k/n", kProductionTableGrid.n_theta, kPreviewTableGrid.n_theta))->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cb->add_option("--n-phi", b->request.grid.n_phi, count("cos phi_local nodes k/n", kProductionTableGrid.n_phi, kPreviewTableGrid.n_phi))->check(CLI::Range(1, std::numeric_limits<int>::max()));
  cb->add_option("--resolution-nm", b->resolution_nm, "Grid step (default: the builder's for the fidelity)");
  cb->add_option("--k-step", b->k_step, "Bloch-k grid step in 1/um (0: one run per entry)");
  cb->add_flag("--restart", b->request.restart, "Ignore the checkpoint <out>.partial of an interrupted build");
  cb->callback([&context, b] { build(context, *b); });

  auto q = std::make_shared<QueryOptions>();
  auto* cq = table->add_subcommand("query", "Interpolated Jones reflection at one (lambda, theta, phi_local)");
  cq->add_option("file", q->file, "Table file (.plt)")->required();
  cq->add_option("--lambda-nm", q->lambda_nm, "Wavelength (nm)")->capture_default_str();
  cq->add_option("--theta-deg", q->theta_deg, "Longitudinal angle theta (deg)")->capture_default_str();
  cq->add_option("--phi-deg", q->phi_deg, "Local azimuth phi_local (deg)")->capture_default_str();
  cq->add_option("--format", q->format, "Output format")->check(CLI::IsMember({"text", "json"}))->capture_default_str();
  cq->callback([q] { query(*q); });

  auto p = std::make_shared<PlotOptions>();
  auto* cp = table->add_subcommand("plot", "Draw |r|^2 over wavelength and angle, both polarizations");
  cp->add_option("file", p->file, "Table file (.plt)")->required();
  cp->add_option("--out", p->out, "PNG to write")->required();
  cp->callback([p] { plot(*p); });
}

}  // namespace plumage::cli
