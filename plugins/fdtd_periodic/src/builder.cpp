#include "builder.hpp"

#include <cmath>
#include <cstdio>

#include "plumage/memory_budget.hpp"
#include "table_build.hpp"

namespace plumage::fdtd_table {

// The peak of a build: `threads` runs at once, each with its two main grids (families 0 and 1;
// the 1-cell normalisation grids are negligible) of nx × nz Yee cells. Per cell: 13 complex field
// and CPML arrays (E, H, D, ψ: 208 B), the Lorentz sums and inverse permittivities (3 complex +
// 3 double + 3 complex: 120 B), and per global Lorentz pole its P, P⁻ (6 complex), weights and
// site lists (3 double + 3 (int, double)): 168 B, bounded over the whole grid although each pole
// covers only its material's rows. The x-resolved transmission DFTs add 4 × wavelengths × nx
// complex per grid. docs/benchmarks.md "Memory estimates" compares it with measured peaks.
MemoryEstimate FdtdTableBuilder::estimate_memory(const CrystalCell& cell, const TableGrid& grid) const {
  const BuildPlan plan = plan_build(params_, cell);
  const Options& o = plan.options;
  const fdtd::Cell engine_cell = cell_from_crystal(cell, -1.0);
  std::size_t poles = 0;
  for (const auto& m : engine_cell.materials) poles += m.poles.size();
  const double h_um = cell.a_x_nm * 1e-3 / o.nx;
  const double nz = 2.0 * o.sim.pml_cells + std::ceil(o.sim.air_above / h_um) +
                    std::ceil((engine_cell.structure_depth + o.sim.substrate_below) / h_um) + 1.0;
  const double cells = static_cast<double>(o.nx) * nz;
  const double grids = 2.0 * o.threads;
  MemoryEstimate e;
  char job[240];
  std::snprintf(job, sizeof job, "fdtd_periodic table of crystal '%s': %d threads x 2 grids of %d x %.0f cells (h = %.3g nm)",
                cell.name.c_str(), o.threads, o.nx, nz, 1000.0 * h_um);
  e.job = job;
  e.add("fields and CPML", grids * cells * 208.0);
  e.add("Lorentz sums and permittivities", grids * cells * 120.0);
  e.add("Lorentz poles (" + std::to_string(poles) + ")", grids * cells * 168.0 * static_cast<double>(poles));
  e.add("transmission DFTs", grids * 4.0 * 16.0 * static_cast<double>(grid.lambda_nm.size()) * o.nx);
  // The worker threads' touched stacks and per-thread allocator arenas: the measured peaks of the
  // preview cells were 0.3-0.7 MiB above the other parts at 2 threads (docs/benchmarks.md).
  e.add("worker threads", 512.0 * 1024.0 * o.threads);
  e.add("table and samples", 64.0 * static_cast<double>(grid.lambda_nm.size() * grid.cos_theta.size() * grid.cos_phi.size()) *
                                 (1.0 + o.grazing_anchors));
  e.lower_with = {"resolution_nm (now " + std::to_string(1000.0 * h_um).substr(0, 6) + " nm: a coarser grid)",
                  "threads (now " + std::to_string(o.threads) + ")",
                  "the crystal's a_x_nm / rows / cortex_nm (a smaller cell)"};
  return e;
}

ReflectionTable FdtdTableBuilder::build(const CrystalCell& cell, const TableGrid& grid, Progress progress) const {
  // Before any run (issue 23): a grid that would not fit is refused, not killed or thrown as
  // std::length_error from a vector (a_x_nm: 1e9).
  check_memory(estimate_memory(cell, grid));
  const BuildPlan plan = plan_build(params_, cell);
  return build_table([&cell](double lambda_um) { return cell_from_crystal(cell, lambda_um); }, cell.a_x_nm * 1e-3,
                     grid, plan.meta, plan.options, progress);
}

}  // namespace plumage::fdtd_table
