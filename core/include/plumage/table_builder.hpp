// Extension point: builders of photonic-crystal reflection tables (issue 5). Implementation:
// "fdtd_periodic" (plugins/fdtd_periodic).
//
// A builder owns its settings for each crystal: the crystal file's section named after the
// builder's type (`fdtd_periodic: {...}`, CrystalCell::builder_sections), which the builder reads
// with its own parameter table in build() and validates in check_cell().
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/crystal_cell.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/plugin.hpp"
#include "plumage/reflection_table.hpp"

namespace plumage {

class PluginRegistry;

class TableBuilder : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "table_builder";

  // Called with (work done, total work, message); may be empty.
  using Progress = std::function<void(std::size_t done, std::size_t total, std::string_view what)>;

  virtual ReflectionTable build(const CrystalCell& cell, const TableGrid& grid,
                                Progress progress) const = 0;

  // Checks this builder's section of the cell (unknown keys, ranges) without building anything;
  // throws ConfigError naming file:line. Default: the builder reads no section.
  virtual void check_cell(const CrystalCell& cell) const {}

  // Peak memory of build(cell, grid), estimated without running anything (plumage/memory_budget.hpp):
  // what `plumage check` reports, and what build() refuses with MemoryBudgetError (exit status 2)
  // where it would not fit. Default: an empty estimate.
  virtual MemoryEstimate estimate_memory(const CrystalCell& cell, const TableGrid& grid) const {
    (void)cell, (void)grid;
    return {};
  }
};

// For `plumage check`: every builder section of the cell must name a registered table_builder
// (else a ConfigError at the section, with the nearest registered name), and that builder must
// accept it (check_cell). Returns the section names checked.
std::vector<std::string> check_builder_sections(const CrystalCell& cell, const PluginRegistry& registry);

}  // namespace plumage
