// `plumage bench <name>`: measured speed of each backend, optionally recorded in
// docs/benchmarks.md (machine, command, date). Benchmarks measure; they never pass or fail.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "commands.hpp"
#include "param_flags.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/config_document.hpp"
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

// `plumage bench <type> [--param value ...] [--record FILE]`: the registered benchmark of that type
// (benchmark.hpp) with its parameters from the flags (param_flags.hpp).
void run_registered_benchmark(AppContext& context, std::vector<std::string> args) {
  std::string record;  // --record FILE is the command's, not the benchmark's
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--record" || args[i].rfind("--record=", 0) == 0) {
      const bool inline_value = args[i].size() > 8;
      if (!inline_value && i + 1 >= args.size()) throw UsageError("--record: needs a file");
      record = inline_value ? args[i].substr(9) : args[i + 1];
      args.erase(args.begin() + static_cast<std::ptrdiff_t>(i), args.begin() + static_cast<std::ptrdiff_t>(i + (inline_value ? 1 : 2)));
      break;
    }
  }
  const PluginRegistry& registry = context.registry();
  const auto types = registry.types_of_kind(Benchmark::plugin_kind);
  if (args.empty()) {
    std::string all;
    for (const auto& t : types) all += (all.empty() ? "" : ", ") + t;
    throw UsageError("bench: name a benchmark (" + all + ")");
  }
  const std::string type = args.front();
  args.erase(args.begin());
  const auto* entry = registry.find(Benchmark::plugin_kind, type);
  if (!entry) {
    std::string msg = "bench: no benchmark '" + type + "'";
    if (auto near = nearest_name(type, types)) msg += " (did you mean '" + *near + "'?)";
    std::string all;
    for (const auto& t : types) all += (all.empty() ? "" : ", ") + t;
    throw UsageError(msg + "; available: " + all);
  }
  if (std::find(args.begin(), args.end(), "--help") != args.end() || std::find(args.begin(), args.end(), "-h") != args.end()) {
    std::cout << "plumage bench " << type << ": " << entry->info.summary << "\n\nOptions (its parameter table):\n"
              << flags_help(entry->info.params) << "  --record FILE\n      record the result in this markdown file\n";
    return;
  }
  std::string command = "plumage bench " + type;
  for (const auto& a : args) command += " " + a;
  const ConfigDocument doc = ConfigDocument::parse(flags_to_yaml(entry->info.params, args), "command line");
  auto benchmark = registry.create_named<Benchmark>(type, doc.root(), registry.context());
  Benchmark::Options options;
  options.command = command;
  options.record = record;
  if (!context.quiet) options.progress = [](std::string_view line) { std::cerr << line << "\n"; };
  const Benchmark::Report report = benchmark->run(options);
  std::cout << report.markdown;
  if (!record.empty()) {
    record_benchmark(record, report.id, report.markdown);
    if (!context.quiet) std::cerr << "recorded in " << record << "\n";
  }
}

void add_bench_command(CLI::App& app, AppContext& context) {
  auto* bench = app.add_subcommand("bench", "Measure the speed of a backend: plumage bench <name> [--help]");
  bench->require_subcommand(0, 1);
  bench->allow_extras();
  bench->prefix_command();
  bench->callback([&context, bench] {
    if (!bench->get_subcommands().empty()) return;
    run_registered_benchmark(context, bench->remaining());
  });
  add_bench_fdtd_command(*bench, context);
  add_bench_render_command(*bench, context);

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
