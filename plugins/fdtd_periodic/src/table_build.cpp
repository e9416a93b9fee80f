#include "table_build.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "grazing.hpp"

namespace plumage::fdtd_table {

namespace {

using fdtd::cplx;
using fdtd::Vec3c;

fdtd::MaterialModel model_of(const Material& m, double lambda_um) {
  if (lambda_um > 0.0) {
    if (m.kind() == Material::Kind::air) return fdtd::air_model();
    const Complex n = m.index(lambda_um * 1000.0);
    return fdtd::constant_model(m.name(), n * n, lambda_um);
  }
  switch (m.kind()) {
    case Material::Kind::air:
      return fdtd::air_model();
    case Material::Kind::keratin:
      return fdtd::keratin_fit().model;
    case Material::Kind::melanin:
      return fdtd::melanin_fit().model;
    case Material::Kind::constant: {
      const Complex n = m.index(550.0);
      if (n.imag() != 0.0)
        throw Error("fdtd_periodic: an absorbing constant material (" + m.name() +
                    ") needs the per-entry mode (k_step_per_um: 0)");
      fdtd::MaterialModel mm;
      mm.name = m.name();
      mm.eps_inf = (n * n).real();
      return mm;
    }
    case Material::Kind::mixture:
      break;
  }
  throw Error("fdtd_periodic: material " + m.name() + " has no broadband model; use k_step_per_um: 0");
}

// Run-level flags kept in the checkpoint (bits 1, 2 of the per-frequency flag byte whose bit 0
// is other_orders), so that a resumed build still reports them (issue 9).
constexpr unsigned kRunNotConverged = 2, kRunRerun = 4;

// Checkpoint records: u32 node, then per frequency u8 valid, u8 flags (bit 0 other_orders, bits
// 1–2 run flags above), 4 f64 angles, 12 complex (E[2], H[2]) as f64 pairs.
void write_record(std::ostream& os, std::uint32_t node, const fdtd::Spectrum& s, unsigned run_flags) {
  os.write(reinterpret_cast<const char*>(&node), 4);
  for (const auto& f : s.freqs) {
    const char flags[2] = {static_cast<char>(f.valid), static_cast<char>((f.other_orders ? 1u : 0u) | run_flags)};
    os.write(flags, 2);
    const double a[4] = {f.sin_theta, f.cos_theta, f.sin_phi, f.cos_phi};
    os.write(reinterpret_cast<const char*>(a), sizeof a);
    for (int q = 0; q < 2; ++q) {
      os.write(reinterpret_cast<const char*>(f.E[q].data()), sizeof(Vec3c));
      os.write(reinterpret_cast<const char*>(f.H[q].data()), sizeof(Vec3c));
    }
  }
}

bool read_record(std::istream& is, std::size_t nfreq, std::uint32_t& node, fdtd::Spectrum& s, unsigned& run_flags) {
  if (!is.read(reinterpret_cast<char*>(&node), 4)) return false;
  s.freqs.assign(nfreq, {});
  run_flags = 0;
  for (auto& f : s.freqs) {
    char flags[2];
    double a[4];
    if (!is.read(flags, 2) || !is.read(reinterpret_cast<char*>(a), sizeof a)) return false;
    f.valid = flags[0] != 0;
    f.other_orders = (static_cast<unsigned char>(flags[1]) & 1u) != 0;
    run_flags |= static_cast<unsigned char>(flags[1]) & (kRunNotConverged | kRunRerun);
    f.sin_theta = a[0], f.cos_theta = a[1], f.sin_phi = a[2], f.cos_phi = a[3];
    for (int q = 0; q < 2; ++q) {
      if (!is.read(reinterpret_cast<char*>(f.E[q].data()), sizeof(Vec3c))) return false;
      if (!is.read(reinterpret_cast<char*>(f.H[q].data()), sizeof(Vec3c))) return false;
    }
  }
  s.stats.converged = (run_flags & kRunNotConverged) == 0;
  return true;
}

Complex dot(const Vec3c& a, const double s[3]) { return a[0] * s[0] + a[1] * s[1] + a[2] * s[2]; }

}  // namespace

fdtd::Cell cell_from_crystal(const CrystalCell& c, double lambda_um) {
  fdtd::Cell cell;
  cell.ax = c.a_x_nm * 1e-3;
  cell.materials = {fdtd::air_model(), model_of(c.host, lambda_um), model_of(c.rod, lambda_um),
                    model_of(c.core, lambda_um), model_of(c.channel, lambda_um)};
  cell.ambient = 0;
  cell.substrate = 1;
  double deepest = 0.0;
  for (int j = 0; j < c.rows; ++j) {
    const double zj = c.rod_depth_nm(j) * 1e-3;
    const double xj = c.shifted(j) ? 0.5 * cell.ax : 0.0;
    cell.circles.push_back({xj, zj, 0.5e-3 * c.rod_diameter_nm, 2});
    if (c.core_diameter_nm > 0) cell.circles.push_back({xj, zj, 0.5e-3 * c.core_diameter_nm, 3});
    deepest = std::max(deepest, zj + 0.5e-3 * c.rod_diameter_nm);
    if (c.channel_diameter_nm > 0) {
      const double zc = zj + 0.5e-3 * c.a_z_nm;
      cell.circles.push_back({0.5 * cell.ax, zc, 0.5e-3 * c.channel_diameter_nm, 4});
      deepest = std::max(deepest, zc + 0.5e-3 * c.channel_diameter_nm);
    }
  }
  cell.structure_depth = deepest;
  return cell;
}

std::pair<double, double> engine_k(double lambda_nm, double theta, double phi) {
  const double k0 = 2.0 * fdtd::kPi / (lambda_nm * 1e-3);
  return {-k0 * std::cos(theta) * std::sin(phi), k0 * std::sin(theta)};
}

JonesReflection jones_from_engine(const fdtd::FreqResult& f) {
  const double st = f.sin_theta, ct = f.cos_theta, sp = f.sin_phi, cp = f.cos_phi;
  const double w[3] = {ct * sp, st, -ct * cp};  // ω_i, engine frame
  // ŝ = ω_i × n̂ with n̂ = (0, 0, −1): (−w_y, w_x, 0)
  double s[3] = {-w[1], w[0], 0.0};
  const double len = std::hypot(s[0], s[1]);
  if (len < 1e-4) {
    s[0] = 0.0, s[1] = -1.0;  // R ŷ
  } else {
    s[0] /= len, s[1] /= len;
  }
  Vec3c eb[2], hb[2];
  fdtd::incident_basis(st, ct, sp, cp, eb, hb);
  Complex B[2][2], C[2][2];
  for (int q = 0; q < 2; ++q) {
    B[0][q] = dot(eb[q], s);
    B[1][q] = dot(hb[q], s);
    C[0][q] = dot(f.E[q], s);
    C[1][q] = dot(f.H[q], s);
  }
  const Complex det = B[0][0] * B[1][1] - B[0][1] * B[1][0];
  const Complex Bi[2][2] = {{B[1][1] / det, -B[0][1] / det}, {-B[1][0] / det, B[0][0] / det}};
  Complex J[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) J[a][b] = C[a][0] * Bi[0][b] + C[a][1] * Bi[1][b];
  return {J[0][0], J[0][1], J[1][0], J[1][1]};
}

namespace {

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

// run_batch, with a run that blows up (engine guard: non-finite or growing field energy) rerun
// once at half the time step: a time-step instability (the scheme beyond its stability limit,
// NOTES §3b) disappears there, and the rerun is reported. A second blow-up, or any other error,
// stops the build. `rerun` (optional) receives 1 per rerun job.
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
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      if (msg.find("blow-up") == std::string::npos) throw;
      if (rep.blown_up == 0) rep.first_blowup = msg + " at (k_x, k_y) = (" + std::to_string(jobs[j].kx) + ", " +
                                                std::to_string(jobs[j].ky) + ") /um";
      ++rep.blown_up;
      redo.push_back(j);
    }
  }
  if (!redo.empty()) {
    fdtd::SimParams half = sim;
    if (half.dt > 0) half.dt *= 0.5;
    else half.courant *= 0.5;
    std::vector<fdtd::Job> again;
    for (std::size_t j : redo) again.push_back(jobs[j]);
    std::vector<fdtd::Spectrum> fixed;
    try {
      fixed = fdtd::run_batch(cell, again, omegas, half, threads);
    } catch (const std::runtime_error& e) {
      throw Error(std::string("fdtd_periodic: a run is unstable even at half the time step (") + e.what() +
                  "); first failure: " + rep.first_blowup);
    }
    for (std::size_t r = 0; r < redo.size(); ++r) {
      out[redo[r]] = std::move(fixed[r]);
      if (rerun) (*rerun)[redo[r]] = 1;
      const auto& st = out[redo[r]].stats;
      if (st.dt_limit > 0) rep.rerun_courant = std::max(rep.rerun_courant, st.dt / st.dt_limit);
    }
  }
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

// A point where the Jones matrix is needed: a table entry or a grazing anchor.
struct Sample {
  std::size_t l;
  double theta, phi;
};

// One run per sample with exact ε(λ) (the per-entry mode). Samples grouped by λ.
void evaluate_per_sample(const CellFactory& make_cell, const TableGrid& grid, const std::vector<Sample>& samples,
                         const fdtd::SimParams& sim, const Options& opt, const TableBuilder::Progress& progress,
                         std::vector<std::optional<fdtd::FreqResult>>& out, std::size_t& runs, RunReport& rep) {
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
      const auto spectra = run_checked(cell, part, omegas, sim, opt.threads, rep, nullptr);
      for (std::size_t b = 0; b < part.size(); ++b) {
        if (spectra[b].freqs.at(0).valid) out[ids[a + b]] = spectra[b].freqs[0];
      }
      done += part.size();
      runs += part.size();
      if (progress) progress(done, samples.size(), "fdtd runs (one per entry)");
    }
  }
}

// Fraction of the stability limit (stable_time_step: Courant with the exact k_y term, lowered
// for the central-difference ADE) the runs will use, worst over the given k_y: with an explicit
// dt the largest dt / limit (the limit falls with |k_y|), else the Courant factor itself.
double courant_fraction(const fdtd::Cell& cell, double h, double ky_abs_max, const fdtd::SimParams& sim) {
  if (sim.dt > 0) return sim.dt / fdtd::stable_time_step(cell, h, ky_abs_max, sim.lorentz_update);
  return sim.courant;
}

std::string fmt(double v, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

}  // namespace

ReflectionTable build_table(const CellFactory& make_cell, double ax_um, const TableGrid& grid,
                            TableMetadata meta, const Options& opt,
                            const TableBuilder::Progress& progress) {
  if (opt.nx < 1) throw Error("fdtd_periodic: nx must be >= 1");
  fdtd::SimParams sim = opt.sim;
  sim.nx = opt.nx;
  const double kz_min = sim.kz_min;
  meta.resolution_nm = 1000.0 * ax_um / opt.nx;
  ReflectionTable table(grid, meta);
  const std::size_t NL = grid.lambda_nm.size(), NT = grid.cos_theta.size(), NP = grid.cos_phi.size();
  auto idx = [&](std::size_t l, std::size_t i, std::size_t j) { return (l * NT + i) * NP + j; };
  auto angles = [&](std::size_t i, std::size_t j) {
    return std::pair<double, double>{std::acos(std::min(1.0, grid.cos_theta[i])),
                                     std::acos(std::min(1.0, grid.cos_phi[j]))};
  };
  // Samples: every entry with k_z/k0 ≥ kz_min, then the anchors of the grazing continuation
  // (grazing.hpp) of every entry below it: each entry e gets anchors A·e + m.
  const std::vector<double> anchor_kappa = anchor_kappas(kz_min, opt.grazing_anchors);
  const std::size_t NA = anchor_kappa.size();
  std::vector<Sample> samples;
  std::vector<std::size_t> entry_sample(NL * NT * NP, SIZE_MAX), anchor_base(NL * NT * NP, SIZE_MAX);
  for (std::size_t l = 0; l < NL; ++l)
    for (std::size_t i = 0; i < NT; ++i)
      for (std::size_t j = 0; j < NP; ++j) {
        if (grid.cos_theta[i] * grid.cos_phi[j] < kz_min) continue;
        const auto [t, p] = angles(i, j);
        entry_sample[idx(l, i, j)] = samples.size();
        samples.push_back({l, t, p});
      }
  const std::size_t first_anchor = samples.size();
  for (std::size_t l = 0; l < NL; ++l)
    for (std::size_t i = 0; i < NT; ++i)
      for (std::size_t j = 0; j < NP; ++j) {
        if (grid.cos_theta[i] * grid.cos_phi[j] >= kz_min) continue;
        const auto [t, p] = angles(i, j);
        anchor_base[idx(l, i, j)] = samples.size();
        for (double ka : anchor_kappa) {
          const auto [ta, pa] = radial_point(t, p, ka);
          samples.push_back({l, ta, pa});
        }
      }
  std::vector<std::optional<JonesReflection>> value(samples.size());
  std::size_t other_orders = 0, runs_total = 0, resumed_runs = 0;
  RunReport rep;
  const double h_um = ax_um / opt.nx;

  // Issue 9, before any run: the time step against the stability limit of the cell (worst k_y).
  // Above it the scheme is certainly unstable: refused (the builder's `courant` is limited to
  // (0, 1] by its parameter table, so this is reached with an explicit sim.dt); the testing flag
  // allow_unstable_dt turns the refusal into a warning and leaves it to the run-time guard.
  // From kCourantNear on it is reported: at the limit itself the Nyquist mode is only marginally
  // stable, and a 0.2 % excess (layered 2-cell grid) blows up within 4 um/c, so there is no margin
  // for anything the bound does not model (NOTES "Warnings").
  constexpr double kCourantNear = 0.99;
  std::vector<std::string> courant_notes;
  auto check_courant = [&](const fdtd::Cell& cell, double ky_max) {
    const double frac = courant_fraction(cell, h_um, ky_max, sim);
    const double lim = fdtd::stable_time_step(cell, h_um, ky_max, sim.lorentz_update);
    const std::string what = "time step dt = " + fmt(sim.dt > 0 ? sim.dt : frac * lim, 6) + " um/c is " + fmt(frac, 5) +
                             " of the stability limit " + fmt(lim, 6) + " um/c (h = " + fmt(1000 * h_um) +
                             " nm, |k_y| up to " + fmt(ky_max) + " /um)";
    if (frac > 1.0) {
      if (!sim.allow_unstable_dt)
        throw Error("fdtd_periodic: " + what + ": certainly unstable; lower dt (or courant) to at most 1");
      const std::string m = what + ": above the limit, certainly unstable (allow_unstable_dt set)";
      warn("fdtd.courant", m);
      courant_notes.push_back(m);
    } else if (frac >= kCourantNear) {
      const std::string m = what + ": at/near the Courant limit (>= " + fmt(kCourantNear) +
                            "), no stability margin; runs are guarded for field growth";
      warn("fdtd.courant", m);
      courant_notes.push_back(m);
    }
  };

  if (opt.k_step_per_um <= 0.0) {
    // One run per sample, constant ε exact at each λ.
    {
      double worst = -1, ky_worst = 0;
      std::size_t l_worst = 0;
      for (std::size_t l = 0; l < NL; ++l) {
        double ky_max = -1;
        for (const auto& smp : samples)
          if (smp.l == l) ky_max = std::max(ky_max, std::abs(engine_k(grid.lambda_nm[l], smp.theta, smp.phi).second));
        if (ky_max < 0) continue;
        const double f = courant_fraction(make_cell(grid.lambda_nm[l] * 1e-3), h_um, ky_max, sim);
        if (f > worst) worst = f, ky_worst = ky_max, l_worst = l;
      }
      if (worst >= 0) check_courant(make_cell(grid.lambda_nm[l_worst] * 1e-3), ky_worst);
    }
    std::vector<std::optional<fdtd::FreqResult>> res(samples.size());
    evaluate_per_sample(make_cell, grid, samples, sim, opt, progress, res, runs_total, rep);
    for (std::size_t s = 0; s < samples.size(); ++s)
      if (res[s]) {
        value[s] = jones_from_engine(*res[s]);
        if (res[s]->other_orders) ++other_orders;
      }
  } else {
    // Broadband runs on a Bloch-k grid k_x = −a Δk, k_y = b Δk (a, b ≥ 0), bilinear in (k_x, k_y)
    // at each table frequency. Each node gives Jones matrices at its own angles.
    const double dk = opt.k_step_per_um;
    std::map<std::pair<int, int>, std::size_t> nodes;
    struct Corner {
      std::size_t node[4];
      double w[4];
    };
    std::vector<Corner> corners(samples.size());
    for (std::size_t s = 0; s < samples.size(); ++s) {
      const auto [kx, ky] = engine_k(grid.lambda_nm[samples[s].l], samples[s].theta, samples[s].phi);
      const double u = std::max(0.0, -kx / dk), v = std::max(0.0, ky / dk);
      const int a0 = static_cast<int>(std::floor(u)), b0 = static_cast<int>(std::floor(v));
      const double fu = u - a0, fv = v - b0;
      Corner& c = corners[s];
      int k = 0;
      for (int da = 0; da < 2; ++da)
        for (int db = 0; db < 2; ++db, ++k) {
          auto key = std::make_pair(a0 + da, b0 + db);
          auto it = nodes.emplace(key, nodes.size()).first;
          c.node[k] = it->second;
          c.w[k] = (da ? fu : 1.0 - fu) * (db ? fv : 1.0 - fv);
        }
    }
    std::vector<fdtd::Job> jobs(nodes.size());
    for (const auto& [key, n] : nodes) jobs[n] = {-key.first * dk, key.second * dk};
    std::vector<double> omegas;
    for (double lam : grid.lambda_nm) omegas.push_back(2.0 * fdtd::kPi / (lam * 1e-3));
    const fdtd::Cell cell = make_cell(-1.0);
    {
      double ky_max = 0;
      for (const auto& jb : jobs) ky_max = std::max(ky_max, std::abs(jb.ky));
      if (!jobs.empty()) check_courant(cell, ky_max);
    }
    std::vector<fdtd::Spectrum> spectra(jobs.size());
    std::vector<char> have(jobs.size(), 0);
    std::vector<unsigned> run_flags(jobs.size(), 0);
    std::size_t resumed = 0;
    std::ofstream ck;
    if (!opt.checkpoint.empty()) {
      std::ostringstream key;
      key.precision(17);
      key << "plumage-fdtd-checkpoint-1;" << opt.checkpoint_tag << ";ax=" << ax_um << ";nx=" << opt.nx
          << ";dk=" << dk << ";kzmin=" << kz_min << ";tol=" << sim.dft_tol << ";pml=" << sim.pml_cells
          << ";w=";
      for (double w : omegas) key << w << ",";
      key << ";nodes=" << jobs.size() << ";";
      for (const auto& jb : jobs) key << jb.kx << "," << jb.ky << ";";
      const std::string header = fnv1a_hex(key.str());
      {
        std::ifstream in(opt.checkpoint, std::ios::binary);
        std::string h(16, '\0');
        if (in && in.read(h.data(), 16) && h == header) {
          std::uint32_t node;
          fdtd::Spectrum sp;
          unsigned flags = 0;
          while (read_record(in, omegas.size(), node, sp, flags)) {
            if (node < jobs.size() && !have[node]) {
              spectra[node] = std::move(sp);
              have[node] = 1;
              run_flags[node] = flags;
              ++resumed;
            }
          }
        }
      }
      // Rewrite the file with the records read (drops a truncated tail), then append.
      ck.open(opt.checkpoint, std::ios::binary | std::ios::trunc);
      if (!ck) throw Error("fdtd_periodic: cannot write checkpoint " + opt.checkpoint);
      ck.write(header.data(), 16);
      for (std::size_t n = 0; n < jobs.size(); ++n)
        if (have[n]) write_record(ck, static_cast<std::uint32_t>(n), spectra[n], run_flags[n]);
      ck.flush();
    }
    std::vector<std::size_t> todo;
    for (std::size_t n = 0; n < jobs.size(); ++n)
      if (!have[n]) todo.push_back(n);
    const std::size_t chunk = static_cast<std::size_t>(std::max(1, opt.threads)) * 2;
    if (progress && resumed > 0) progress(resumed, jobs.size(), "fdtd broadband runs (Bloch k grid, resumed)");
    for (std::size_t a = 0; a < todo.size(); a += chunk) {
      std::vector<fdtd::Job> part;
      for (std::size_t b = a; b < std::min(todo.size(), a + chunk); ++b) part.push_back(jobs[todo[b]]);
      std::vector<char> rerun;
      auto out = run_checked(cell, part, omegas, sim, opt.threads, rep, &rerun);
      for (std::size_t b = 0; b < out.size(); ++b) {
        const std::size_t n = todo[a + b];
        spectra[n] = std::move(out[b]);
        run_flags[n] = (rerun[b] ? kRunRerun : 0u) |
                       (spectra[n].stats.steps > 0 && !spectra[n].stats.converged ? kRunNotConverged : 0u);
        if (ck.is_open()) write_record(ck, static_cast<std::uint32_t>(n), spectra[n], run_flags[n]);
      }
      if (ck.is_open()) ck.flush();
      runs_total += part.size();
      if (progress) progress(resumed + a + part.size(), jobs.size(), "fdtd broadband runs (Bloch k grid)");
    }
    resumed_runs = resumed;
    // Resumed runs: their stability/convergence flags come from the checkpoint.
    for (std::size_t n = 0; n < jobs.size(); ++n) {
      if (!have[n]) continue;
      ++rep.runs;
      if (run_flags[n] & kRunNotConverged) ++rep.not_converged;
      if (run_flags[n] & kRunRerun) ++rep.blown_up;
    }
    // Bilinear in k of the surface impedance Z = (I + J)(I − J)⁻¹/κ of every corner at its own
    // κ = k_z/k0 (grazing.hpp), mapped back with the sample's κ: J itself has a square-root branch
    // point at the light line (κ = sqrt(1 − |k_∥|²/k0²)) and is poorly interpolated near it.
    for (std::size_t s = 0; s < samples.size(); ++s) {
      const Corner& c = corners[s];
      JonesReflection acc{};
      double wsum = 0.0;
      bool orders = false;
      for (int k = 0; k < 4; ++k) {
        if (c.w[k] == 0.0) continue;
        const fdtd::FreqResult& f = spectra[c.node[k]].freqs.at(samples[s].l);
        if (!f.valid) continue;
        orders = orders || f.other_orders;
        const JonesReflection r = impedance_of(jones_from_engine(f), f.cos_theta * f.cos_phi);
        acc.ss += c.w[k] * r.ss, acc.sp += c.w[k] * r.sp, acc.ps += c.w[k] * r.ps, acc.pp += c.w[k] * r.pp;
        wsum += c.w[k];
      }
      // Too little support: an entry is then treated as not simulated (continued like those below
      // kz_min). An anchor sits next to the invalid region by construction, so any valid corner
      // is used (Z is smooth; the production table otherwise left 1634 entries at −I).
      if (wsum < (s >= first_anchor ? 1e-9 : 0.25)) continue;
      if (orders) ++other_orders;
      acc.ss /= wsum, acc.sp /= wsum, acc.ps /= wsum, acc.pp /= wsum;
      value[s] = jones_of(acc, std::cos(samples[s].theta) * std::cos(samples[s].phi));
    }
  }

  // Entries: simulated value; below kz_min (or without support) the grazing continuation from
  // the anchors on the entry's radial k_∥ line; if an anchor is missing too, the continuation
  // from the nearest simulated entry of the row (one anchor: Z constant).
  std::size_t continued = 0, fallback = 0, grazing_only = 0;
  // Issue 9: entries below kz_min (never simulated), and simulated entries so near grazing that
  // the engine's own error is large (kGrazingSimulated: 6.7e-3 at k_z/k0 = 0.1, 3.0e-2 at 0.05 on
  // the layered cell, NOTES §5a) — reachable only with a kz_min below it.
  constexpr double kGrazingSimulated = 0.1;
  std::size_t below_kz_min = 0, simulated_grazing = 0;
  double min_simulated_kappa = 1.0;
  for (std::size_t l = 0; l < NL; ++l)
    for (std::size_t i = 0; i < NT; ++i) {
      for (std::size_t j = 0; j < NP; ++j) {
        const std::size_t e = idx(l, i, j);
        const double kappa = grid.cos_theta[i] * grid.cos_phi[j];
        if (kappa < kz_min) ++below_kz_min;
        if (entry_sample[e] != SIZE_MAX && value[entry_sample[e]]) {
          table.at(l, i, j) = *value[entry_sample[e]];
          if (kappa < kGrazingSimulated) ++simulated_grazing, min_simulated_kappa = std::min(min_simulated_kappa, kappa);
          continue;
        }
        std::vector<GrazingAnchor> anchors;
        if (anchor_base[e] != SIZE_MAX)
          for (std::size_t m = 0; m < NA; ++m)
            if (value[anchor_base[e] + m]) anchors.push_back({anchor_kappa[m], *value[anchor_base[e] + m]});
        if (anchors.size() == NA && NA > 0) {
          table.at(l, i, j) = continue_to_grazing(anchors, kappa);
          ++continued;
          continue;
        }
        anchors.clear();
        for (std::size_t k = j + 1; k < NP && anchors.empty(); ++k)
          if (entry_sample[idx(l, i, k)] != SIZE_MAX && value[entry_sample[idx(l, i, k)]])
            anchors.push_back({grid.cos_theta[i] * grid.cos_phi[k], *value[entry_sample[idx(l, i, k)]]});
        if (!anchors.empty()) {
          table.at(l, i, j) = continue_to_grazing(anchors, kappa);
          ++fallback;
        } else {
          table.at(l, i, j) = grazing_jones();
          ++grazing_only;
        }
      }
    }
  std::ostringstream notes;
  notes << "fdtd runs: " << runs_total + resumed_runs;
  if (resumed_runs > 0) notes << " (" << resumed_runs << " resumed from a checkpoint)";
  notes << "; entries continued to the grazing limit (k_z/k0 < " << kz_min << ", impedance form from "
        << NA << " anchors): " << continued << " of " << NL * NT * NP;
  if (fallback > 0) notes << "; from the nearest simulated entry (anchor without support): " << fallback;

  // Issue 9: every condition is both a diagnostics warning (stderr, the run's file metadata) and a
  // "WARNING:" in the table's own notes (the .plt keeps it when the table is cached and reused).
  const std::size_t n_entries = NL * NT * NP;
  auto report = [&](const char* code, const std::string& message) {
    warn(code, message);
    notes << "; WARNING: " << message << " [" << code << "]";
  };
  // The two warnings the notes carried before issue 9 keep their text (with the code appended).
  if (grazing_only > 0)
    notes << "; WARNING: set to the grazing limit (no support): " << grazing_only << " [fdtd.no_support]";
  for (const auto& m : courant_notes) notes << "; WARNING: " << m << " [fdtd.courant]";
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
  if (continued + fallback > 0)
    report("fdtd.grazing_continued",
           std::to_string(continued + fallback) + " of " + std::to_string(n_entries) +
               " entries not simulated but continued to the grazing limit by the impedance form (" +
               std::to_string(below_kz_min) + " with k_z/k0 < kz_min = " + fmt(kz_min) + "; " +
               std::to_string(fallback) + " from the nearest simulated entry instead of anchors)");
  if (grazing_only > 0)
    warn("fdtd.no_support", std::to_string(grazing_only) + " of " + std::to_string(n_entries) +
                                " entries had no simulated support and were set to the grazing limit -I");
  if (simulated_grazing > 0)
    report("fdtd.grazing_simulated",
           std::to_string(simulated_grazing) + " simulated entries have k_z/k0 < " + fmt(kGrazingSimulated) +
               " (down to " + fmt(min_simulated_kappa, 3) + ", kz_min = " + fmt(kz_min) +
               "), where the engine error exceeds ~7e-3 (NOTES 5a); raise kz_min to continue them instead");
  if (other_orders > 0) {
    std::string m = std::to_string(other_orders) + " of " + std::to_string(samples.size()) +
                    " samples (entries and grazing anchors) have a second propagating diffraction order (period " +
                    fmt(1000 * ax_um) + " nm > lambda/(1 + |sin|) at the short wavelengths); the table stores "
                    "only the specular order and misses that power";
    std::string detail;
    if (rep.max_other_eff > 0)
      detail = " (up to " + fmt(rep.max_other_eff, 3) + " of the incident power at " +
               fmt(1000 * rep.max_other_eff_lambda) + " nm)";
    warn("fdtd.other_orders", m + detail);
    notes << "; WARNING: " << other_orders
          << " samples with other propagating diffraction orders (only the specular order is stored)" << detail
          << " [fdtd.other_orders]";
  }
  table.metadata().notes = notes.str();
  table.metadata().resolution_nm = meta.resolution_nm;
  return table;
}

}  // namespace plumage::fdtd_table
