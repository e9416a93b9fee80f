// Parameters of the fdtd_periodic table builder, each declared once (plumage/param_table.hpp):
// the builder's own (PluginInfo::params, `plumage table build` options) and a crystal file's
// `fdtd_periodic:` section (this builder's numerics for that cell, NOTES.md §3a, §5a).
#pragma once

#include <optional>
#include <string>

#include "plumage/crystal_cell.hpp"
#include "plumage/param_table.hpp"
#include "table_build.hpp"

namespace plumage::fdtd_table {

// The plug-in's version, also written into every table's producer text.
inline constexpr const char* kPluginVersion = "1.0.0";

struct BuilderParams {
  enum class Fidelity { preview, production };
  Fidelity fidelity = Fidelity::production;
  std::optional<double> resolution_nm;  // unset: preview 15 nm; production: the crystal's or 10 nm
  std::optional<double> k_step_per_um;  // unset: preview 1/um, production 0.5/um
  int threads = 2;
  int pml_cells = 24;
  double kz_min = 0.25;
  double dft_tol = 3e-4;
  double courant = 0.95;
  bool smoothing = true;
  std::optional<bool> dispersion_correction;  // unset: the crystal's
  std::optional<bool> exact_fill;             // unset: the crystal's
  std::optional<int> grazing_anchors;         // unset: the crystal's
  double substrate_below_um = 0.30;
  double air_above_um = 0.30;
  std::string checkpoint;
};
const ParamTable<BuilderParams>& builder_params();

// A crystal file's `fdtd_periodic:` section. Defaults: the plain scheme of the cached production
// tables (opt in per crystal).
struct CrystalNumerics {
  bool dispersion_correction = false;
  bool exact_fill = false;
  std::optional<double> resolution_nm;  // production grid step of this crystal; unset: 10 nm
  std::optional<double> k_step_per_um;  // production Bloch-k step of this crystal; unset: 0.5 /µm
  int grazing_anchors = 2;
};
const ParamTable<CrystalNumerics>& crystal_numerics_params();

// The cell's `fdtd_periodic:` section read and finished (unknown keys and out-of-range values are
// ConfigErrors naming file:line), or the defaults when the cell has none.
CrystalNumerics crystal_numerics(const CrystalCell& cell);

// What one build of `cell` runs: the table driver's options (grid step from the requested
// resolution, the crystal's numerics unless overridden) and the table's metadata.
struct BuildPlan {
  Options options;
  TableMetadata meta;
};
BuildPlan plan_build(const BuilderParams& params, const CrystalCell& cell);

}  // namespace plumage::fdtd_table
