// The options of ScatteringSolver "bem" and their parameter table (param_table.hpp). The default
// of every option is written once, here, with the measurement behind it; the table names it, gives
// its unit, range and one-line doc, and takes the default from BemOptions{} (so a BemOptions made
// in C++ and one read from an empty config section agree). `plumage plugins describe bem` and
// docs/parameters.md list the table.
#pragma once

#include <string>
#include <string_view>

#include "hmatrix.hpp"
#include "hodlr.hpp"
#include "pair_integrals.hpp"
#include "plumage/param_table.hpp"

namespace plumage::bem {

struct BemOptions {
  enum class Incidence { beam, plane_wave };
  // dense: LU; gmres: GMRES with the dense matrix as mat-vec; hmatrix: GMRES with the
  // hierarchical matrix (exact sparse near field + ACA blocks, hmatrix.hpp) as mat-vec and the LU
  // of (part of) its near field as preconditioner — the solver for large barbules.
  enum class Method { dense, gmres, hmatrix };
  double points_per_wavelength = 30.0;  // h ≤ λ/(|n| ppw) on both sides of every interface
  // Axial currents get separate half tents at corners turning by this much or more (mesh.hpp;
  // NOTES.md §6.2: shared tents through 90° corners gave error spikes of 1e-2 on blocks).
  double corner_split_deg = 30.0;
  Incidence incidence = Incidence::beam;
  Method method = Method::dense;
  double window_fraction = 0.25;
  // Dense LU (and method gmres, whose mat-vec is the dense matrix) stores N² complex numbers:
  // refuse larger systems (16 GB at 31 600 unknowns) with a clear error instead of exhausting
  // memory; method hmatrix has no such limit.
  int max_dense_unknowns = 20000;
  // Method hmatrix with preconditioner dense_single stores N² complex<float> (8 N² bytes, plus the
  // H-matrix): refused above this size (12.8 GB at 40 000) instead of exhausting memory.
  int max_dense_single_unknowns = 40000;
  double gmres_tolerance = 1e-8;  // relative residual (methods gmres, hmatrix)
  int gmres_restart = 300;
  int gmres_max_iterations = 5000;
  // Numerical rules of the pair integrals (pair_integrals.hpp): not parameters — the probes vary
  // them to measure the quadrature error (NOTES.md §4).
  QuadratureOptions quadrature;
  HMatrixOptions hmatrix;
  HodlrOptions hodlr;  // preconditioner hodlr of method hmatrix (hodlr.hpp)
  // Right-hand sides after the first start GMRES from the residual-minimising combination of all
  // earlier solutions (method gmres/hmatrix; NOTES.md §5).
  bool warm_start = true;
  // Right-hand sides solved together (method gmres/hmatrix): their GMRES run in lockstep, so that the
  // operator and the preconditioner pass over their data once per step for all of them (NOTES.md §5
  // "Right-hand sides together"); the warm start then combines the solutions of the earlier groups.
  // Each column keeps up to 2 gmres_restart + 1 vectors (flexible GMRES): the memory estimate counts
  // them for min(gmres_block, right-hand sides) columns.
  int gmres_block = 8;
  // Memory budget of one solve ("8GiB"; "" = the process's: --max-memory or what the machine has,
  // plumage/memory_budget.hpp): a system whose estimated peak (memory_estimate.hpp) is larger is
  // refused before assembly.
  std::string max_memory;
  // When set, one line of timings and sizes per (λ, θ_i) is appended to this file.
  std::string log_file;
  // Warnings (issue 9; thresholds measured, NOTES.md "Warnings (issue 9)"). bem.mesh_coarse: some
  // segment has fewer points per wavelength (in the denser of its two media) than this — the
  // far field's error on the validation cylinders passes 1e-2 relative L2 there (≤ 0: off).
  double warn_min_ppw = 14.0;
  // bem.near_touching: two boundary pieces that are not neighbours along the mesh come closer
  // than this × their segment length. The far field was measured unaffected down to 1e-4
  // (cylinders and a rod under a surface 0.001 nm apart on ~10 nm segments) and wrong by 1e-2 to
  // 1e-1 for outlines that cross, so this flags contact and crossings, not closeness (≤ 0: off).
  double warn_gap_ratio = 1e-5;
};

// The solver's parameters, declared once: read with bem_options_table().read(section), listed
// with .specs().
const ParamTable<BemOptions>& bem_options_table();

// The word of a method as the table spells it ("dense", "gmres", "hmatrix").
std::string_view method_name(BemOptions::Method method);

}  // namespace plumage::bem
