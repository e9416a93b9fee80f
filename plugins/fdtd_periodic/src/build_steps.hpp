// Internal to the table driver (table_build.cpp): the steps of one table build that have a file
// of their own — running batches with the blow-up rerun and the stability check (runs.cpp), and
// the resumable checkpoint of the k-grid runs (checkpoint.cpp).
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "table_build.hpp"

namespace plumage::fdtd_table::detail {

std::string fmt(double v, int precision = 4);

// Stability and convergence bookkeeping of one build (issue 9: every failure is reported).
struct RunReport {
  std::size_t runs = 0;            // fresh and resumed
  std::size_t blown_up = 0;        // runs that blew up and were rerun at half the time step
  std::string first_blowup;        // the engine's message for the first of them
  double rerun_courant = 0.0;      // Courant factor (dt / stability limit) of the reruns
  std::size_t not_converged = 0;   // runs stopped by max_time before the DFTs settled
  double not_converged_time = 0.0; // fresh runs: longest simulated time among them (um/c)
  double max_energy_ratio = 0.0;   // fresh runs: largest field energy / (nx × normalisation energy)
  double max_other_eff = 0.0;      // fresh runs: largest power in the other orders (a table λ, one pol)
  double max_other_eff_lambda = 0.0;
};

// run_batch, with a run that blows up (fdtd::FieldBlowUp: non-finite or growing field energy)
// rerun once at half the time step: a time-step instability (the scheme beyond its stability
// limit, NOTES §3b) disappears there, and the rerun is reported. A second blow-up is a
// NumericalError that stops the build; any other error stops it as it is. `rerun` (optional)
// receives 1 per rerun job.
std::vector<fdtd::Spectrum> run_checked(const fdtd::Cell& cell, const std::vector<fdtd::Job>& jobs,
                                        const std::vector<double>& omegas, const fdtd::SimParams& sim,
                                        int threads, RunReport& rep, std::vector<char>* rerun);

// Issue 9, before any run: the time step against the stability limit of the cell (worst k_y).
// Above it the scheme is certainly unstable: refused (the builder's `courant` is limited to
// (0, 1] by its parameter table, so this is reached with an explicit sim.dt); the testing flag
// allow_unstable_dt turns the refusal into a warning and leaves it to the run-time guard.
// From kCourantNear on it is reported: at the limit itself the Nyquist mode is only marginally
// stable, and a 0.2 % excess (layered 2-cell grid) blows up within 4 um/c, so there is no margin
// for anything the bound does not model (NOTES "Warnings").
class CourantCheck {
 public:
  static constexpr double kCourantNear = 0.99;

  CourantCheck(double h_um, const fdtd::SimParams& sim) : h_um_(h_um), sim_(sim) {}
  // Fraction of the stability limit (stable_time_step: Courant with the exact k_y term, lowered
  // for the central-difference ADE) the runs will use, worst over |k_y| ≤ ky_abs_max: with an
  // explicit dt the largest dt / limit (the limit falls with |k_y|), else the Courant factor.
  double fraction(const fdtd::Cell& cell, double ky_abs_max) const;
  // Refuses (Error) or warns (fdtd.courant) as above; warnings are also kept for the notes.
  void check(const fdtd::Cell& cell, double ky_max);
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  double h_um_;
  const fdtd::SimParams& sim_;
  std::vector<std::string> notes_;
};

// Run-level flags kept in the checkpoint (bits 1, 2 of the per-frequency flag byte whose bit 0
// is other_orders), so that a resumed build still reports them (issue 9).
constexpr unsigned kRunNotConverged = 2, kRunRerun = 4;

// The k-grid runs of one build in Options::checkpoint: a header (hash of cell tag, grid step,
// numerics, frequencies and nodes) and one record per finished run. A later build with the same
// header resumes the runs found; a truncated tail is dropped (the file is rewritten on open).
class Checkpoint {
 public:
  // Opens (no-op when opt.checkpoint is empty) and reads back the matching finished runs.
  Checkpoint(const Options& opt, double ax_um, const fdtd::SimParams& sim, double k_step, const std::vector<double>& omegas,
             const std::vector<fdtd::Job>& jobs, std::vector<fdtd::Spectrum>& spectra, std::vector<char>& have,
             std::vector<unsigned>& run_flags);
  std::size_t resumed() const { return resumed_; }
  void append(std::uint32_t node, const fdtd::Spectrum& s, unsigned run_flags);
  void flush();

 private:
  std::ofstream file_;
  std::size_t resumed_ = 0;
};

}  // namespace plumage::fdtd_table::detail
