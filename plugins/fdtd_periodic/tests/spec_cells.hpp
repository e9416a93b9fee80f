// The crystals of configs/crystals as engine cells, for the engine tests: the crystal files are
// the one source of the cells (the engine no longer ships a copy of them).
#pragma once

#include <filesystem>
#include <string>

#include "plumage/crystal_cell.hpp"
#include "table_build.hpp"

namespace plumage::fdtd_testing {

// configs/crystals/<name>.yaml with the broadband material fits (materials 0 air, 1 host,
// 2 rod, 3 core, 4 channel: cell_from_crystal).
inline fdtd::Cell spec_cell(const std::string& name) {
  const CrystalCell cc =
      load_crystal_cell(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs/crystals" / (name + ".yaml"));
  return fdtd_table::cell_from_crystal(cc, -1.0);
}

}  // namespace plumage::fdtd_testing
