// `plumage bench <name>`: measured speed of each backend, optionally recorded in
// docs/benchmarks.md (machine, command, date). Benchmarks measure; they never pass or fail.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include "bench_record.hpp"
#include "commands.hpp"
#include "plumage/local_reflection.hpp"

namespace plumage::cli {

namespace {

struct MultilayerBench {
  int layers = 30;
  int points = 1000;
  int wavelengths = 50;
  int repeats = 5;
  std::string record;
};

void bench_multilayer(AppContext& context, const MultilayerBench& b, const std::string& command) {
  if (b.layers < 1 || b.points < 1 || b.wavelengths < 1 || b.repeats < 1) {
    throw UsageError("bench multilayer: counts must be positive");
  }
  auto model = context.registry().create_named<LocalReflection>("multilayer", ParamView{},
                                                                context.registry().context());
  // A bronzewing-like stack: alternating keratin and melanin with per-point thickness jitter,
  // each point at its own angle, all 50 production wavelengths per point.
  std::mt19937_64 rng(20241203);
  std::uniform_real_distribution<double> jitter(0.9, 1.1), angle(0.0, deg_to_rad(80.0));
  std::vector<LayerProfile> profiles(static_cast<std::size_t>(b.points));
  std::vector<double> angles(profiles.size());
  for (std::size_t p = 0; p < profiles.size(); ++p) {
    for (int j = 0; j < b.layers; ++j) {
      const bool melanin = j % 2 == 1;
      profiles[p].layers.push_back({melanin ? Material::melanin() : Material::keratin(),
                                    (melanin ? 90.0 : 100.0) * jitter(rng)});
    }
    angles[p] = angle(rng);
  }
  std::vector<LocalReflection::Request> requests;
  for (std::size_t p = 0; p < profiles.size(); ++p) {
    for (int w = 0; w < b.wavelengths; ++w) {
      requests.push_back({400.0 + 6.0 * w, {0.0, angles[p]}, &profiles[p]});
    }
  }
  std::vector<JonesReflection> out(requests.size());
  std::vector<double> seconds;
  double checksum = 0;
  for (int r = 0; r < b.repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    model->reflect(requests, out);
    const auto t1 = std::chrono::steady_clock::now();
    seconds.push_back(std::chrono::duration<double>(t1 - t0).count());
    checksum += std::norm(out[out.size() / 2].ss);
  }
  std::sort(seconds.begin(), seconds.end());
  const double per_eval_ns = seconds.front() / static_cast<double>(requests.size()) * 1e9;
  const double median_ns = seconds[seconds.size() / 2] / static_cast<double>(requests.size()) * 1e9;

  std::ostringstream md;
  md << std::fixed << std::setprecision(1);
  md << "## multilayer\n\n"
     << "Time per (surface point, wavelength) for a " << b.layers
     << "-layer keratin/melanin stack, both polarizations (r_s and r_p), one thread, through the "
        "plug-in's batch API (`LocalReflection::reflect`), " << requests.size()
     << " evaluations per run (" << b.points << " points x " << b.wavelengths
     << " wavelengths, each point at its own angle), best and median of " << b.repeats
     << " runs.\n\n"
     << "| machine | command | date | best ns/eval | median ns/eval | goal |\n"
     << "|---|---|---|---|---|---|\n"
     << "| " << machine_description() << " | `" << command << "` | " << today_iso() << " | "
     << per_eval_ns << " | " << median_ns << " | <= 1000 ns |\n";
  std::cout << md.str();
  if (checksum != checksum) std::cerr << "warning: non-finite result in benchmark\n";
  if (!b.record.empty()) {
    record_benchmark(b.record, "multilayer", md.str());
    std::cerr << "recorded in " << b.record << "\n";
  }
}

}  // namespace

void add_bench_command(CLI::App& app, AppContext& context) {
  auto* bench = app.add_subcommand("bench", "Measure the speed of a backend");
  bench->require_subcommand(1);

  auto ml = std::make_shared<MultilayerBench>();
  auto* cmd = bench->add_subcommand("multilayer", "Multilayer reflection: time per (point, wavelength)");
  cmd->add_option("--layers", ml->layers, "Layers in the stack")->capture_default_str();
  cmd->add_option("--points", ml->points, "Surface points (distinct stacks)")->capture_default_str();
  cmd->add_option("--wavelengths", ml->wavelengths, "Wavelengths per point")->capture_default_str();
  cmd->add_option("--repeats", ml->repeats, "Timed runs")->capture_default_str();
  cmd->add_option("--record", ml->record, "Markdown file to record the result in (e.g. docs/benchmarks.md)");
  cmd->callback([&context, ml, cmd] {
    std::ostringstream command;
    command << "plumage bench multilayer --layers " << ml->layers << " --points " << ml->points
            << " --wavelengths " << ml->wavelengths;
    bench_multilayer(context, *ml, command.str());
  });
}

}  // namespace plumage::cli
