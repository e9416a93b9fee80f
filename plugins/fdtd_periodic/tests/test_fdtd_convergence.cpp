// Convergence ladder of the three crystal families at the production setting (issue 5
// acceptance: |Δ|r|²| between the two finest resolutions ≤ 2e-3). Slow: CTest label `validation`.
//
// For each crystal (configs/crystals: mallard-green, magpie-blue, peacock-cyan) the same broadband
// runs (Lorentz-fitted materials, as in the production k-grid mode) are done at grid steps
// ≈ 15, 10, 7.6 and 5 nm (nx = round(a_x/h)) at five Bloch wavevectors spanning normal, oblique,
// conical and near-grazing incidence; every valid frequency (k_z/k0 ≥ 0.25, 16 λ from 400 to
// 700 nm) gives a (s, p) Jones matrix (table_build.hpp). Printed per rung: max over frequencies,
// k points and the four Jones elements of ||J_ab|²(h) − |J_ab|²(finest)| and of the difference
// to the next finer rung.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "plumage/crystal_cell.hpp"
#include "builder_params.hpp"
#include "table_build.hpp"

using namespace plumage;

namespace {

std::vector<double> band() {
  std::vector<double> w;
  for (double l = 0.40; l <= 0.70 + 1e-9; l += 0.02) w.push_back(2 * fdtd::kPi / l);
  return w;
}

// Max over common valid frequencies of max_ab ||J_ab|² − |K_ab|²|.
double max_dR(const std::vector<fdtd::Spectrum>& a, const std::vector<fdtd::Spectrum>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t f = 0; f < a[k].freqs.size(); ++f) {
      const auto& fa = a[k].freqs[f];
      const auto& fb = b[k].freqs[f];
      if (!fa.valid || !fb.valid) continue;
      const JonesReflection J = fdtd_table::jones_from_engine(fa), K = fdtd_table::jones_from_engine(fb);
      d = std::max({d, std::abs(std::norm(J.ss) - std::norm(K.ss)), std::abs(std::norm(J.sp) - std::norm(K.sp)),
                    std::abs(std::norm(J.ps) - std::norm(K.ps)), std::abs(std::norm(J.pp) - std::norm(K.pp))});
    }
  return d;
}

}  // namespace

TEST_CASE("convergence ladder of mallard, magpie and peacock crystals", "[validation][ladder]") {
  const double hs_nm[] = {15.0, 10.0, 7.6, 5.0};  // production: 10 nm (register.cpp)
  // (θ, φ) in degrees at 550 nm, converted to a fixed Bloch k (each run covers all valid λ).
  const double angles[][2] = {{0, 0}, {20, 30}, {0, 60}, {45, 0}, {40, 50}};
  const auto omegas = band();
  for (const char* name : {"mallard-green", "magpie-blue", "peacock-cyan"}) {
    const CrystalCell cc = load_crystal_cell(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs/crystals" /
                                             (std::string(name) + ".yaml"));
    const fdtd::Cell cell = fdtd_table::cell_from_crystal(cc, -1.0);
    const fdtd_table::CrystalNumerics numerics = fdtd_table::crystal_numerics(cc);
    std::vector<fdtd::Job> jobs;
    for (const auto& a : angles) {
      const auto [kx, ky] = fdtd_table::engine_k(550.0, a[0] * fdtd::kPi / 180, a[1] * fdtd::kPi / 180);
      jobs.push_back({kx, ky});
    }
    std::vector<std::vector<fdtd::Spectrum>> rungs;
    std::vector<int> nxs;
    for (double h : hs_nm) {
      fdtd::SimParams p;
      p.nx = std::max(4, static_cast<int>(std::lround(cc.a_x_nm / h)));
      p.dispersion_correction = numerics.dispersion_correction;  // the crystal's numerics (NOTES §3a)
      p.exact_fill = numerics.exact_fill;
      nxs.push_back(p.nx);
      rungs.push_back(fdtd::run_batch(cell, jobs, omegas, p, 2));
      double cpu = 0;
      for (const auto& s : rungs.back()) cpu += s.stats.cpu_seconds;
      std::printf("[ladder] %s nx=%d (h=%.2f nm): %.1f s cpu for %zu runs\n", name, p.nx, cc.a_x_nm / p.nx, cpu,
                  jobs.size());
    }
    const std::size_t n = rungs.size();
    for (std::size_t r = 0; r + 1 < n; ++r) {
      std::printf("[ladder] %s h=%.2f nm: max|d|r|^2| vs next finer (%.2f nm) = %.2e, vs finest (%.2f nm) = %.2e\n",
                  name, cc.a_x_nm / nxs[r], cc.a_x_nm / nxs[r + 1], max_dR(rungs[r], rungs[r + 1]),
                  cc.a_x_nm / nxs[n - 1], max_dR(rungs[r], rungs[n - 1]));
    }
    // Acceptance (issue 5): the two finest rungs agree to 2e-3 in |r|².
    CHECK(max_dR(rungs[n - 2], rungs[n - 1]) <= 2e-3);
  }
}
