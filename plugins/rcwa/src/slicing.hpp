// Staircase of a crystal cell into z-slices, each lamellar in x (Fourier modal method, issue 27).
//
// Frame: the FDTD engine's (plugins/fdtd_periodic/src/table_build.hpp): crystal at z > 0 (z is
// the depth), air above z < 0, semi-infinite host below the structure. A slice's profile is the
// host plus boxes of other materials; boxes are nested (core inside rod), so ε(x) and 1/ε(x) are
// superpositions host + Σ (mat − under)·box, whose Fourier coefficients are closed form.
#pragma once

#include <vector>

#include "plumage/crystal_cell.hpp"
#include "plumage/materials.hpp"

namespace plumage::rcwa {

struct Box {
  double x_center_nm = 0;
  double width_nm = 0;
  int material = 0;  // index into SlicedCell::materials
  int under = 0;     // the material it replaces
};

struct Slice {
  double thickness_nm = 0;
  std::vector<Box> boxes;
  int type = 0;  // slices of equal geometry (boxes and thickness) share a type: solved once per entry
};

struct SlicedCell {
  double period_nm = 0;
  std::vector<Material> materials;  // [0] air (above), [1] host (between boxes and below)
  std::vector<Slice> slices;        // from the surface downward
  int n_types = 0;
  // Per type: the type whose geometry is this one shifted by half a period (hexagonal odd rows), or
  // −1. Its orders' amplitudes differ by (−1)^m only, so its S-matrix is D S D, D = diag((−1)^m).
  std::vector<int> half_shift_type;
};

// Slices of `cell`: boundaries at every circle's top and bottom; an interval crossed by circles
// gets ceil(slices_per_row · length / rod diameter) slices, each box the circle's mean chord over
// its slice (volume-preserving staircase).
SlicedCell slice_crystal(const CrystalCell& cell, int slices_per_row);

// Assigns Slice::type by comparing geometries (after building slices by hand).
void assign_slice_types(SlicedCell& cell);

}  // namespace plumage::rcwa
