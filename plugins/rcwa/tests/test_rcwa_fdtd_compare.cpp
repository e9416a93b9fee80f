// Comparison with an FDTD table on its own grid (issue 27 part 2; NOTES.md §4). Not part of any
// suite (hidden tag): it needs an FDTD table built beforehand (minutes of CPU),
//   plumage table build configs/crystals/<cell>.yaml --n-lambda 7 --n-theta 4 --n-phi 4 --out fdtd.plt
//   RCWA_FDTD_TABLE=fdtd.plt RCWA_CELL=<cell> test_rcwa "[fdtd-compare]"
// (RCWA_HARMONICS, RCWA_SLICES, RCWA_RICHARDSON=1 replace the production settings of the cell)
// and prints, per entry the FDTD simulated (cos θ cos φ ≥ 0.25), |r|² of the rcwa at production,
// the rcwa converged (Richardson in slices from 24 and 48 per rod diameter at M = 8) and the
// FDTD, and the summary: max and mean |Δ|r|²| and the entries above 0.005.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "builder.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/reflection_table.hpp"
#include "slicing.hpp"
#include "solver.hpp"

using namespace plumage;
using namespace plumage::rcwa;

namespace {

double max_power_difference(const JonesReflection& a, const JonesReflection& b) {
  return std::max({std::abs(std::norm(a.ss) - std::norm(b.ss)), std::abs(std::norm(a.sp) - std::norm(b.sp)),
                   std::abs(std::norm(a.ps) - std::norm(b.ps)), std::abs(std::norm(a.pp) - std::norm(b.pp))});
}

struct Summary {
  double max = 0, sum = 0;
  int count = 0, above = 0;
  void add(double d) { max = std::max(max, d), sum += d, ++count, above += d > 0.005 ? 1 : 0; }
  void print(const char* what) const {
    std::printf("%s: %d entries, max %.4f, mean %.4f, > 0.005: %d\n", what, count, max, count ? sum / count : 0.0, above);
  }
};

}  // namespace

TEST_CASE("rcwa: against an FDTD table on its grid", "[.][fdtd-compare]") {
  const char* table_file = std::getenv("RCWA_FDTD_TABLE");
  const char* cell_name = std::getenv("RCWA_CELL");
  if (!table_file || !cell_name) FAIL("set RCWA_FDTD_TABLE and RCWA_CELL");
  const ReflectionTable fdtd = ReflectionTable::load(table_file);
  const CrystalCell cell = load_crystal_cell(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/" + cell_name + ".yaml");
  BuilderParams params;
  if (const char* v = std::getenv("RCWA_HARMONICS")) params.harmonics = std::atoi(v);
  if (const char* v = std::getenv("RCWA_SLICES")) params.slices_per_row = std::atoi(v);
  params.richardson = std::getenv("RCWA_RICHARDSON") != nullptr;
  const BuildSettings production = build_settings(params, cell_settings(cell));
  const SlicedCell sliced = slice_crystal(cell, production.slices_per_row);
  const SlicedCell half = slice_crystal(cell, std::max(1, production.slices_per_row / 2));
  const SlicedCell s24 = slice_crystal(cell, 24), s48 = slice_crystal(cell, 48);
  const SolverSettings converged{.harmonics = 8, .li_rule = true};
  const TableGrid& g = fdtd.grid();
  Summary prod_vs_fdtd, conv_vs_fdtd, prod_vs_conv;
  std::printf("lambda cos_t cos_p | ss pp: rcwa-prod rcwa-conv fdtd | max|d| conv-fdtd\n");
  for (std::size_t il = 0; il < g.lambda_nm.size(); ++il)
    for (std::size_t it = 0; it < g.cos_theta.size(); ++it)
      for (std::size_t ip = 0; ip < g.cos_phi.size(); ++ip) {
        if (g.cos_theta[it] * g.cos_phi[ip] < 0.25 - 1e-12) continue;  // continued, not simulated, by the FDTD
        const double l = g.lambda_nm[il], t = std::acos(g.cos_theta[it]), p = std::acos(g.cos_phi[ip]);
        const JonesReflection a = production.richardson
                                      ? solve_entry_extrapolated(half, sliced, l, t, p, production.solver).jones
                                      : solve_entry(sliced, l, t, p, production.solver).jones;
        const JonesReflection c = solve_entry_extrapolated(s24, s48, l, t, p, converged).jones;
        const JonesReflection& f = fdtd.at(il, it, ip);
        prod_vs_fdtd.add(max_power_difference(a, f));
        conv_vs_fdtd.add(max_power_difference(c, f));
        prod_vs_conv.add(max_power_difference(a, c));
        std::printf("%.0f %.2f %.2f | %.4f %.4f  %.4f %.4f  %.4f %.4f | %.4f\n", l, g.cos_theta[it], g.cos_phi[ip],
                    std::norm(a.ss), std::norm(a.pp), std::norm(c.ss), std::norm(c.pp), std::norm(f.ss), std::norm(f.pp),
                    max_power_difference(c, f));
      }
  std::printf("rcwa production: M = %d, %d slices%s\n", production.solver.harmonics, production.slices_per_row,
              production.richardson ? ", Richardson" : "");
  prod_vs_fdtd.print("rcwa production vs fdtd");
  conv_vs_fdtd.print("rcwa converged vs fdtd");
  prod_vs_conv.print("rcwa production vs rcwa converged");
  CHECK(conv_vs_fdtd.count > 0);
}
