// The layered reference cell of the FDTD tests and accuracy ladder: air | keratin 300 nm |
// melanin 200 nm | keratin, `nx` grid cells of h wide (x-invariant, so the closed-form Airy
// recursion of tmm_reference.hpp is its exact answer). nx = 2 makes the Bloch harmonics reach the
// x Nyquist wavenumber (k_x h = π), i.e. the grid attains the full 2D Courant bound; a 1-cell grid
// has no x Nyquist mode. lambda_um > 0: constant ε at that wavelength; else the broadband fits.
#pragma once

#include "fdtd_periodic.hpp"

namespace plumage::fdtd_testing {

inline fdtd::Cell layered_cell(double h_um, int nx, double lambda_um) {
  fdtd::Cell c;
  c.ax = h_um * nx;
  if (lambda_um > 0) {
    const auto nk = fdtd::keratin_index(lambda_um), nm = fdtd::melanin_index(lambda_um);
    c.materials = {fdtd::air_model(), fdtd::constant_model("keratin", nk * nk, lambda_um),
                   fdtd::constant_model("melanin", nm * nm, lambda_um)};
  } else {
    c.materials = {fdtd::air_model(), fdtd::keratin_fit().model, fdtd::melanin_fit().model};
  }
  c.ambient = 0;
  c.substrate = 1;
  c.slabs = {{0.3, 0.5, 2}};
  c.structure_depth = 0.5;
  return c;
}

}  // namespace plumage::fdtd_testing
