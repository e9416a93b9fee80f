// Reflection tables from the periodic FDTD engine (issue 5): frame mapping, conversion of the
// engine's reflected E/H to the (s, p) Jones matrix of local_reflection.hpp, and the k-grid
// driver that maps broadband fixed-Bloch-k runs onto the (λ, cos θ, cos φ) table grid.
//
// Frame mapping. Our local frame (conventions.hpp, at a surface point): normal +z into air,
// axis y, ω_i = (cosθ sinφ, sinθ, cosθ cosφ). Engine frame (fdtd_periodic.hpp): crystal at
// z > 0, outward normal −z. We use the proper rotation R = diag(1, −1, −1) (180° about x), which
// maps our ω_i to the engine's ω_i with θ_e = −θ, φ_e = φ: exact for any y-invariant cell (no
// x-mirror assumed). Being proper, R maps E and η0H alike and preserves cross products, so the
// Jones matrix computed with vectors in the engine frame equals ours:
//   n̂_e = (0, 0, −1), ŝ_e = ω_i,e × n̂_e/|…| (R ŷ = −ŷ at exactly normal incidence),
//   B[:, q] = (E_inc,q·ŝ, η0H_inc,q·ŝ), C[:, q] = (E_r,q·ŝ, η0H_r,q·ŝ)  (engine pol q = 1, 2),
//   J = C B⁻¹.
#pragma once

#include <functional>
#include <string>
#include <utility>

#include "fdtd_periodic.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/reflection_table.hpp"
#include "plumage/table_builder.hpp"

namespace plumage::fdtd_table {

struct Options {
  int nx = 19;               // cells per period
  double k_step_per_um = 0.5;  // Bloch k grid step; 0: one run per table entry (exact ε at λ)
  int threads = 2;
  fdtd::SimParams sim;       // nx is overwritten from `nx`
  // k-grid mode: finished runs are appended to this file after every chunk, and a later build
  // with the same key (tag, grid, nodes, resolution) skips them (resumable builds). Empty: off.
  std::string checkpoint;
  std::string checkpoint_tag;  // identifies the cell (e.g. its config hash)
  // Entries with k_z/k0 < sim.kz_min: anchors per entry of the grazing continuation
  // (grazing.hpp; Z polynomial in κ² of degree anchors − 1).
  // (per crystal: its `fdtd_periodic: {grazing_anchors}`; 3 for magpie and peacock, NOTES §5a)
  int grazing_anchors = 2;
};

// Engine cell for one crystal: lambda_um > 0 gives constant complex ε at that wavelength
// (exact single-λ model), lambda_um <= 0 the broadband Lorentz fits.
using CellFactory = std::function<fdtd::Cell(double lambda_um)>;

fdtd::Cell cell_from_crystal(const CrystalCell& cell, double lambda_um);

// Engine Bloch wavevector (k_x, k_y) in 1/µm of our (λ, θ, φ_local).
std::pair<double, double> engine_k(double lambda_nm, double theta_rad, double phi_local_rad);

// Jones matrix (s, p) of one engine frequency result (uses the result's own angles).
JonesReflection jones_from_engine(const fdtd::FreqResult& f);

// Fills `grid` (φ_local ≥ 0). Entries with cos θ cos φ < sim.kz_min are not simulated: they are
// continued to the grazing limit diag(−1, −1) in the surface-impedance form of grazing.hpp from
// anchors on their radial k_∥ line inside the simulated region; counts and other-order warnings
// go to meta.notes. ax_um: lateral period (for the grid step h = ax/nx).
// `stats` (optional) receives the run counts.
struct BuildStats {
  std::size_t runs = 0;          // engine runs done by this build
  std::size_t resumed_runs = 0;  // runs read back from the checkpoint instead
};
ReflectionTable build_table(const CellFactory& make_cell, double ax_um, const TableGrid& grid,
                            TableMetadata meta, const Options& options,
                            const TableBuilder::Progress& progress, BuildStats* stats = nullptr);

}  // namespace plumage::fdtd_table
