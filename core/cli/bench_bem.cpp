// `plumage bench bem`: the full-wave BEM ScatteringSolver (plug-in "bem", issue 6) on a hummingbird
// barbule segment with its exact geometry at one (λ, θ_i), 20 incident azimuths (cos φ_i = 0.05 b,
// spec §1.1), both polarizations, 400 pattern directions; time, peak memory, and the speed ratio of
// the approximate solver on the same barbule. Reaches the plug-in only through the registry.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <regex>
#include <sstream>

#include "bench_record.hpp"
#include "commands.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::cli {

namespace {

struct BemBench {
  std::string config = "configs/species/hummingbird.yaml";
  std::vector<double> widths_um{10.0, 0.3};
  double lambda_nm = 550;
  double theta_deg = 0;
  double ppw = 30;
  int max_dense_unknowns = 20000;
  std::string record;
};

double peak_rss_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / (1024.0 * 1024.0);
}

// The species file with the outline width replaced (corners scaled down for narrow segments),
// written to a temporary file next to nothing else (the config has no relative references).
std::filesystem::path segment_config(const std::string& file, double width_um) {
  std::ifstream in(file);
  if (!in) throw UsageError("bench bem: cannot read " + file);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto outline = s.find("\n  outline:");
  if (outline == std::string::npos) throw UsageError("bench bem: " + file + " has no structure.outline");
  std::string head = s.substr(0, outline), tail = s.substr(outline);
  tail = std::regex_replace(tail, std::regex("(\n    width_um:)[^\n]*"), "$1 " + std::to_string(width_um),
                            std::regex_constants::format_first_only);
  const double corner = std::min(1.0, 0.1 * width_um);
  tail = std::regex_replace(tail, std::regex("(\n    corner_um:)[^\n]*"), "$1 " + std::to_string(corner),
                            std::regex_constants::format_first_only);
  const auto path = std::filesystem::temp_directory_path() /
                    ("plumage-bench-bem-" + std::to_string(getpid()) + ".yaml");
  std::ofstream(path) << head << tail;
  return path;
}

struct Run {
  double width_um = 0, approx_s = 0, bem_s = 0, rss_gb = 0;
  std::string status;
};

Run run_width(AppContext& context, const BemBench& b, double width_um) {
  Run r;
  r.width_um = width_um;
  const auto path = segment_config(b.config, width_um);
  const SpeciesConfig cfg = load_species_config(path, context.registry());
  std::filesystem::remove(path);
  const CrossSection cs = cfg.structure->generate(0);
  const double theta = deg_to_rad(b.theta_deg);
  std::vector<double> phi_i;
  for (int k = 1; k <= 20; ++k) phi_i.push_back(std::acos(0.05 * k));
  const auto phi_o = pattern_directions(400).phi_o_rad;
  // approximate solver (the species' own), best of 3
  auto approx = context.registry().create_named<ScatteringSolver>("approximate", ParamView{}, context.registry().context());
  r.approx_s = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto prep = approx->prepare(cs, cfg.reflection);
    const auto ff = approx->solve(*prep, b.lambda_nm, theta, phi_i, phi_o);
    r.approx_s = std::min(r.approx_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::ostringstream opts;
  opts << "points_per_wavelength: " << b.ppw << "\nmax_dense_unknowns: " << b.max_dense_unknowns << "\n";
  const ConfigDocument doc = ConfigDocument::parse(opts.str(), "bench bem options");
  auto bem = context.registry().create_named<ScatteringSolver>("bem", doc.root(), context.registry().context());
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const auto prep = bem->prepare(cs, cfg.reflection);
    const auto ff = bem->solve(*prep, b.lambda_nm, theta, phi_i, phi_o);
    r.bem_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.status = "solved (dense LU)";
  } catch (const Error& e) {
    r.bem_s = -1;
    r.status = std::string("not solved: ") + e.what();
  }
  r.rss_gb = peak_rss_gb();
  return r;
}

void bench_bem(AppContext& context, const BemBench& b) {
  std::ostringstream md;
  md << std::setprecision(3);
  md << "## bem\n\n"
     << "Full-wave 2.5D BEM (plug-in `bem`, " << b.ppw << " points per wavelength, dense LU) on `" << b.config
     << "` instance 0 with the outline width replaced (corners min(1 um, W/10)), lambda = " << b.lambda_nm
     << " nm, theta_i = " << b.theta_deg
     << " deg, 20 incident azimuths (cos phi_i = 0.05 b), both polarizations, 400 pattern directions. "
        "Approximate solver: the same barbule and directions, prepare + solve, best of 3. Peak RSS of "
        "the whole process so far. Goal (issue 6): 10 um segment in <= 600 s and <= 8 GB; the fast "
        "(GMRES + compressed mat-vec) solver is not implemented, so wide segments are refused by the "
        "dense solver's size guard (message below).\n\n"
     << "| machine | command | date | width um | BEM s | approximate s | ratio | peak RSS GB | status | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (double w : b.widths_um) {
    const Run r = run_width(context, b, w);
    md << "| " << machine_description() << " | `plumage bench bem` | " << today_iso() << " | " << w << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_s) : std::string("-")) << " | " << r.approx_s << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_s / r.approx_s) + "x" : std::string("-")) << " | " << r.rss_gb
       << " | " << r.status << " | <= 600 s, <= 8 GB (W = 10) |\n";
    std::cout << "width " << w << " um: BEM " << r.bem_s << " s, approximate " << r.approx_s << " s, peak RSS "
              << r.rss_gb << " GB; " << r.status << "\n";
  }
  if (!b.record.empty()) {
    record_benchmark(b.record, "bem", md.str());
    std::cerr << "recorded in " << b.record << "\n";
  }
}

}  // namespace

void add_bench_bem_command(CLI::App& bench, AppContext& context) {
  auto b = std::make_shared<BemBench>();
  auto* cmd = bench.add_subcommand("bem", "Full-wave BEM on a hummingbird segment vs the approximate solver");
  cmd->add_option("--config", b->config, "Species config")->capture_default_str();
  cmd->add_option("--width-um", b->widths_um, "Segment widths (um)")->capture_default_str();
  cmd->add_option("--lambda-nm", b->lambda_nm, "Wavelength")->capture_default_str();
  cmd->add_option("--theta-deg", b->theta_deg, "theta_i")->capture_default_str();
  cmd->add_option("--ppw", b->ppw, "BEM points per wavelength")->capture_default_str();
  cmd->add_option("--max-dense-unknowns", b->max_dense_unknowns, "BEM dense size guard")->capture_default_str();
  cmd->add_option("--record", b->record, "Markdown file to record the result in (e.g. docs/benchmarks.md)");
  cmd->callback([&context, b] { bench_bem(context, *b); });
}

}  // namespace plumage::cli
