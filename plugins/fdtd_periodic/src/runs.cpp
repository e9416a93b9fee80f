// Batches of engine runs for the table driver: the blow-up rerun and the stability check
// (build_steps.hpp).
#include <algorithm>
#include <sstream>

#include "build_steps.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"

namespace plumage::fdtd_table::detail {

std::string fmt(double v, int precision) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

namespace {

// The rerun at half the time step of the jobs `redo` (their results replace those in `out`).
void rerun_at_half_step(const fdtd::Cell& cell, const std::vector<fdtd::Job>& jobs, const std::vector<std::size_t>& redo,
                        const std::vector<double>& omegas, const fdtd::SimParams& sim, int threads, RunReport& rep,
                        std::vector<fdtd::Spectrum>& out, std::vector<char>* rerun) {
  fdtd::SimParams half = sim;
  if (half.dt > 0) half.dt *= 0.5;
  else half.courant *= 0.5;
  std::vector<fdtd::Job> again;
  for (std::size_t j : redo) again.push_back(jobs[j]);
  std::vector<fdtd::Spectrum> fixed;
  try {
    fixed = fdtd::run_batch(cell, again, omegas, half, threads);
  } catch (const fdtd::FieldBlowUp& e) {
    throw NumericalError(std::string("fdtd_periodic: a run is unstable even at half the time step (") + e.what() +
                         "); first failure: " + rep.first_blowup);
  }
  for (std::size_t r = 0; r < redo.size(); ++r) {
    out[redo[r]] = std::move(fixed[r]);
    if (rerun) (*rerun)[redo[r]] = 1;
    const auto& st = out[redo[r]].stats;
    if (st.dt_limit > 0) rep.rerun_courant = std::max(rep.rerun_courant, st.dt / st.dt_limit);
  }
}

}  // namespace

std::vector<fdtd::Spectrum> run_checked(const fdtd::Cell& cell, const std::vector<fdtd::Job>& jobs,
                                        const std::vector<double>& omegas, const fdtd::SimParams& sim,
                                        int threads, RunReport& rep, std::vector<char>* rerun) {
  std::vector<std::exception_ptr> errs;
  auto out = fdtd::run_batch_collect(cell, jobs, omegas, sim, threads, errs);
  if (rerun) rerun->assign(jobs.size(), 0);
  std::vector<std::size_t> redo;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (!errs[j]) continue;
    try {
      std::rethrow_exception(errs[j]);
    } catch (const fdtd::FieldBlowUp& e) {
      if (rep.blown_up == 0) rep.first_blowup = std::string(e.what()) + " at (k_x, k_y) = (" + std::to_string(jobs[j].kx) +
                                                ", " + std::to_string(jobs[j].ky) + ") /um";
      ++rep.blown_up;
      redo.push_back(j);
    }
  }
  if (!redo.empty()) rerun_at_half_step(cell, jobs, redo, omegas, sim, threads, rep, out, rerun);
  for (const auto& sp : out) {
    ++rep.runs;
    if (sp.stats.steps > 0 && !sp.stats.converged) {
      ++rep.not_converged;
      rep.not_converged_time = std::max(rep.not_converged_time, sp.stats.sim_time);
    }
    rep.max_energy_ratio = std::max(rep.max_energy_ratio, sp.stats.energy_ratio);
    for (const auto& f : sp.freqs)
      for (const auto& o : f.orders)
        for (double e : o.eff)
          if (f.valid && e > rep.max_other_eff) rep.max_other_eff = e, rep.max_other_eff_lambda = f.lambda;
  }
  return out;
}

double CourantCheck::fraction(const fdtd::Cell& cell, double ky_abs_max) const {
  if (sim_.dt > 0) return sim_.dt / fdtd::stable_time_step(cell, h_um_, ky_abs_max, sim_.lorentz_update);
  return sim_.courant;
}

void CourantCheck::check(const fdtd::Cell& cell, double ky_max) {
  const double frac = fraction(cell, ky_max);
  const double lim = fdtd::stable_time_step(cell, h_um_, ky_max, sim_.lorentz_update);
  const std::string what = "time step dt = " + fmt(sim_.dt > 0 ? sim_.dt : frac * lim, 6) + " um/c is " + fmt(frac, 5) +
                           " of the stability limit " + fmt(lim, 6) + " um/c (h = " + fmt(1000 * h_um_) +
                           " nm, |k_y| up to " + fmt(ky_max) + " /um)";
  if (frac > 1.0) {
    if (!sim_.allow_unstable_dt)
      throw Error("fdtd_periodic: " + what + ": certainly unstable; lower dt (or courant) to at most 1");
    const std::string m = what + ": above the limit, certainly unstable (allow_unstable_dt set)";
    warn("fdtd.courant", m);
    notes_.push_back(m);
  } else if (frac >= kCourantNear) {
    const std::string m = what + ": at/near the Courant limit (>= " + fmt(kCourantNear) +
                          "), no stability margin; runs are guarded for field growth";
    warn("fdtd.courant", m);
    notes_.push_back(m);
  }
}

}  // namespace plumage::fdtd_table::detail
