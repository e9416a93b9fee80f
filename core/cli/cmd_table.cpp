// `plumage table build|query|plot`: photonic-crystal reflection tables (issue 5).
//   table build CONFIG --fidelity preview|production --out FILE   (table_builder plug-in;
//     resumable: finished runs are kept in FILE.partial until the table is written)
//   table query FILE --lambda-nm 500 --theta-deg 30 --phi-deg 10 [--format text|json]
//   table plot FILE --out PNG                                      (|r|² over λ and angle)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>

#include "plumage/charts.hpp"
#include "commands.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/error.hpp"
#include "plumage/reflection_table.hpp"
#include "plumage/table_builder.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();

struct BuildOptions {
  std::string config;
  std::string fidelity = "production";
  std::string out;
  std::string builder = "fdtd_periodic";
  double lambda_lo = 400, lambda_hi = 700;
  int n_lambda = 0, n_theta = 0, n_phi = 0;  // 0: by fidelity (production 50×20×50, preview 16×10×10)
  double resolution_nm = kUnset;            // unset: the builder's default for the fidelity
  double k_step = kUnset;                   // unset: the builder's default
  bool restart = false;                     // ignore an existing checkpoint
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

std::string read_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UsageError("cannot read " + file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void build(AppContext& context, const BuildOptions& o) {
  const CrystalCell cell = load_crystal_cell(o.config);
  const bool preview = o.fidelity == "preview";
  const int nl = o.n_lambda > 0 ? o.n_lambda : (preview ? 16 : 50);
  const int nt = o.n_theta > 0 ? o.n_theta : (preview ? 10 : 20);
  const int np = o.n_phi > 0 ? o.n_phi : (preview ? 10 : 50);
  std::ostringstream params;
  params << "fidelity: " << o.fidelity << "\n";
  // Given values go to the builder unchanged, so it validates them (exit 2 naming the field).
  if (!std::isnan(o.resolution_nm)) params << "resolution_nm: " << o.resolution_nm << "\n";
  if (!std::isnan(o.k_step)) params << "k_step_per_um: " << o.k_step << "\n";
  // Resumable: finished runs go to <out>.partial; a rerun of the same build continues from it.
  const std::string partial = o.out + ".partial";
  if (o.restart) std::filesystem::remove(partial);
  if (o.builder == "fdtd_periodic") params << "checkpoint: \"" << partial << "\"\n";
  const ConfigDocument doc = ConfigDocument::parse(params.str(), "table build options");
  auto builder = context.registry().create_named<TableBuilder>(o.builder, doc.root(), context.registry().context());
  std::unique_ptr<Progress> bar;
  ReflectionTable table = builder->build(
      cell, TableGrid::uniform(o.lambda_lo, o.lambda_hi, nl, nt, np),
      [&](std::size_t done, std::size_t total, std::string_view what) {
        if (!bar) bar = std::make_unique<Progress>(std::string(what), total, context.quiet);
        bar->advance(done);
      });
  table.metadata().config_hash = fnv1a_hex(read_text(o.config));
  // Every warning of the run (plumage/diagnostics.hpp), also those raised outside the builder.
  // Codes the builder already wrote into its notes ("WARNING: … [code]") are not repeated.
  {
    auto& notes = table.metadata().notes;
    std::string extra;
    for (const Warning& w : diagnostics().warnings()) {
      if (notes.find("[" + w.code + "]") != std::string::npos) continue;
      extra += "; WARNING: " + w.message + (w.count > 1 ? " (raised " + std::to_string(w.count) + " times)" : "") +
               " [" + w.code + "]";
    }
    if (!extra.empty()) notes += notes.empty() ? extra.substr(2) : extra;
  }
  table.save(o.out);
  std::filesystem::remove(partial);
  if (!context.quiet) {
    std::cerr << "wrote " << o.out << ": " << cell.name << ", " << nl << " x " << nt << " x " << np
              << " entries, resolution " << table.metadata().resolution_nm << " nm\n  "
              << table.metadata().notes << "\n";
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

// The table's notes (warnings included) inside a JSON string.
std::string json_escape(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (static_cast<unsigned char>(ch) < 0x20) {
      out += ' ';
      continue;
    }
    out += ch;
  }
  return out;
}

void query(const QueryOptions& o) {
  const ReflectionTable t = load_input_table(o.file);
  const JonesReflection r = t.query(o.lambda_nm, deg_to_rad(o.theta_deg), deg_to_rad(o.phi_deg));
  const double Rs = std::norm(r.ss) + std::norm(r.ps), Rp = std::norm(r.pp) + std::norm(r.sp);
  auto c = [](Complex z) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.9g, %.9g", z.real(), z.imag());
    return std::string(buf);
  };
  if (o.format == "json") {
    std::cout << "{\"file\": \"" << o.file << "\", \"crystal\": \"" << t.metadata().crystal
              << "\", \"lambda_nm\": " << o.lambda_nm << ", \"theta_deg\": " << o.theta_deg
              << ", \"phi_deg\": " << o.phi_deg << ", \"jones\": {\"ss\": [" << c(r.ss) << "], \"sp\": ["
              << c(r.sp) << "], \"ps\": [" << c(r.ps) << "], \"pp\": [" << c(r.pp)
              << "]}, \"R_s\": " << Rs << ", \"R_p\": " << Rp << ", \"notes\": \"" << json_escape(t.metadata().notes)
              << "\"}\n";
  } else {
    std::cout << t.metadata().crystal << " at " << o.lambda_nm << " nm, theta " << o.theta_deg
              << " deg, phi_local " << o.phi_deg << " deg (Jones, (s, p) basis)\n"
              << "  ss = " << c(r.ss) << "\n  sp = " << c(r.sp) << "\n  ps = " << c(r.ps)
              << "\n  pp = " << c(r.pp) << "\n  R_s = " << Rs << "  R_p = " << Rp << "\n"
              << "  notes: " << t.metadata().notes << "\n";
  }
}

void plot(const PlotOptions& o) {
  const ReflectionTable t = load_input_table(o.file);
  const auto& L = t.grid().lambda_nm;
  LineChart chart;
  chart.title = t.metadata().crystal + " reflection table (" + o.file + ")";
  chart.x_label = "wavelength (nm)";
  chart.y_label = "|r|^2";
  const double lo = L.front(), hi = L.back();
  const int n = std::max<int>(2, static_cast<int>(L.size()) * 4);
  for (int pol = 0; pol < 2; ++pol) {
    const std::string name = pol == 0 ? "s" : "p";
    for (double a : {0.0, 20.0, 40.0, 60.0, 75.0}) {
      for (int k = 0; k < n; ++k) {
        const double lam = L.size() == 1 ? lo : lo + (hi - lo) * k / (n - 1);
        const JonesReflection rp = t.query(lam, 0.0, deg_to_rad(a));  // in-plane (phi_local)
        const JonesReflection rt = t.query(lam, deg_to_rad(a), 0.0);  // conical (theta)
        const double Rp = pol == 0 ? std::norm(rp.ss) + std::norm(rp.ps) : std::norm(rp.pp) + std::norm(rp.sp);
        const double Rt = pol == 0 ? std::norm(rt.ss) + std::norm(rt.ps) : std::norm(rt.pp) + std::norm(rt.sp);
        char series[64];
        std::snprintf(series, sizeof series, "%g deg", a);
        chart.points.push_back({name + "-pol, theta = 0, angle = phi_local", series, lam, Rp});
        chart.points.push_back({name + "-pol, phi_local = 0, angle = theta", series, lam, Rt});
      }
    }
  }
  draw_line_chart(chart, o.out);
}

}  // namespace

void add_table_command(CLI::App& app, AppContext& context) {
  auto* table = app.add_subcommand("table", "Photonic-crystal reflection tables: build, query, plot");
  table->require_subcommand(1);

  auto b = std::make_shared<BuildOptions>();
  auto* cb = table->add_subcommand("build", "Build a table for a crystal config with a table_builder plug-in");
  cb->add_option("config", b->config, "Crystal config (configs/crystals/*.yaml)")->required();
  cb->add_option("--fidelity", b->fidelity, "preview or production")
      ->check(CLI::IsMember({"preview", "production"}))->capture_default_str();
  cb->add_option("--out", b->out, "Table file to write (.plt)")->required();
  cb->add_option("--builder", b->builder, "table_builder plug-in")->capture_default_str();
  cb->add_option("--lambda-min", b->lambda_lo, "Shortest wavelength (nm)")->capture_default_str();
  cb->add_option("--lambda-max", b->lambda_hi, "Longest wavelength (nm)")->capture_default_str();
  cb->add_option("--n-lambda", b->n_lambda, "Wavelengths (default by fidelity: 50 / 16)");
  cb->add_option("--n-theta", b->n_theta, "cos theta nodes k/n (default 20 / 10)");
  cb->add_option("--n-phi", b->n_phi, "cos phi_local nodes k/n (default 50 / 10)");
  cb->add_option("--resolution-nm", b->resolution_nm, "Grid step (default: the builder's for the fidelity)");
  cb->add_option("--k-step", b->k_step, "Bloch-k grid step in 1/um (0: one run per entry)");
  cb->add_flag("--restart", b->restart, "Ignore the checkpoint <out>.partial of an interrupted build");
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
