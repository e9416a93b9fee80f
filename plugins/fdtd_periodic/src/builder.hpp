// The table_builder "fdtd_periodic": a crystal cell → its reflection table through the table
// driver (table_build.hpp), with this builder's parameters (builder_params.hpp).
#pragma once

#include <memory>

#include "builder_params.hpp"
#include "plumage/table_builder.hpp"

namespace plumage::fdtd_table {

class FdtdTableBuilder final : public TableBuilder {
 public:
  explicit FdtdTableBuilder(BuilderParams params) : params_(std::move(params)) {}

  // Refuses (MemoryBudgetError, exit status 2) a cell whose grid would not fit, before any run.
  ReflectionTable build(const CrystalCell& cell, const TableGrid& grid, Progress progress) const override;
  MemoryEstimate estimate_memory(const CrystalCell& cell, const TableGrid& grid) const override;
  // The cell's `fdtd_periodic:` section (crystal_numerics).
  void check_cell(const CrystalCell& cell) const override { crystal_numerics(cell); }

 private:
  BuilderParams params_;
};

}  // namespace plumage::fdtd_table
