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
// Removes `--flag VALUE` / `--flag=VALUE` from args and returns VALUE ("" when absent).
static std::string take_flag(std::vector<std::string>& args, const std::string& flag) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == flag || args[i].rfind(flag + "=", 0) == 0) {
      const bool inline_value = args[i].size() > flag.size();
      if (!inline_value && i + 1 >= args.size()) throw UsageError(flag + ": needs a value");
      std::string value = inline_value ? args[i].substr(flag.size() + 1) : args[i + 1];
      args.erase(args.begin() + static_cast<std::ptrdiff_t>(i), args.begin() + static_cast<std::ptrdiff_t>(i + (inline_value ? 1 : 2)));
      return value;
    }
  }
  return {};
}

void run_registered_benchmark(AppContext& context, std::vector<std::string> args) {
  const std::string record = take_flag(args, "--record");  // the command's, not the benchmark's
  // The global --max-memory after `bench <name>` too (bench takes everything after it).
  if (std::string budget = take_flag(args, "--max-memory"); !budget.empty()) {
    context.max_memory = budget;
    context.apply_budget_and_progress();
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
  bench->allow_extras();
  bench->prefix_command();
  bench->callback([&context, bench] { run_registered_benchmark(context, bench->remaining()); });
}

}  // namespace plumage::cli
