// The ideal photonic-crystal unit cell behind barbule types 5–7 (spec photonic-crystals.md),
// read from configs/crystals/<species>-<variant>.yaml:
//
//   crystal:
//     name: mallard-green
//     lattice: hexagonal          # hexagonal | rectangular
//     a_x_nm: 190                 # period along the surface
//     a_z_nm: 164.5               # row spacing in depth
//     rod_diameter_nm: 152        # melanin rods (outer diameter)
//     core_diameter_nm: 0         # air core of hollow rods (0: solid)
//     channel_diameter_nm: 0      # air channel at each cell centre below a row (rectangular)
//     rows: 6
//     cortex_nm: 123.5            # keratin from the surface to the top of the first row
//     materials: {host: keratin, rod: melanin, core: air, channel: air}   # optional
//     expected_peak_nm: 545       # optional, informational
//     fdtd_periodic: {grazing_anchors: 3}   # optional: settings of one table builder
//
// Depth z > 0 into the barbule; row j has rod centres at depth cortex + D/2 + j·a_z. Hexagonal:
// odd rows shifted by a_x/2. Rectangular: channels at (a_x/2, z_j + a_z/2).
//
// A map under a key that is not a cell field is the section of the table builder of that name
// (`fdtd_periodic:`): core keeps it unread in CrystalCell::builder_sections, the builder reads and
// checks it with its own parameter table (TableBuilder::check_cell, check_builder_sections in
// table_builder.hpp). A key one typo away from a cell field is an error, not a section.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "plumage/materials.hpp"
#include "plumage/params.hpp"

namespace plumage {

struct CrystalCell {
  std::string name;
  enum class Lattice { hexagonal, rectangular } lattice = Lattice::hexagonal;
  double a_x_nm = 0;
  double a_z_nm = 0;
  double rod_diameter_nm = 0;
  double core_diameter_nm = 0;
  double channel_diameter_nm = 0;
  int rows = 0;
  double cortex_nm = 0;
  Material host = Material::keratin();
  Material rod = Material::melanin();
  Material core = Material::air();
  Material channel = Material::air();
  double expected_peak_nm = 0;  // 0 when not given
  // Table-builder sections by builder type (e.g. "fdtd_periodic"), unread by core: each builder
  // reads its own with its parameter table and finish()es it (unknown keys name file:line).
  std::map<std::string, ParamView> builder_sections;

  double rod_depth_nm(int row) const { return cortex_nm + 0.5 * rod_diameter_nm + row * a_z_nm; }
  double depth_nm() const { return rod_depth_nm(rows - 1) + 0.5 * rod_diameter_nm; }
  bool shifted(int row) const { return lattice == Lattice::hexagonal && row % 2 == 1; }
};

// Parses the `crystal:` map (node = that map). Validates every value and checks that rods do not
// overlap their neighbours, cores fit in rods and channels fit between rods. Its parameters are
// declared once (crystal_cell.cpp: a ParamTable, listed in docs/parameters.md).
CrystalCell parse_crystal_cell(const ParamView& node);
// Loads a crystal file (top-level key `crystal:`), rejecting unknown keys.
CrystalCell load_crystal_cell(const std::filesystem::path& file);

}  // namespace plumage
