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

// The solver settings and slices per rod diameter of a fidelity (explicit values win).
struct BuildSettings {
  SolverSettings solver;
  int slices_per_row = 0;
  bool richardson = false;
};
BuildSettings build_settings(const BuilderParams& p);

class RcwaTableBuilder final : public TableBuilder {
 public:
  explicit RcwaTableBuilder(BuilderParams params) : params_(params) {}
  ReflectionTable build(const CrystalCell& cell, const TableGrid& grid, Progress progress) const override;
  MemoryEstimate estimate_memory(const CrystalCell& cell, const TableGrid& grid) const override;

 private:
  BuilderParams params_;
};

}  // namespace plumage::rcwa
