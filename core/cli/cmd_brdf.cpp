// `plumage brdf plot FILE.plm --incident "0,0 0,-45 45,0" --out fig.png [--instances K]
//  [--size N] [--exposure E]`: projected-hemisphere plots of a feather material (paper Fig. 10),
// the mean BRDF and K instances per incident (θ_i, φ_i) in degrees; the exposure (stated in the
// picture's title) maps the 99.5th percentile of the mean panels' luminance to 1 unless given.
//
// `plumage brdf check FILE.plm [--transmission T]`: white furnace of the BSDF built from the
// material at every table entry and cell centre (A_r + T <= 1). Exit 1 on a violation.
//
// Both computations are plumage/brdf_report.hpp; this file parses flags and prints.
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "plumage/brdf_report.hpp"
#include "plumage/error.hpp"

namespace plumage::cli {

namespace {

struct PlotOptions {
  std::string file;
  std::string incident = "0,0 0,-45 45,0";
  std::string out;
  int instances = 2;
  int size = 192;
  double exposure = 0.0;  // 0: automatic
};

std::vector<IncidentAngles> parse_incidents(const std::string& text) {
  std::vector<IncidentAngles> out;
  std::istringstream in(text);
  std::string item;
  while (in >> item) {
    const auto comma = item.find(',');
    IncidentAngles v{};
    try {
      if (comma == std::string::npos) throw std::invalid_argument("no comma");
      std::size_t used = 0;
      v.theta_deg = std::stod(item.substr(0, comma), &used);
      if (used != comma) throw std::invalid_argument("theta");
      const std::string rest = item.substr(comma + 1);
      v.phi_deg = std::stod(rest, &used);
      if (used != rest.size()) throw std::invalid_argument("phi");
    } catch (const std::exception&) {
      throw UsageError("--incident: '" + item + "' is not theta,phi in degrees (e.g. \"0,0 0,-45 45,0\")");
    }
    out.push_back(v);
  }
  return out;
}

void plot(const AppContext& context, const PlotOptions& o) {
  check_output_flag("--out", o.out, {o.file}, "material");
  HemispherePlotOptions options;
  options.incidents = parse_incidents(o.incident);
  options.instances = o.instances;
  options.size = o.size;
  options.exposure = o.exposure;
  check_hemisphere_plot_options(options);
  auto material = std::make_shared<const FeatherMaterial>(read_feather_material(o.file));
  const HemispherePanels panels = hemisphere_panels(material, options);
  write_hemisphere_figure(panels, options, *material, o.out);
  if (!context.quiet) std::fprintf(stderr, "wrote %s (exposure %g)\n", o.out.c_str(), panels.exposure);
}

struct CheckOptions {
  std::string file;
  double transmission = FeatherBsdfOptions{}.transmission_albedo;
};

void check(const CheckOptions& o) {
  if (!(o.transmission >= 0.0 && o.transmission <= 1.0)) throw UsageError("--transmission must be in [0, 1]");
  const FurnaceReport r =
      white_furnace(std::make_shared<const FeatherMaterial>(read_feather_material(o.file)), o.transmission);
  std::printf("bin  lambda_nm  T_w      max(A_r+T)  material max A_r (nodes)  nodes with A_r > 1\n");
  for (std::size_t w = 0; w < r.bins.size(); ++w) {
    const FurnaceBin& b = r.bins[w];
    std::printf("%3zu  %9.1f  %.4f   %.5f     %.5f                   %d\n", w, b.lambda_nm, b.transmission, b.worst_total,
                b.material_raw, b.raw_over_one);
  }
  std::printf("worst A_r + T over %zu table entries and cell centres: %.5f; material: %d nodes with A_r > 1 "
              "(worst %.5f)\n",
              r.entries, r.worst_total, r.raw_over_one, r.worst_raw);
  const std::size_t nodes = r.bins.size() * r.nodes_per_bin;
  std::printf("BSDF reflection clamp acts at %d of %zu nodes and %d of %zu cell centres\n", r.clamped_nodes, nodes,
              r.clamped_centres, nodes);
  if (!r.passes()) throw Error(o.file + ": white furnace violated: A_r + T = " + std::to_string(r.worst_total));
}

}  // namespace

void add_brdf_command(CLI::App& app, AppContext& context) {
  auto* brdf = app.add_subcommand("brdf", "Feather BSDF (.plm materials): pictures and the white furnace");
  brdf->require_subcommand(1);
  auto p = std::make_shared<PlotOptions>();
  auto* cp = brdf->add_subcommand("plot", "Projected-hemisphere plots of the mean BRDF and of instances (paper Fig. 10)");
  cp->add_option("file", p->file, "Feather material (.plm)")->required()->check(CLI::ExistingFile);
  cp->add_option("--incident", p->incident, "Incident directions \"theta,phi ...\" in degrees")->capture_default_str();
  cp->add_option("--out", p->out, "PNG to write")->required();
  cp->add_option("--instances", p->instances, "BRDF instances per incident direction")->capture_default_str();
  cp->add_option("--size", p->size, "Pixels per panel side")->capture_default_str();
  cp->add_option("--exposure", p->exposure, "Linear exposure (0: automatic)")->capture_default_str();
  cp->callback([&context, p] { plot(context, *p); });
  auto c = std::make_shared<CheckOptions>();
  auto* cc = brdf->add_subcommand("check", "White furnace of the BSDF at every table entry (A_r + T <= 1)");
  cc->add_option("file", c->file, "Feather material (.plm)")->required()->check(CLI::ExistingFile);
  cc->add_option("--transmission", c->transmission, "Requested diffuse transmission albedo")->capture_default_str();
  cc->callback([c] { check(*c); });
}

}  // namespace plumage::cli
