// The ladder report (plumage/ladder_report.hpp): running the ladders, the Pareto marks, the CSV
// and the markdown table.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/ladder_report.hpp"

namespace plumage {

namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// Markdown table cells: a '|' inside a cell would end it.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string three_digits(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << x;
  return s.str();
}

}  // namespace

std::vector<LadderRow> run_accuracy_ladders(const PluginRegistry& registry, const std::vector<std::string>& names,
                                            bool quick, const std::function<void(const std::string&)>& started,
                                            const std::function<void(const std::string&, std::string_view)>& progress) {
  std::vector<std::string> ladders = registry.types_of_kind(AccuracyLadder::plugin_kind);
  std::sort(ladders.begin(), ladders.end());
  std::vector<LadderRow> rows;
  for (const auto& name : ladders) {
    if (!names.empty() && std::find(names.begin(), names.end(), name) == names.end()) continue;
    auto ladder = registry.create_named<AccuracyLadder>(name, ParamView{}, registry.context());
    AccuracyLadder::Options options;
    options.quick = quick;
    if (started) started(name);
    if (progress) options.progress = [&progress, &name](std::string_view line) { progress(name, line); };
    for (auto& p : ladder->run(options)) {
      if (!(p.error >= 0.0) || !std::isfinite(p.error)) {
        warn("bench.ladder_error", name + ": rung '" + p.setting + "' of '" + p.case_name +
                                       "' reported a non-finite or negative error");
      }
      rows.push_back({std::move(p), false});
    }
  }
  return rows;
}

// A rung is Pareto-optimal on its curve when no other rung of the same (backend, case) is at
// least as good in both error and wall time and better in one.
void mark_pareto(std::vector<LadderRow>& rows) {
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

void write_ladder_csv(const std::vector<LadderRow>& rows, const std::filesystem::path& file) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "backend,case,setting,fidelity,reference,metric,error,wall_s,cpu_s,pareto\n";
    out << std::setprecision(6);
    for (const auto& r : rows) {
      const auto& p = r.point;
      out << csv_field(p.backend) << ',' << csv_field(p.case_name) << ',' << csv_field(p.setting) << ','
          << p.fidelity << ',' << csv_field(p.reference) << ',' << csv_field(p.metric) << ','
          // All digits of the error: rungs 1e-7 apart (float vs double paths) must stay ordered as
          // the Pareto marks were computed.
          << std::setprecision(17) << p.error << std::setprecision(6) << ',' << p.wall_s << ',' << p.cpu_s << ',' << (r.pareto ? 1 : 0) << '\n';
    }
  }, false);
}

std::string ladder_markdown(const std::vector<LadderRow>& rows, bool quick, const std::string& command,
                            const std::string& chart_link) {
  std::ostringstream md;
  md << "## ladder\n\n"
     << "Every backend along its ladder of fidelity settings against its independent reference "
        "(`plumage bench ladder`" << (quick ? ", quick variant: the cheap rungs only" : "")
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
    const std::string setting = r.pareto ? "**" + p.setting + "**" : p.setting;
    md << "| " << cell(p.backend) << " | " << cell(p.case_name) << " | " << cell(setting) << " | "
       << cell(p.reference) << " | " << cell(p.metric) << " | " << three_digits(p.error) << " | "
       << three_digits(p.wall_s) << " | " << three_digits(p.cpu_s) << " |\n";
  }
  return md.str();
}

}  // namespace plumage
