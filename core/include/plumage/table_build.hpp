// `plumage table build` as a library call (issue 22): a crystal config → a reflection table file
// with a registered table_builder, resumable, with the run's warnings in the table's notes.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "plumage/plugin_registry.hpp"
#include "plumage/table_builder.hpp"

namespace plumage {

// The table grids of the two fidelities, declared once: production 201 λ (1.5 nm) × 20 cos θ × 50
// cos φ_local (also the photonic_crystal model's default), preview 16 × 10 × 10. The paper's 50 λ
// (6.1 nm) left up to 0.021 in |r|² to the linear λ interpolation of ReflectionTable::query on the
// magpie cells; 201 keep it ≤ 0.0013 on all 14 cells away from the host's Rayleigh anomalies
// (issue 27 part 4, plugins/rcwa/NOTES.md §6). The FDTD's cost does not depend on it (broadband
// runs); the rcwa's grows with it.
struct TableGridSize {
  int n_lambda = 0, n_theta = 0, n_phi = 0;
};
inline constexpr TableGridSize kProductionTableGrid{201, 20, 50};
inline constexpr TableGridSize kPreviewTableGrid{16, 10, 10};

struct TableBuildRequest {
  std::filesystem::path crystal_config;  // configs/crystals/*.yaml
  std::string fidelity = "production";   // production | preview: the grid and the builder's own fidelity
  std::string builder = "fdtd_periodic";  // a registered table_builder
  double lambda_min_nm = 400, lambda_max_nm = 700;
  TableGridSize grid{};                     // a count of 0: the fidelity's
  std::optional<double> resolution_nm;      // unset: the builder's default for the fidelity
  std::optional<double> k_step_per_um;      // unset: the builder's default
  std::filesystem::path out;                // the .plt to write
  // A builder that declares a `checkpoint` parameter keeps finished runs in <out>.partial, and a
  // rerun of the same build continues from it; restart discards it first.
  bool restart = false;
};

struct TableBuildResult {
  std::string crystal;  // the cell's name
  TableGridSize grid;   // as built
  double resolution_nm = 0;
  std::string notes;    // the table's notes, warnings included
};

// Builds the table and writes request.out (ReflectionTable::save, atomic). The builder gets the
// request's values unchanged, so it validates them (ConfigError naming the field).
TableBuildResult build_table_file(const TableBuildRequest& request, const PluginRegistry& registry,
                                  const TableBuilder::Progress& progress);

}  // namespace plumage
