// The layered reference cell of the FDTD accuracy ladder and tests: air | keratin 300 nm |
// melanin 200 nm | keratin, `nx` grid cells of h wide (x-invariant, so the closed-form Airy
// recursion of airy.hpp is its exact answer). nx = 2 makes the Bloch harmonics reach the
// x Nyquist wavenumber (k_x h = π), i.e. the grid attains the full 2D Courant bound; a 1-cell grid
// has no x Nyquist mode. lambda_um > 0: constant ε at that wavelength; else the broadband fits.
#pragma once

#include "fdtd_periodic.hpp"

namespace plumage::fdtd_reference {

fdtd::Cell layered_cell(double h_um, int nx, double lambda_um);

}  // namespace plumage::fdtd_reference
