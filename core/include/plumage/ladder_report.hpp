// The report of `plumage bench ladder` (issue 9): every registered accuracy ladder
// (accuracy_ladder.hpp) — each backend at a ladder of fidelity settings against its independent
// reference — into one CSV, one chart (error against wall time, log–log, one curve per backend
// and case, the Pareto-optimal rungs of each curve marked; scripts/plot_ladder.py) and a table
// for docs/benchmarks.md. The benchmark "ladder" (core/src/report/ladder_benchmark.cpp) runs it.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/accuracy_ladder.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage {

struct LadderRow {
  LadderPoint point;
  bool pareto = false;  // no other rung of the same (backend, case) is as good in both error and time
};

// Runs the named ladders (all registered ones when `names` is empty) in name order; a rung with a
// non-finite or negative error raises the warning `bench.ladder_error`. `started` is called with
// each ladder's name before it runs, `progress` with its status lines; both may be empty.
std::vector<LadderRow> run_accuracy_ladders(const PluginRegistry& registry, const std::vector<std::string>& names,
                                            bool quick, const std::function<void(const std::string&)>& started,
                                            const std::function<void(const std::string&, std::string_view)>& progress);

// Sets `pareto` on every row.
void mark_pareto(std::vector<LadderRow>& rows);

// "backend,case,setting,fidelity,reference,metric,error,wall_s,cpu_s,pareto", written atomically.
void write_ladder_csv(const std::vector<LadderRow>& rows, const std::filesystem::path& file);

// The docs/benchmarks.md section: what was measured, machine, command and date, one row per rung
// (Pareto-optimal settings in bold); `chart_link` (markdown) is mentioned when not empty.
std::string ladder_markdown(const std::vector<LadderRow>& rows, bool quick, const std::string& command,
                            const std::string& chart_link);

}  // namespace plumage
