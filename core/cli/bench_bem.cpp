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

#include "plumage/bench_record.hpp"
#include "commands.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::cli {

namespace {

struct BemBench {
  std::string config = "configs/species/hummingbird.yaml";
  std::vector<double> widths_um{10.0};
  double lambda_nm = 550;
  double theta_deg = 0;
  double ppw = 30;
  std::string method = "hmatrix";
  double aca_tolerance = 1e-6;
  double gmres_tolerance = 1e-6;
  int azimuths = 20;  // fewer: a subset spread over the 20 (cos φ_i = 0.05 b), stated in the record
  int max_dense_unknowns = 20000;
  std::vector<std::string> bem_params;  // further solver parameters, key=value (e.g. preconditioner=dense_single)
  std::string record;
};

double peak_rss_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / (1024.0 * 1024.0);
}

struct Run {
  double width_um = 0, approx_s = 0, bem_s = 0, bem_cpu_s = 0, rss_gb = 0;
  std::string status, log;  // log: the solver's own line (sizes, time split, iterations per RHS)
};

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

Run run_width(AppContext& context, const BemBench& b, double width_um) {
  Run r;
  r.width_um = width_um;
  const SpeciesConfig cfg = load_species_segment(b.config, width_um, context.registry());
  const CrossSection cs = cfg.structure->generate(0);
  // Narrow segments can be outside the generator's valid range (at 0.3 um the hummingbird's
  // platelets cross each other and the outline): timing such a mesh would be meaningless.
  if (const auto problems = validate(cs); !problems.empty()) {
    std::ostringstream m;
    m << "bench bem: " << b.config << " at width " << width_um << " um is not a valid cross section ("
      << problems.front() << "); choose a wider segment";
    throw UsageError(m.str());
  }
  prepare_species(cfg, context.preparation());
  const double theta = deg_to_rad(b.theta_deg);
  std::vector<double> phi_i;
  if (b.azimuths >= 20 || b.azimuths < 2) {
    for (int k = 1; k <= 20; ++k) phi_i.push_back(std::acos(0.05 * k));
  } else {
    for (int j = 0; j < b.azimuths; ++j) phi_i.push_back(std::acos(0.05 * (1 + std::lround(19.0 * j / (b.azimuths - 1)))));
  }
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
  const auto log_path = std::filesystem::temp_directory_path() /
                        ("plumage-bench-bem-" + std::to_string(getpid()) + ".log");
  std::filesystem::remove(log_path);
  std::ostringstream opts;
  opts << "points_per_wavelength: " << b.ppw << "\nmax_dense_unknowns: " << b.max_dense_unknowns
       << "\nmethod: " << b.method << "\nlog_file: " << log_path.string() << "\n";
  if (b.method != "dense") {
    opts << "gmres_tolerance: " << b.gmres_tolerance << "\n";
    if (b.method == "hmatrix") opts << "aca_tolerance: " << b.aca_tolerance << "\n";
  }
  for (const std::string& kv : b.bem_params) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UsageError("bench bem: --bem-param '" + kv + "' is not key=value (e.g. preconditioner=dense_single)");
    }
    opts << kv.substr(0, eq) << ": " << kv.substr(eq + 1) << "\n";
  }
  const ConfigDocument doc = ConfigDocument::parse(opts.str(), "bench bem options");
  auto bem = context.registry().create_named<ScatteringSolver>("bem", doc.root(), context.registry().context());
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  try {
    const auto prep = bem->prepare(cs, cfg.reflection);
    const auto ff = bem->solve(*prep, b.lambda_nm, theta, phi_i, phi_o);
    r.bem_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.bem_cpu_s = process_cpu_seconds() - cpu0;
    r.status = "solved (" + b.method + ")";
  } catch (const Error& e) {
    r.bem_s = -1;
    r.status = std::string("not solved: ") + e.what();
  }
  r.rss_gb = peak_rss_gb();
  if (std::ifstream log(log_path); log) std::getline(log, r.log);
  std::filesystem::remove(log_path);
  return r;
}

void bench_bem(AppContext& context, const BemBench& b) {
  std::ostringstream md;
  md << std::setprecision(3);
  md << "## bem\n\n"
     << "Full-wave 2.5D BEM (plug-in `bem`, " << b.ppw << " points per wavelength, method " << b.method;
  if (b.method == "hmatrix") md << ", ACA tolerance " << b.aca_tolerance;
  if (b.method != "dense") md << ", GMRES tolerance " << b.gmres_tolerance;
  md << ") on `" << b.config
     << "` instance 0 with the outline width replaced (corners min(1 um, W/10)), lambda = " << b.lambda_nm
     << " nm, theta_i = " << b.theta_deg
     << " deg, " << (b.azimuths >= 20 || b.azimuths < 2 ? 20 : b.azimuths)
     << " incident azimuths (cos phi_i = 0.05 b; fewer than 20 = a subset spread over them, for both solvers), "
        "both polarizations, 400 pattern directions. "
        "Approximate solver: the same barbule and directions, prepare + solve, best of 3. Peak RSS of "
        "the whole process so far; BEM CPU = process CPU time during the BEM solve (both threads). Goal "
        "(issue 6): 10 um segment in <= 600 s and <= 8 GB. The solver's own line (unknowns, assembly = "
        "near field + ACA, factor = near-field LU, solve = GMRES for all right-hand sides, far field, "
        "H-matrix sizes, GMRES iterations per right-hand side) follows the table.\n\n"
     << "| machine | command | date | width um | BEM s | BEM CPU s | approximate s | ratio | peak RSS GB | status | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::ostringstream logs;
  for (double w : b.widths_um) {
    const Run r = run_width(context, b, w);
    std::ostringstream ppw;
    ppw << b.ppw;
    std::string command = "plumage bench bem --ppw " + ppw.str();
    for (const std::string& kv : b.bem_params) command += " --bem-param " + kv;
    md << "| " << machine_description() << " | `" << command << "` | " << today_iso() << " | " << w
       << " | " << (r.bem_s >= 0 ? std::to_string(r.bem_s) : std::string("-")) << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_cpu_s) : std::string("-")) << " | " << r.approx_s << " | "
       << (r.bem_s >= 0 ? std::to_string(r.bem_s / r.approx_s) + "x" : std::string("-")) << " | " << r.rss_gb
       << " | " << r.status << " | <= 600 s, <= 8 GB (W = 10) |\n";
    std::cout << "width " << w << " um: BEM " << r.bem_s << " s (CPU " << r.bem_cpu_s << " s), approximate "
              << r.approx_s << " s, peak RSS " << r.rss_gb << " GB; " << r.status << "\n" << r.log << "\n";
    if (!r.log.empty()) logs << "\nW = " << w << " um: `" << r.log << "`\n";
  }
  md << logs.str();
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
  cmd->add_option("--azimuths", b->azimuths, "incident azimuths (20 = all; fewer = a spread subset)")->capture_default_str();
  cmd->add_option("--method", b->method, "BEM method: hmatrix | dense | gmres")->capture_default_str();
  cmd->add_option("--aca-tolerance", b->aca_tolerance, "BEM ACA tolerance (method hmatrix)")->capture_default_str();
  cmd->add_option("--gmres-tolerance", b->gmres_tolerance, "BEM GMRES relative residual")->capture_default_str();
  cmd->add_option("--bem-param", b->bem_params,
                  "further bem solver parameter key=value (repeatable; see `plumage plugins`), e.g. "
                  "preconditioner=dense_single");
  cmd->add_option("--record", b->record, "Markdown file to record the result in (e.g. docs/benchmarks.md)");
  cmd->callback([&context, b] { bench_bem(context, *b); });
}

}  // namespace plumage::cli
