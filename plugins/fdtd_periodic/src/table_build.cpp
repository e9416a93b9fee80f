// The table driver: table entries and grazing anchors → engine runs (one per sample with exact
// ε(λ), or broadband runs on a Bloch-k grid) → Jones matrices → the table, with the entries
// below kz_min continued to grazing (grazing.hpp) and every condition reported (issue 9).
#include "table_build.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "build_steps.hpp"
#include "grazing.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"

namespace plumage::fdtd_table {

namespace {

using namespace detail;

// A point where the Jones matrix is needed: a table entry or a grazing anchor.
struct Sample {
  std::size_t l;
  double theta, phi;
};

// Samples: every entry with k_z/k0 ≥ kz_min, then the anchors of the grazing continuation
// (grazing.hpp) of every entry below it: entry e gets the anchors anchor_base[e] + m.
struct TableSamples {
  std::size_t NL = 0, NT = 0, NP = 0;
  std::vector<double> anchor_kappa;
  std::vector<Sample> samples;
  std::vector<std::size_t> entry_sample, anchor_base;  // SIZE_MAX: none
  std::size_t first_anchor = 0;
  std::size_t idx(std::size_t l, std::size_t i, std::size_t j) const { return (l * NT + i) * NP + j; }
};

TableSamples table_samples(const TableGrid& grid, double kz_min, int grazing_anchors) {
  TableSamples t;
  t.NL = grid.lambda_nm.size(), t.NT = grid.cos_theta.size(), t.NP = grid.cos_phi.size();
  auto angles = [&](std::size_t i, std::size_t j) {
    return std::pair<double, double>{std::acos(std::min(1.0, grid.cos_theta[i])),
                                     std::acos(std::min(1.0, grid.cos_phi[j]))};
  };
  t.anchor_kappa = anchor_kappas(kz_min, grazing_anchors);
  t.entry_sample.assign(t.NL * t.NT * t.NP, SIZE_MAX);
  t.anchor_base.assign(t.NL * t.NT * t.NP, SIZE_MAX);
  for (std::size_t l = 0; l < t.NL; ++l)
    for (std::size_t i = 0; i < t.NT; ++i)
      for (std::size_t j = 0; j < t.NP; ++j) {
        if (grid.cos_theta[i] * grid.cos_phi[j] < kz_min) continue;
        const auto [th, ph] = angles(i, j);
        t.entry_sample[t.idx(l, i, j)] = t.samples.size();
        t.samples.push_back({l, th, ph});
      }
  t.first_anchor = t.samples.size();
  for (std::size_t l = 0; l < t.NL; ++l)
    for (std::size_t i = 0; i < t.NT; ++i)
      for (std::size_t j = 0; j < t.NP; ++j) {
        if (grid.cos_theta[i] * grid.cos_phi[j] >= kz_min) continue;
        const auto [th, ph] = angles(i, j);
        t.anchor_base[t.idx(l, i, j)] = t.samples.size();
        for (double ka : t.anchor_kappa) {
          const auto [ta, pa] = radial_point(th, ph, ka);
          t.samples.push_back({l, ta, pa});
        }
      }
  return t;
}

// The Jones matrix of every sample that was simulated (or interpolated with enough support),
// and the counts of the runs behind them.
struct SampleValues {
  std::vector<std::optional<JonesReflection>> value;
  std::size_t other_orders = 0, runs = 0, resumed_runs = 0;
  RunReport rep;
};

// One run per sample with exact ε(λ) (the per-entry mode), samples grouped by λ; before any run
// the time step is checked at the λ with the worst stability fraction.
void evaluate_per_sample(const CellFactory& make_cell, const TableGrid& grid, const std::vector<Sample>& samples,
                         const fdtd::SimParams& sim, const Options& opt, const TableBuilder::Progress& progress,
                         CourantCheck& courant, SampleValues& out) {
  double worst = -1, ky_worst = 0;
  std::size_t l_worst = 0;
  for (std::size_t l = 0; l < grid.lambda_nm.size(); ++l) {
    double ky_max = -1;
    for (const auto& smp : samples)
      if (smp.l == l) ky_max = std::max(ky_max, std::abs(engine_k(grid.lambda_nm[l], smp.theta, smp.phi).second));
    if (ky_max < 0) continue;
    const double f = courant.fraction(make_cell(grid.lambda_nm[l] * 1e-3), ky_max);
    if (f > worst) worst = f, ky_worst = ky_max, l_worst = l;
  }
  if (worst >= 0) courant.check(make_cell(grid.lambda_nm[l_worst] * 1e-3), ky_worst);
  std::size_t done = 0;
  for (std::size_t l = 0; l < grid.lambda_nm.size(); ++l) {
    std::vector<std::size_t> ids;
    for (std::size_t s = 0; s < samples.size(); ++s)
      if (samples[s].l == l) ids.push_back(s);
    if (ids.empty()) continue;
    const double lam_um = grid.lambda_nm[l] * 1e-3;
    const fdtd::Cell cell = make_cell(lam_um);
    const std::vector<double> omegas{2.0 * fdtd::kPi / lam_um};
    const std::size_t chunk = static_cast<std::size_t>(std::max(1, opt.threads)) * 2;
    for (std::size_t a = 0; a < ids.size(); a += chunk) {
      std::vector<fdtd::Job> part;
      for (std::size_t b = a; b < std::min(ids.size(), a + chunk); ++b) {
        const auto [kx, ky] = engine_k(grid.lambda_nm[l], samples[ids[b]].theta, samples[ids[b]].phi);
        part.push_back({kx, ky});
      }
      const auto spectra = run_checked(cell, part, omegas, sim, opt.threads, out.rep, nullptr);
      for (std::size_t b = 0; b < part.size(); ++b) {
        if (!spectra[b].freqs.at(0).valid) continue;
        const fdtd::FreqResult& f = spectra[b].freqs[0];
        out.value[ids[a + b]] = jones_from_engine(f);
        if (f.other_orders) ++out.other_orders;
      }
      done += part.size();
      out.runs += part.size();
      if (progress) progress(done, samples.size(), "fdtd runs (one per entry)");
    }
  }
}

// Broadband runs on a Bloch-k grid k_x = −a Δk, k_y = b Δk (a, b ≥ 0), bilinear in (k_x, k_y)
// at each table frequency: the nodes bracketing each sample and their weights.
struct KGrid {
  struct Corner {
    std::size_t node[4];
    double w[4];
  };
  std::vector<fdtd::Job> jobs;  // one per node
  std::vector<Corner> corners;  // one per sample
};

KGrid k_grid(const TableGrid& grid, const std::vector<Sample>& samples, double dk) {
  KGrid g;
  std::map<std::pair<int, int>, std::size_t> nodes;
  g.corners.resize(samples.size());
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const auto [kx, ky] = engine_k(grid.lambda_nm[samples[s].l], samples[s].theta, samples[s].phi);
    const double u = std::max(0.0, -kx / dk), v = std::max(0.0, ky / dk);
    const int a0 = static_cast<int>(std::floor(u)), b0 = static_cast<int>(std::floor(v));
    const double fu = u - a0, fv = v - b0;
    KGrid::Corner& c = g.corners[s];
    int k = 0;
    for (int da = 0; da < 2; ++da)
      for (int db = 0; db < 2; ++db, ++k) {
        auto key = std::make_pair(a0 + da, b0 + db);
        auto it = nodes.emplace(key, nodes.size()).first;
        c.node[k] = it->second;
        c.w[k] = (da ? fu : 1.0 - fu) * (db ? fv : 1.0 - fv);
      }
  }
  g.jobs.resize(nodes.size());
  for (const auto& [key, n] : nodes) g.jobs[n] = {-key.first * dk, key.second * dk};
  return g;
}

// Every node's run: resumed from the checkpoint or run in chunks (appended to the checkpoint
// after each), with the resumed runs' stability/convergence flags counted from the checkpoint.
std::vector<fdtd::Spectrum> run_nodes(const fdtd::Cell& cell, const std::vector<fdtd::Job>& jobs,
                                      const std::vector<double>& omegas, double ax_um, const fdtd::SimParams& sim,
                                      const Options& opt, const TableBuilder::Progress& progress, SampleValues& out) {
  std::vector<fdtd::Spectrum> spectra(jobs.size());
  std::vector<char> have(jobs.size(), 0);
  std::vector<unsigned> run_flags(jobs.size(), 0);
  Checkpoint checkpoint(opt, ax_um, sim, opt.k_step_per_um, omegas, jobs, spectra, have, run_flags);
  const std::size_t resumed = checkpoint.resumed();
  std::vector<std::size_t> todo;
  for (std::size_t n = 0; n < jobs.size(); ++n)
    if (!have[n]) todo.push_back(n);
  const std::size_t chunk = static_cast<std::size_t>(std::max(1, opt.threads)) * 2;
  if (progress && resumed > 0) progress(resumed, jobs.size(), "fdtd broadband runs (Bloch k grid, resumed)");
  for (std::size_t a = 0; a < todo.size(); a += chunk) {
    std::vector<fdtd::Job> part;
    for (std::size_t b = a; b < std::min(todo.size(), a + chunk); ++b) part.push_back(jobs[todo[b]]);
    std::vector<char> rerun;
    auto done = run_checked(cell, part, omegas, sim, opt.threads, out.rep, &rerun);
    for (std::size_t b = 0; b < done.size(); ++b) {
      const std::size_t n = todo[a + b];
      spectra[n] = std::move(done[b]);
      run_flags[n] = (rerun[b] ? kRunRerun : 0u) |
                     (spectra[n].stats.steps > 0 && !spectra[n].stats.converged ? kRunNotConverged : 0u);
      checkpoint.append(static_cast<std::uint32_t>(n), spectra[n], run_flags[n]);
    }
    checkpoint.flush();
    out.runs += part.size();
    if (progress) progress(resumed + a + part.size(), jobs.size(), "fdtd broadband runs (Bloch k grid)");
  }
  out.resumed_runs = resumed;
  for (std::size_t n = 0; n < jobs.size(); ++n) {
    if (!have[n]) continue;
    ++out.rep.runs;
    if (run_flags[n] & kRunNotConverged) ++out.rep.not_converged;
    if (run_flags[n] & kRunRerun) ++out.rep.blown_up;
  }
  return spectra;
}

// Bilinear in k of the surface impedance Z = (I + J)(I − J)⁻¹/κ of every corner at its own
// κ = k_z/k0 (grazing.hpp), mapped back with the sample's κ: J itself has a square-root branch
// point at the light line (κ = sqrt(1 − |k_∥|²/k0²)) and is poorly interpolated near it.
void interpolate_samples(const KGrid& g, const std::vector<fdtd::Spectrum>& spectra, const TableSamples& t,
                         SampleValues& out) {
  for (std::size_t s = 0; s < t.samples.size(); ++s) {
    const KGrid::Corner& c = g.corners[s];
    JonesReflection acc{};
    double wsum = 0.0;
    bool orders = false;
    for (int k = 0; k < 4; ++k) {
      if (c.w[k] == 0.0) continue;
      const fdtd::FreqResult& f = spectra[c.node[k]].freqs.at(t.samples[s].l);
      if (!f.valid) continue;
      orders = orders || f.other_orders;
      const JonesReflection r = impedance_of(jones_from_engine(f), f.cos_theta * f.cos_phi);
      acc.ss += c.w[k] * r.ss, acc.sp += c.w[k] * r.sp, acc.ps += c.w[k] * r.ps, acc.pp += c.w[k] * r.pp;
      wsum += c.w[k];
    }
    // Too little support: an entry is then treated as not simulated (continued like those below
    // kz_min). An anchor sits next to the invalid region by construction, so any valid corner
    // is used (Z is smooth; the production table otherwise left 1634 entries at −I).
    if (wsum < (s >= t.first_anchor ? 1e-9 : 0.25)) continue;
    if (orders) ++out.other_orders;
    acc.ss /= wsum, acc.sp /= wsum, acc.ps /= wsum, acc.pp /= wsum;
    out.value[s] = jones_of(acc, std::cos(t.samples[s].theta) * std::cos(t.samples[s].phi));
  }
}

// Issue 27 (rcwa NOTES §4 item 1): the engine marks a frequency valid only for k_z/k0 at or
// above its threshold, so with the threshold at kz_min an entry at cos θ cos φ ≈ kz_min loses
// the Bloch-k corners that lie just below it (κ moves fast there: dκ ≈ −(k_∥/k0)/κ · dk_∥/k0)
// and was made from part of its corners or continued instead (0.01–0.06 in |r|² off). The engine
// therefore runs with the threshold lowered to the smallest κ of any weighted, propagating corner
// of a sample, but not below kEngineKappaFloor (such corners stay dropped), where the engine's
// own error at fixed k reaches 7e-3 (NOTES §5a). Measured on a mallard-green 7 × 4 × 4 table
// (NOTES §6a): floor 0.1 and 0.05 both leave 5 of 21 boundary entries above 0.005 against the
// rcwa; 0.05 fixes (700 nm, 0.5, 0.5) (0.0125 → 0.0034) but costs 20 % more CPU, worsens
// (400 nm, 0.5, 0.5) (0.0041 → 0.0065) and had a run stop at the time cap: 0.1. Which entries
// are simulated is still
// decided by kz_min. kRoundingSlack: κ = cos θ cos φ = kz_min exactly, recomputed from (k_x, k_y),
// may round below it (the exact-k mode lost such entries).
constexpr double kEngineKappaFloor = 0.1;
constexpr double kRoundingSlack = 1e-9;

double engine_kz_min_k_grid(const KGrid& g, const TableGrid& grid, const TableSamples& t, double kz_min) {
  double lowest = kz_min;
  for (std::size_t s = 0; s < t.samples.size(); ++s) {
    const double k0 = 2.0 * fdtd::kPi / (grid.lambda_nm[t.samples[s].l] * 1e-3);
    for (int k = 0; k < 4; ++k) {
      if (g.corners[s].w[k] == 0.0) continue;
      const fdtd::Job& jb = g.jobs[g.corners[s].node[k]];
      const double kappa2 = 1.0 - (jb.kx * jb.kx + jb.ky * jb.ky) / (k0 * k0);
      if (kappa2 > 0) lowest = std::min(lowest, std::max(kEngineKappaFloor, std::sqrt(kappa2)));
    }
  }
  return std::min(kz_min, lowest) - kRoundingSlack;
}

void evaluate_k_grid(const CellFactory& make_cell, double ax_um, const TableGrid& grid, const TableSamples& t,
                     fdtd::SimParams sim, const Options& opt, const TableBuilder::Progress& progress,
                     CourantCheck& courant, SampleValues& out) {
  const KGrid g = k_grid(grid, t.samples, opt.k_step_per_um);
  sim.kz_min = engine_kz_min_k_grid(g, grid, t, sim.kz_min);
  std::vector<double> omegas;
  for (double lam : grid.lambda_nm) omegas.push_back(2.0 * fdtd::kPi / (lam * 1e-3));
  const fdtd::Cell cell = make_cell(-1.0);
  double ky_max = 0;
  for (const auto& jb : g.jobs) ky_max = std::max(ky_max, std::abs(jb.ky));
  if (!g.jobs.empty()) courant.check(cell, ky_max);
  const std::vector<fdtd::Spectrum> spectra = run_nodes(cell, g.jobs, omegas, ax_um, sim, opt, progress, out);
  interpolate_samples(g, spectra, t, out);
}

// How the entries were filled (for the notes and warnings).
struct EntryCounts {
  std::size_t continued = 0, fallback = 0, grazing_only = 0;
  std::size_t below_kz_min = 0, simulated_grazing = 0;
  double min_simulated_kappa = 1.0;
};

// Issue 9: simulated entries so near grazing that the engine's own error is large (6.7e-3 at
// k_z/k0 = 0.1, 3.0e-2 at 0.05 on the layered cell, NOTES §5a) — reachable only with a kz_min
// below it.
constexpr double kGrazingSimulated = 0.1;

// Entries: simulated value; below kz_min (or without support) the grazing continuation from
// the anchors on the entry's radial k_∥ line; if an anchor is missing too, the continuation
// from the nearest simulated entry of the row (one anchor: Z constant); with neither, −I.
EntryCounts fill_entries(ReflectionTable& table, const TableGrid& grid, const TableSamples& t,
                         const std::vector<std::optional<JonesReflection>>& value, double kz_min) {
  EntryCounts n;
  const std::size_t NA = t.anchor_kappa.size();
  for (std::size_t l = 0; l < t.NL; ++l)
    for (std::size_t i = 0; i < t.NT; ++i)
      for (std::size_t j = 0; j < t.NP; ++j) {
        const std::size_t e = t.idx(l, i, j);
        const double kappa = grid.cos_theta[i] * grid.cos_phi[j];
        if (kappa < kz_min) ++n.below_kz_min;
        if (t.entry_sample[e] != SIZE_MAX && value[t.entry_sample[e]]) {
          table.at(l, i, j) = *value[t.entry_sample[e]];
          if (kappa < kGrazingSimulated) ++n.simulated_grazing, n.min_simulated_kappa = std::min(n.min_simulated_kappa, kappa);
          continue;
        }
        std::vector<GrazingAnchor> anchors;
        if (t.anchor_base[e] != SIZE_MAX)
          for (std::size_t m = 0; m < NA; ++m)
            if (value[t.anchor_base[e] + m]) anchors.push_back({t.anchor_kappa[m], *value[t.anchor_base[e] + m]});
        if (anchors.size() == NA && NA > 0) {
          table.at(l, i, j) = continue_to_grazing(anchors, kappa);
          ++n.continued;
          continue;
        }
        anchors.clear();
        for (std::size_t k = j + 1; k < t.NP && anchors.empty(); ++k)
          if (t.entry_sample[t.idx(l, i, k)] != SIZE_MAX && value[t.entry_sample[t.idx(l, i, k)]])
            anchors.push_back({grid.cos_theta[i] * grid.cos_phi[k], *value[t.entry_sample[t.idx(l, i, k)]]});
        if (!anchors.empty()) {
          table.at(l, i, j) = continue_to_grazing(anchors, kappa);
          ++n.fallback;
        } else {
          table.at(l, i, j) = grazing_jones();
          ++n.grazing_only;
        }
      }
  return n;
}

// The table's notes. Issue 9: every condition is both a diagnostics warning (stderr, the run's
// file metadata) and a "WARNING:" in the table's own notes (the .plt keeps it when the table is
// cached and reused); the two warnings the notes carried before issue 9 keep their text (with the
// code appended).
std::string table_notes(const SampleValues& v, const EntryCounts& n, const TableSamples& t, const CourantCheck& courant,
                        const fdtd::SimParams& sim, double ax_um) {
  const RunReport& rep = v.rep;
  const double kz_min = sim.kz_min;
  const std::size_t n_entries = t.NL * t.NT * t.NP;
  std::ostringstream notes;
  notes << "fdtd runs: " << v.runs + v.resumed_runs;
  if (v.resumed_runs > 0) notes << " (" << v.resumed_runs << " resumed from a checkpoint)";
  notes << "; entries continued to the grazing limit (k_z/k0 < " << kz_min << ", impedance form from "
        << t.anchor_kappa.size() << " anchors): " << n.continued << " of " << n_entries;
  if (n.fallback > 0) notes << "; from the nearest simulated entry (anchor without support): " << n.fallback;
  auto report = [&](const char* code, const std::string& message) {
    warn(code, message);
    notes << "; WARNING: " << message << " [" << code << "]";
  };
  if (n.grazing_only > 0)
    notes << "; WARNING: set to the grazing limit (no support): " << n.grazing_only << " [fdtd.no_support]";
  for (const auto& m : courant.notes()) notes << "; WARNING: " << m << " [fdtd.courant]";
  if (rep.blown_up > 0) {
    std::string m = std::to_string(rep.blown_up) + " of " + std::to_string(rep.runs) +
                    " fdtd runs blew up (run-time energy guard) and were rerun at half the time step";
    if (rep.rerun_courant > 0) m += " (" + fmt(rep.rerun_courant) + " of the stability limit)";
    if (!rep.first_blowup.empty()) m += "; first: " + rep.first_blowup;
    report("fdtd.courant", m);
  }
  if (rep.not_converged > 0)
    report("fdtd.not_converged",
           std::to_string(rep.not_converged) + " of " + std::to_string(rep.runs) +
               " fdtd runs stopped at the time cap (max_time = " + fmt(sim.max_time) +
               " um/c, at least the source + 10 um/c" +
               (rep.not_converged_time > 0 ? "; up to " + fmt(rep.not_converged_time) + " um/c simulated" : std::string()) +
               ") before the reflected DFTs settled to dft_tol = " + fmt(sim.dft_tol) + "; their entries may be inaccurate");
  if (n.continued + n.fallback > 0)
    report("fdtd.grazing_continued",
           std::to_string(n.continued + n.fallback) + " of " + std::to_string(n_entries) +
               " entries not simulated but continued to the grazing limit by the impedance form (" +
               std::to_string(n.below_kz_min) + " with k_z/k0 < kz_min = " + fmt(kz_min) + "; " +
               std::to_string(n.fallback) + " from the nearest simulated entry instead of anchors)");
  if (n.grazing_only > 0)
    warn("fdtd.no_support", std::to_string(n.grazing_only) + " of " + std::to_string(n_entries) +
                                " entries had no simulated support and were set to the grazing limit -I");
  if (n.simulated_grazing > 0)
    report("fdtd.grazing_simulated",
           std::to_string(n.simulated_grazing) + " simulated entries have k_z/k0 < " + fmt(kGrazingSimulated) +
               " (down to " + fmt(n.min_simulated_kappa, 3) + ", kz_min = " + fmt(kz_min) +
               "), where the engine error exceeds ~7e-3 (NOTES 5a); raise kz_min to continue them instead");
  if (v.other_orders > 0) {
    std::string m = std::to_string(v.other_orders) + " of " + std::to_string(t.samples.size()) +
                    " samples (entries and grazing anchors) have a second propagating diffraction order (period " +
                    fmt(1000 * ax_um) + " nm > lambda/(1 + |sin|) at the short wavelengths); the table stores "
                    "only the specular order and misses that power";
    std::string detail;
    if (rep.max_other_eff > 0)
      detail = " (up to " + fmt(rep.max_other_eff, 3) + " of the incident power at " +
               fmt(1000 * rep.max_other_eff_lambda) + " nm)";
    warn("fdtd.other_orders", m + detail);
    notes << "; WARNING: " << v.other_orders
          << " samples with other propagating diffraction orders (only the specular order is stored)" << detail
          << " [fdtd.other_orders]";
  }
  return notes.str();
}

}  // namespace

ReflectionTable build_table(const CellFactory& make_cell, double ax_um, const TableGrid& grid,
                            TableMetadata meta, const Options& opt,
                            const TableBuilder::Progress& progress, BuildStats* stats) {
  if (opt.nx < 1) throw Error("fdtd_periodic: nx must be >= 1");
  fdtd::SimParams sim = opt.sim;
  sim.nx = opt.nx;
  meta.resolution_nm = 1000.0 * ax_um / opt.nx;
  ReflectionTable table(grid, meta);
  const TableSamples t = table_samples(grid, sim.kz_min, opt.grazing_anchors);
  SampleValues v;
  v.value.resize(t.samples.size());
  CourantCheck courant(ax_um / opt.nx, sim);
  if (opt.k_step_per_um <= 0.0) {
    fdtd::SimParams engine_sim = sim;  // every sample has κ ≥ kz_min up to rounding
    engine_sim.kz_min -= kRoundingSlack;
    evaluate_per_sample(make_cell, grid, t.samples, engine_sim, opt, progress, courant, v);
  } else {
    evaluate_k_grid(make_cell, ax_um, grid, t, sim, opt, progress, courant, v);
  }
  const EntryCounts n = fill_entries(table, grid, t, v.value, sim.kz_min);
  table.metadata().notes = table_notes(v, n, t, courant, sim, ax_um);
  table.metadata().resolution_nm = meta.resolution_nm;
  if (stats) *stats = {v.runs, v.resumed_runs};
  return table;
}

}  // namespace plumage::fdtd_table
