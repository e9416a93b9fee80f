// `plumage bench <name>`: measured speed of each backend, optionally recorded in
// docs/benchmarks.md (machine, command, date). Benchmarks measure; they never pass or fail.
#include <algorithm>
#include <iostream>

#include "plumage/bench_record.hpp"
#include "commands.hpp"
#include "param_flags.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/config_document.hpp"

namespace plumage::cli {

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
  options.preparation = context.preparation();
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
}

}  // namespace plumage::cli
