// Shared helpers of the BEM solver tests: the ladder's cylinder cases (ladder/cylinder_check.hpp:
// cylinder cross sections, plane-wave solves, comparison with the exact series of
// reference/cylinder_series) under their test names, and a junction body.
#pragma once

#include "ladder/cylinder_check.hpp"

namespace plumage::bem::testing {

using bem::circle_polygon;
using bem::circle_vertices;
using bem::compare_with_series;
using bem::Compare;
using bem::full_circle;
using bem::layered_cylinder;
using bem::PlaneWaveResult;
using bem::series_field;
using bem::solve_plane_wave;

// A lossless body with junctions: a square split into two touching halves of different index,
// plus a third region touching both (three-region points), in air. Used by the solver,
// hierarchical-matrix and probe programs.
inline CrossSection junction_body() {
  CrossSection cs;
  cs.label = "junction body";
  auto rect = [](double x0, double z0, double x1, double z1, int nx, int nz) {
    Polygon p;
    for (int k = 0; k < nx; ++k) p.push_back({x0 + (x1 - x0) * k / nx, z0});
    for (int k = 0; k < nz; ++k) p.push_back({x1, z0 + (z1 - z0) * k / nz});
    for (int k = 0; k < nx; ++k) p.push_back({x1 - (x1 - x0) * k / nx, z1});
    for (int k = 0; k < nz; ++k) p.push_back({x0, z1 - (z1 - z0) * k / nz});
    return p;
  };
  cs.regions.push_back({rect(-200, -150, 0, 150, 8, 12), Material::constant(1.55), RegionRole::body});
  cs.regions.push_back({rect(0, -150, 160, 150, 8, 12), Material::constant({1.9, 0.0}), RegionRole::body});
  cs.regions.push_back({rect(-80, 150, 60, 230, 7, 4), Material::constant(1.3), RegionRole::film});
  return cs;
}

}  // namespace plumage::bem::testing
