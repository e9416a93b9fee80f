// Private to the pipeline: how many instances `simulate` and `characterize` solve at a time, so that
// their solves together fit in the memory budget (issue 23 Deliver 2, plumage/memory_budget.hpp).
//
// A solver's estimate (ScatteringSolver::estimate_memory) is the peak of ONE solve. The pipeline
// solves its instances in parallel, one per thread, so the process holds up to
// min(instances, threads) solves at once: measured on the keratin cylinder (BEM dense, 1 264
// unknowns), 75 MB peak RSS on one thread against 120 MB on two. The plan takes the larger of the
// estimates at the shortest and the longest wavelength for instance 0 (the generators vary the
// instances little; each solve checks itself again before it assembles) and lowers the number of
// parallel solves to what the budget holds, refusing only when a single solve does not fit.
#pragma once

#include <cstddef>
#include <functional>
#include <span>

#include "plumage/far_field.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

struct SolvePlan {
  int parallel = 1;              // instances solved at a time
  MemoryEstimate per_solve;      // the largest single-solve estimate (no parts: nothing large)
  bool lowered = false;          // fewer than min(instances, threads) because of the budget
};

// `results_bytes`: what the run accumulates beside the solves (simulate: every unit's far fields;
// characterize: a group's). Throws MemoryBudgetError when the results and one solve do not fit.
// `what` names the command in the note printed when the parallelism is lowered ("simulate",
// "characterize").
SolvePlan plan_parallel_solves(const SpeciesConfig& config, std::span<const double> lambdas_nm, std::size_t n_phi_i,
                               std::size_t n_phi_o, int instances, double results_bytes, const char* what);

// Outgoing directions of a solve on the specular cone: the pattern's and the projected ones.
inline std::size_t cone_directions(int pattern_samples, int projected_samples) {
  return pattern_directions(pattern_samples).phi_o_rad.size() +
         projected_directions(0.0, projected_samples).phi_o_rad.size();
}

// Bytes of `count` far fields of `n_phi_o` directions (FarField: the azimuths and two complex
// polarisation components per direction).
inline double far_field_bytes(double count, std::size_t n_phi_o) { return count * static_cast<double>(n_phi_o) * 40.0; }

// Runs body() with at most plan.parallel threads (a oneTBB arena) when the budget lowered it, else
// as is (a run of fewer instances than threads keeps every thread for the solver's own loops).
void run_with_plan(const SolvePlan& plan, const std::function<void()>& body);

}  // namespace plumage
