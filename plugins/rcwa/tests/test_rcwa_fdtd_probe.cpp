// Which FDTD setting loses accuracy near kz_min (issue 27 part 2; NOTES.md §4): the fdtd_periodic
// builder through the registry (no link to that plug-in), one run per entry (k_step 0), at
// entries with cos θ cos φ = 0.25 and 0.5, its defaults and one setting changed at a time,
// against the rcwa converged (M = 8, Richardson from 24 and 48 slices). Hidden: ~1 min CPU,
//   test_rcwa "[fdtd-probe]"
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>

#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/table_builder.hpp"
#include "slicing.hpp"
#include "solver.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::rcwa;

TEST_CASE("rcwa: FDTD settings near kz_min against the rcwa", "[.][fdtd-probe]") {
  const CrystalCell cell = load_crystal_cell(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
  TableGrid grid;
  grid.lambda_nm = {550, 700};
  grid.cos_theta = {0.5, 1.0};
  grid.cos_phi = {0.5, 1.0};  // cos α = 0.25, 0.5, 0.5, 1
  const SlicedCell s24 = slice_crystal(cell, 24), s48 = slice_crystal(cell, 48);
  // Measured 2026-12-03 (NOTES.md §4): pml_cells 64 and dft_tol 3e-5 change nothing; the entries at
  // cos α = 0.25 are not simulated at kz_min = 0.25 (continued from the nearest simulated entry).
  // k_step 0 (one run per entry) and "kz_min: 0.2": 0.0012; at 5 nm 0.0010. Then the production
  // Bloch-k grid (k_step 0.5/um) with kz_min 0.25, 0.2, 0.3:
  const char* variants[] = {"k_step_per_um: 0\n", "k_step_per_um: 0\nkz_min: 0.2\n",
                            "k_step_per_um: 0\nkz_min: 0.2\nresolution_nm: 5\n", "", "kz_min: 0.2\n", "kz_min: 0.3\n"};
  const char* only = std::getenv("RCWA_PROBE_FROM");  // skip the first variants
  for (std::size_t v = only ? std::strtoul(only, nullptr, 10) : 0; v < std::size(variants); ++v) {
    const char* variant = variants[v];
    const ConfigDocument doc = ConfigDocument::parse(std::string("threads: 1\n") + variant, "fdtd.yaml");
    auto fdtd = plumage::testing::registry().create_named<TableBuilder>("fdtd_periodic", doc.root(),
                                                                          plumage::testing::registry().context());
    const ReflectionTable t = fdtd->build(cell, grid, {});
    std::printf("fdtd variant [%s]:", variant);
    for (std::size_t il = 0; il < 2; ++il)
      for (std::size_t it = 0; it < 2; ++it)
        for (std::size_t ip = 0; ip < 2; ++ip) {
          const double l = grid.lambda_nm[il], th = std::acos(grid.cos_theta[it]), ph = std::acos(grid.cos_phi[ip]);
          const JonesReflection r = solve_entry_extrapolated(s24, s48, l, th, ph, {.harmonics = 8, .li_rule = true}).jones;
          const JonesReflection& f = t.at(il, it, ip);
          std::printf(" (%.0f, %.2f, %.2f) d|r_ss|^2 %+.4f d|r_pp|^2 %+.4f;", l, grid.cos_theta[it], grid.cos_phi[ip],
                      std::norm(f.ss) - std::norm(r.ss), std::norm(f.pp) - std::norm(r.pp));
        }
    std::printf("\n");
    std::fflush(stdout);
  }
}
