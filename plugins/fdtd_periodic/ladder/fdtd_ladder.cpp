// Accuracy ladder "fdtd_periodic" (issue 9): the engine at growing resolution (cells per period,
// h = a_x / nx) against
//  * the multilayer limit: a laterally uniform keratin/melanin stack, whose reflected field the
//    closed-form Airy recursion of the reference library (reference/airy.hpp) gives exactly
//    (written without the engine's code paths); metric max |E_r − E_ref| over the valid band and
//    both polarizations;
//  * its finest resolution on a real crystal (mallard-green, configs/crystals): max over the
//    valid band and the four Jones elements of ||J_ab|²(h) − |J_ab|²(h_finest)| — the issue-5
//    acceptance metric (≤ 2e-3 between the two finest production rungs).
// Both at one oblique, conical incidence, broadband runs with the production numerics.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "fdtd_ladder.hpp"

#include "airy.hpp"
#include "builder_params.hpp"
#include "fdtd_periodic.hpp"
#include "layered_cell.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/error.hpp"
#include "table_build.hpp"

namespace plumage::fdtd_table {

namespace {

std::vector<double> band_omegas() {
  std::vector<double> w;
  for (double l = 0.40; l <= 0.70 + 1e-9; l += 0.02) w.push_back(2 * fdtd::kPi / l);
  return w;
}

LadderPoint point(const std::string& case_name, double h_nm, int nx, const std::string& reference,
                  const std::string& metric, double error, const fdtd::Spectrum& s) {
  LadderPoint pt;
  pt.backend = "fdtd_periodic";
  pt.case_name = case_name;
  char setting[48];
  std::snprintf(setting, sizeof setting, "h=%.3g nm (nx=%d)", h_nm, nx);
  pt.setting = setting;
  pt.fidelity = 1.0 / h_nm;
  pt.reference = reference;
  pt.metric = metric;
  pt.error = error;
  pt.wall_s = s.stats.wall_seconds;
  pt.cpu_s = s.stats.cpu_seconds;
  return pt;
}

}  // namespace

const ParamTable<LadderParams>& ladder_params() {
  static const auto table = ParamTable<LadderParams>{}.text(
      "crystal", &LadderParams::crystal, "configs/crystals/mallard-green.yaml", "crystal cell of the second case");
  return table;
}

namespace {

constexpr double kTheta = 25.0 * fdtd::kPi / 180.0, kPhi = 40.0 * fdtd::kPi / 180.0;

// 1. Layered stack: air | keratin 300 nm | melanin 200 nm | keratin, two cells wide, against the
// closed-form Airy recursion with the same fitted ε.
void layered_case(const AccuracyLadder::Options& options, std::vector<LadderPoint>& points) {
  const auto omegas = band_omegas();
  const std::vector<double> hs_nm = options.quick ? std::vector<double>{20, 14, 10} : std::vector<double>{20, 14, 10, 7, 5};
  const char* name = "keratin 300 nm / melanin 200 nm stack (25, 40) deg";
  for (double h_nm : hs_nm) {
    const double h = h_nm / 1000.0;
    const fdtd::Cell c = fdtd_reference::layered_cell(h, 2, -1.0);
    fdtd::SimParams p;
    p.nx = 2;
    const double k0 = 2 * fdtd::kPi / 0.55;
    const double kx = -k0 * std::cos(kTheta) * std::sin(kPhi), ky = -k0 * std::sin(kTheta);
    const fdtd::Spectrum s = fdtd::run_spectrum(c, kx, ky, omegas, p);
    double worst = 0.0;
    for (const auto& f : s.freqs) {
      if (!f.valid) continue;
      fdtd_reference::Stack st;
      st.eps = {1.0, c.materials[1].eps(f.omega), c.materials[2].eps(f.omega), c.materials[1].eps(f.omega)};
      st.thick = {0.3, 0.2};
      fdtd::Vec3c eb[2], hb[2];
      fdtd::incident_basis(f.sin_theta, f.cos_theta, f.sin_phi, f.cos_phi, eb, hb);
      for (int q = 0; q < 2; ++q) {
        const auto ref = fdtd_reference::reflect(st, f.omega, kx, ky, eb[q]);
        for (int j = 0; j < 3; ++j) worst = std::max(worst, std::abs(f.E[q][j] - ref[0][j]));
      }
    }
    points.push_back(point(name, h_nm, p.nx, "closed-form Airy recursion (multilayer limit)",
                           "max |E_r - E_ref|, 400-700 nm, both pols", worst, s));
    if (options.progress) {
      char line[200];
      std::snprintf(line, sizeof line, "stack h=%.3g nm: error %.3g, %.3g s", h_nm, worst, s.stats.wall_seconds);
      options.progress(line);
    }
  }
}

// 2. A real crystal (with its own numerics, NOTES §3a) against its finest rung.
void crystal_case(const AccuracyLadder::Options& options, const std::string& crystal_file,
                  std::vector<LadderPoint>& points) {
  if (!std::filesystem::exists(crystal_file)) {
    throw Error("accuracy ladder 'fdtd_periodic': " + crystal_file +
                " not found (run `plumage bench ladder` from the source tree's top folder)");
  }
  const auto omegas = band_omegas();
  const CrystalCell cc = load_crystal_cell(crystal_file);
  const fdtd::Cell cell = cell_from_crystal(cc, -1.0);
  const CrystalNumerics numerics = crystal_numerics(cc);
  const std::vector<double> hs_nm = options.quick ? std::vector<double>{15, 10, 7.6} : std::vector<double>{15, 10, 7.6, 5, 3.8};
  const auto [kx, ky] = engine_k(550.0, kTheta, kPhi);
  std::vector<fdtd::Spectrum> rungs;
  std::vector<int> nxs;
  for (double h : hs_nm) {
    fdtd::SimParams p;
    p.nx = std::max(4, static_cast<int>(std::lround(cc.a_x_nm / h)));
    p.dispersion_correction = numerics.dispersion_correction;
    p.exact_fill = numerics.exact_fill;
    nxs.push_back(p.nx);
    rungs.push_back(fdtd::run_spectrum(cell, kx, ky, omegas, p));
    if (options.progress) {
      char line[160];
      std::snprintf(line, sizeof line, "%s nx=%d: %.3g s", cc.name.c_str(), p.nx, rungs.back().stats.wall_seconds);
      options.progress(line);
    }
  }
  const auto& finest = rungs.back();
  char case_name[96];
  std::snprintf(case_name, sizeof case_name, "%s crystal (25, 40) deg", cc.name.c_str());
  char reference[96];
  std::snprintf(reference, sizeof reference, "its finest rung (h=%.3g nm)", cc.a_x_nm / nxs.back());
  for (std::size_t r = 0; r + 1 < rungs.size(); ++r) {
    double d = 0.0;
    for (std::size_t f = 0; f < rungs[r].freqs.size(); ++f) {
      const auto& fa = rungs[r].freqs[f];
      const auto& fb = finest.freqs[f];
      if (!fa.valid || !fb.valid) continue;
      const JonesReflection J = jones_from_engine(fa), K = jones_from_engine(fb);
      d = std::max({d, std::abs(std::norm(J.ss) - std::norm(K.ss)), std::abs(std::norm(J.sp) - std::norm(K.sp)),
                    std::abs(std::norm(J.ps) - std::norm(K.ps)), std::abs(std::norm(J.pp) - std::norm(K.pp))});
    }
    points.push_back(point(case_name, cc.a_x_nm / nxs[r], nxs[r], reference,
                           "max ||J_ab|^2 - |J_ab,ref|^2|, 400-700 nm", d, rungs[r]));
  }
}

}  // namespace

std::vector<LadderPoint> run_fdtd_ladder(const AccuracyLadder::Options& options, const std::string& crystal_file) {
  std::vector<LadderPoint> points;
  layered_case(options, points);
  crystal_case(options, crystal_file, points);
  return points;
}

}  // namespace plumage::fdtd_table
