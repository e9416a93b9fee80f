// Extension point: builders of photonic-crystal reflection tables (issue 5). Implementation:
// "fdtd_periodic" (plugins/fdtd_periodic).
#pragma once

#include <functional>
#include <string_view>

#include "plumage/crystal_cell.hpp"
#include "plumage/plugin.hpp"
#include "plumage/reflection_table.hpp"

namespace plumage {

class TableBuilder : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "table_builder";

  // Called with (work done, total work, message); may be empty.
  using Progress = std::function<void(std::size_t done, std::size_t total, std::string_view what)>;

  virtual ReflectionTable build(const CrystalCell& cell, const TableGrid& grid,
                                Progress progress) const = 0;
};

}  // namespace plumage
