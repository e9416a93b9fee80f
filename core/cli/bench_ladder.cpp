// `plumage bench ladder`: every registered accuracy ladder (plumage/accuracy_ladder.hpp) — each
// backend at a ladder of fidelity settings against its independent reference — into one CSV,
// one chart (error against wall time, log–log, one curve per backend and case, the Pareto-optimal
// rungs of each curve marked) and a table for docs/benchmarks.md (issue 9).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "plumage/charts.hpp"
#include "commands.hpp"
#include "plumage/accuracy_ladder.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/diagnostics.hpp"

namespace plumage::cli {

namespace {

struct LadderBench {
  bool quick = false;
  std::vector<std::string> only;
  std::string out = "build/bench-ladder";
  std::string record;
  std::string chart_copy;  // also copy the chart here (docs/img/...) when recording
};

struct Row {
  LadderPoint point;
  bool pareto = false;
};

// A rung is Pareto-optimal on its curve when no other rung of the same (backend, case) is at
// least as good in both error and wall time and better in one.
void mark_pareto(std::vector<Row>& rows) {
  for (auto& a : rows) {
    a.pareto = true;
    for (const auto& b : rows) {
      if (&a == &b || a.point.backend != b.point.backend || a.point.case_name != b.point.case_name) continue;
      const bool no_worse = b.point.error <= a.point.error && b.point.wall_s <= a.point.wall_s;
      const bool better = b.point.error < a.point.error || b.point.wall_s < a.point.wall_s;
      if (no_worse && better) {
        a.pareto = false;
        break;
      }
    }
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void write_csv(const std::vector<Row>& rows, const std::filesystem::path& file) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "backend,case,setting,fidelity,reference,metric,error,wall_s,cpu_s,pareto\n";
    out << std::setprecision(6);
    for (const auto& r : rows) {
      const auto& p = r.point;
      out << csv_field(p.backend) << ',' << csv_field(p.case_name) << ',' << csv_field(p.setting) << ','
          << p.fidelity << ',' << csv_field(p.reference) << ',' << csv_field(p.metric) << ',' << p.error << ','
          << p.wall_s << ',' << p.cpu_s << ',' << (r.pareto ? 1 : 0) << '\n';
    }
  }, false);
}

// Markdown table cells: a '|' inside a cell would end it.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string markdown(const std::vector<Row>& rows, const LadderBench& b, const std::string& command,
                     const std::string& chart_link) {
  std::ostringstream md;
  md << "## ladder\n\n"
     << "Every backend along its ladder of fidelity settings against its independent reference "
        "(`plumage bench ladder`" << (b.quick ? ", quick variant: the cheap rungs only" : "")
     << "). Error in each backend's own metric (column), wall and process-CPU time of the rung "
        "alone (references excluded); **bold** rungs are Pareto-optimal on their curve (no other "
        "rung of the same backend and case is both as accurate and as fast).";
  if (!chart_link.empty()) md << " Chart: " << chart_link << ".";
  md << "\n\n| machine | command | date |\n|---|---|---|\n| " << machine_description() << " | `" << command
     << "` | " << today_iso() << " |\n\n"
     << "| backend | case | setting | reference | metric | error | wall s | CPU s |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const auto& p = r.point;
    std::ostringstream err, wall, cpu;
    err << std::setprecision(3) << p.error;
    wall << std::setprecision(3) << p.wall_s;
    cpu << std::setprecision(3) << p.cpu_s;
    const std::string setting = r.pareto ? "**" + p.setting + "**" : p.setting;
    md << "| " << cell(p.backend) << " | " << cell(p.case_name) << " | " << cell(setting) << " | "
       << cell(p.reference) << " | " << cell(p.metric) << " | " << err.str() << " | " << wall.str() << " | " << cpu.str() << " |\n";
  }
  return md.str();
}

void bench_ladder(AppContext& context, const LadderBench& b, const std::string& command) {
  auto& registry = context.registry();
  std::vector<std::string> ladders = registry.types_of_kind(AccuracyLadder::plugin_kind);
  std::sort(ladders.begin(), ladders.end());
  for (const auto& name : b.only) {
    if (std::find(ladders.begin(), ladders.end(), name) == ladders.end()) {
      std::string known;
      for (const auto& l : ladders) known += (known.empty() ? "" : ", ") + l;
      throw UsageError("bench ladder: no accuracy ladder named '" + name + "' (registered: " + known + ")");
    }
  }
  std::vector<Row> rows;
  for (const auto& name : ladders) {
    if (!b.only.empty() && std::find(b.only.begin(), b.only.end(), name) == b.only.end()) continue;
    auto ladder = registry.create_named<AccuracyLadder>(name, ParamView{}, registry.context());
    AccuracyLadder::Options options;
    options.quick = b.quick;
    if (!context.quiet) {
      std::cerr << "ladder " << name << (b.quick ? " (quick)" : "") << "\n";
      options.progress = [&name](std::string_view line) { std::cerr << "  " << name << ": " << line << "\n"; };
    }
    for (auto& p : ladder->run(options)) {
      if (!(p.error >= 0.0) || !std::isfinite(p.error)) {
        warn("bench.ladder_error", name + ": rung '" + p.setting + "' of '" + p.case_name +
                                       "' reported a non-finite or negative error");
      }
      rows.push_back({std::move(p), false});
    }
  }
  if (rows.empty()) throw UsageError("bench ladder: no rungs were run");
  mark_pareto(rows);

  const std::filesystem::path dir(b.out);
  std::filesystem::create_directories(dir);
  const auto csv = dir / "ladder.csv";
  const auto png = dir / "ladder.png";
  write_csv(rows, csv);
  std::string chart_link;
  try {
    draw_script_chart("plot_ladder.py", {csv.string()}, png,
                      std::string("Accuracy against cost, every backend") + (b.quick ? " (quick)" : ""));
    if (!b.chart_copy.empty()) {
      std::filesystem::create_directories(std::filesystem::path(b.chart_copy).parent_path());
      std::filesystem::copy_file(png, b.chart_copy, std::filesystem::copy_options::overwrite_existing);
      chart_link = "![ladder](" + std::filesystem::path(b.chart_copy).lexically_relative(
                                       std::filesystem::path(b.record).parent_path()).string() + ")";
    }
  } catch (const Error& e) {
    // The CSV and the table stand without the picture; say so rather than fail the run.
    warn("bench.chart", std::string("no chart drawn: ") + e.what());
  }
  const std::string md = markdown(rows, b, command, chart_link);
  std::cout << md;
  if (!context.quiet) std::cerr << "wrote " << csv.string() << (std::filesystem::exists(png) ? " and " + png.string() : "") << "\n";
  if (!b.record.empty()) {
    record_benchmark(b.record, b.quick ? "ladder-quick" : "ladder", md);
    if (!context.quiet) std::cerr << "recorded in " << b.record << "\n";
  }
}

}  // namespace

void add_bench_ladder_command(CLI::App& bench, AppContext& context) {
  auto b = std::make_shared<LadderBench>();
  auto* cmd = bench.add_subcommand(
      "ladder", "Every backend along its fidelity ladder against its reference: CSV, error-vs-time chart, table");
  cmd->add_flag("--quick", b->quick, "Only the cheap rungs (the CI variant, 15-35 s)");
  cmd->add_option("--only", b->only, "Run only these ladders (backend names, repeatable)");
  cmd->add_option("--out", b->out, "Folder for ladder.csv and ladder.png")->capture_default_str();
  cmd->add_option("--record", b->record, "Markdown file to record the table in (e.g. docs/benchmarks.md)");
  cmd->add_option("--chart-copy", b->chart_copy, "Also copy the chart here and link it from the record (e.g. docs/img/ladder.png)");
  cmd->callback([&context, b] {
    std::string command = "plumage bench ladder";
    if (b->quick) command += " --quick";
    for (const auto& o : b->only) command += " --only " + o;
    bench_ladder(context, *b, command);
  });
}

}  // namespace plumage::cli
