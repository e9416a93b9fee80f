// Parallel solves within the memory budget (solve_memory.hpp).
#include "solve_memory.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace plumage {

SolvePlan plan_parallel_solves(const SpeciesConfig& config, std::span<const double> lambdas_nm, std::size_t n_phi_i,
                               std::size_t n_phi_o, int instances, double results_bytes, const char* what) {
  const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
  SolvePlan plan;
  plan.parallel = std::max(1, std::min(instances, threads));
  if (!config.solver || !config.structure || lambdas_nm.empty()) return plan;
  const CrossSection section = config.structure->generate(0);
  const auto [lo, hi] = std::minmax_element(lambdas_nm.begin(), lambdas_nm.end());
  for (double lambda : {*lo, *hi}) {
    MemoryEstimate e = config.solver->estimate_memory(section, lambda, n_phi_i, n_phi_o);
    if (plan.per_solve.parts.empty() || e.total_bytes() > plan.per_solve.total_bytes()) plan.per_solve = std::move(e);
  }
  if (plan.per_solve.parts.empty()) return plan;
  const MemoryAvailability available = memory_available();
  // The results and one solve must fit.
  MemoryEstimate run = plan.per_solve;
  run.job = std::string(what) + ": the run's far fields and one " + plan.per_solve.job;
  run.add("far fields of the run", results_bytes);
  check_memory(run, available);
  const double one = std::max(1.0, plan.per_solve.total_bytes());
  const double room = static_cast<double>(available.bytes) - results_bytes;
  const int fit = static_cast<int>(std::min<double>(plan.parallel, std::floor(room / one)));
  if (fit < plan.parallel) {
    report_step(std::string(what) + ": memory", 0, 0,
                std::to_string(fit) + " solve(s) at a time instead of " + std::to_string(plan.parallel) + ": " +
                    plan.per_solve.describe() + " each, " + format_bytes(static_cast<double>(available.bytes)) +
                    " available (" + available.source + ")");
    plan.parallel = std::max(1, fit);
    plan.lowered = true;
  }
  return plan;
}

void run_with_plan(const SolvePlan& plan, const std::function<void()>& body) {
  if (!plan.lowered) {
    body();
    return;
  }
  tbb::task_arena arena(plan.parallel);
  arena.execute(body);
}

}  // namespace plumage
