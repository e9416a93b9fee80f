// Benchmark "ladder" (`plumage bench ladder`): every registered accuracy ladder against its
// reference, reported as a CSV, an error-against-time chart and a docs/benchmarks.md table
// (plumage/ladder_report.hpp). Section id "ladder", or "ladder-quick" for the cheap rungs.
#include <algorithm>
#include <filesystem>

#include "plumage/atomic_file.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/charts.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/ladder_report.hpp"
#include "plumage/param_table.hpp"

namespace plumage {

namespace {

namespace fs = std::filesystem;

struct LadderBenchParams {
  bool quick = false;
  std::vector<std::string> only;
  std::string out;
  std::string chart_copy;
};

const ParamTable<LadderBenchParams>& ladder_bench_params() {
  static const auto table =
      ParamTable<LadderBenchParams>{}
          .boolean("quick", &LadderBenchParams::quick, false, "only the cheap rungs (the CI variant, 15-35 s)")
          .custom("only", "list", "-", "every ladder", "run only these ladders (backend names, comma-separated)",
                  [](const ParamView& p, LadderBenchParams& o) {
                    if (!p.has("only")) return;
                    for (const auto& item : p.items("only")) o.only.push_back(item.scalar_text());
                  })
          .text("out", &LadderBenchParams::out, "build/bench-ladder", "folder for ladder.csv and ladder.png")
          .text("chart_copy", &LadderBenchParams::chart_copy, "",
                "also copy the chart here and link it from the record (e.g. docs/img/ladder.png)");
  return table;
}

class LadderBenchmark final : public Benchmark {
 public:
  LadderBenchmark(const PluginRegistry& registry, LadderBenchParams params)
      : registry_(registry), params_(std::move(params)) {}

  Report run(const Options& options) const override {
    const auto say = [&](const std::string& line) {
      if (options.progress) options.progress(line);
    };
    // Output paths first: nothing runs for outputs that would be refused.
    check_output_directory(params_.out);
    check_output_path(fs::path(params_.out) / "ladder.csv");
    check_output_path(fs::path(params_.out) / "ladder.png");
    check_output_path(params_.chart_copy);  // outside draw_chart, whose errors become warnings
    std::vector<LadderRow> rows = run_accuracy_ladders(
        registry_, params_.only, params_.quick,
        [&](const std::string& name) { say("ladder " + name + (params_.quick ? " (quick)" : "")); },
        [&](const std::string& name, std::string_view line) { say("  " + name + ": " + std::string(line)); });
    if (rows.empty()) throw Error("bench ladder: no rungs were run");
    mark_pareto(rows);

    const fs::path dir(params_.out);
    create_output_directory(dir);
    const fs::path csv = dir / "ladder.csv";
    const fs::path png = dir / "ladder.png";
    write_ladder_csv(rows, csv);
    const std::string chart_link = draw_chart(csv, png, options.record);
    const std::string command = options.command.empty() ? default_command() : options.command;
    say("wrote " + csv.string() + (fs::exists(png) ? " and " + png.string() : ""));
    return {params_.quick ? "ladder-quick" : "ladder", ladder_markdown(rows, params_.quick, command, chart_link)};
  }

 private:
  std::string default_command() const {
    std::string command = "plumage bench ladder";
    if (params_.quick) command += " --quick";
    for (const auto& o : params_.only) command += " --only " + o;
    return command;
  }

  // The chart, copied beside the record when asked; returns the record's link to the copy. The
  // CSV and the table stand without the picture: a drawing failure is a warning, not an error.
  std::string draw_chart(const fs::path& csv, const fs::path& png, const fs::path& record) const {
    try {
      draw_script_chart("plot_ladder.py", {csv.string()}, png,
                        std::string("Accuracy against cost, every backend") + (params_.quick ? " (quick)" : ""));
      if (params_.chart_copy.empty()) return "";
      create_output_directory(fs::path(params_.chart_copy).parent_path());
      fs::copy_file(png, params_.chart_copy, fs::copy_options::overwrite_existing);
      return "![ladder](" + fs::path(params_.chart_copy).lexically_relative(record.parent_path()).string() + ")";
    } catch (const Error& e) {
      warn("bench.chart", std::string("no chart drawn: ") + e.what());
      return "";
    }
  }

  const PluginRegistry& registry_;
  LadderBenchParams params_;
};

}  // namespace

void register_ladder_benchmark(PluginRegistry& registry) {
  registry.builtin_registrar().add<Benchmark>(
      {.type = "ladder",
       .version = "1.0.0",
       .summary = "every backend along its fidelity ladder against its reference: CSV, error-vs-time chart, table",
       .params = ladder_bench_params().specs()},
      [](const ParamView& params, const PluginContext& context) {
        if (!context.registry) throw Error("benchmark 'ladder': needs a registry in its context");
        LadderBenchParams p = ladder_bench_params().read(params);
        // An unknown name is refused before anything runs or is written.
        std::vector<std::string> ladders = context.registry->types_of_kind(AccuracyLadder::plugin_kind);
        std::sort(ladders.begin(), ladders.end());
        for (const auto& name : p.only) {
          if (std::find(ladders.begin(), ladders.end(), name) != ladders.end()) continue;
          std::string known;
          for (const auto& l : ladders) known += (known.empty() ? "" : ", ") + l;
          throw ConfigError(params.mark_of("only"), "only",
                            "no accuracy ladder named '" + name + "' (registered: " + known + ")");
        }
        return std::make_unique<LadderBenchmark>(*context.registry, std::move(p));
      });
}

}  // namespace plumage
