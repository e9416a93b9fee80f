// The table_builder "rcwa" (issue 27): a crystal cell → its reflection table by the Fourier modal
// method (solver.hpp), entry by entry on the table grid, with this builder's ParamTable.
#pragma once

#include "plumage/param_table.hpp"
#include "plumage/table_builder.hpp"
#include "solver.hpp"

namespace plumage::rcwa {

inline constexpr const char* kPluginVersion = "1.0.0";

struct BuilderParams {
  enum class Fidelity { preview, production };
  Fidelity fidelity = Fidelity::production;
  int harmonics = 0;       // 0: by fidelity
  int slices_per_row = 0;  // 0: by fidelity
  bool li_rule = true;
  bool richardson = false;  // extrapolate in slices from slices_per_row/2 and slices_per_row
  int threads = 2;
};
const ParamTable<BuilderParams>& builder_params();

// A crystal's own production settings: its config's `rcwa:` section (CrystalCell::builder_sections),
// for cells that converge slower than the preset (magpie's hollow rods, NOTES.md §3).
struct CellSettings {
  int harmonics = 0;       // 0: the preset's
  int slices_per_row = 0;  // 0: the preset's
  bool richardson = false;
};
const ParamTable<CellSettings>& cell_params();
CellSettings cell_settings(const CrystalCell& cell);  // reads and checks the section (ConfigError)

// The solver settings and slices per rod diameter of a fidelity: explicit builder options win,
// then (production only) the cell's section, then the preset.
struct BuildSettings {
  SolverSettings solver;
  int slices_per_row = 0;
  bool richardson = false;
};
BuildSettings build_settings(const BuilderParams& p, const CellSettings& cell = {});

class RcwaTableBuilder final : public TableBuilder {
 public:
  explicit RcwaTableBuilder(BuilderParams params) : params_(params) {}
  ReflectionTable build(const CrystalCell& cell, const TableGrid& grid, Progress progress) const override;
  void check_cell(const CrystalCell& cell) const override { cell_settings(cell); }
  MemoryEstimate estimate_memory(const CrystalCell& cell, const TableGrid& grid) const override;

 private:
  BuilderParams params_;
};

}  // namespace plumage::rcwa
