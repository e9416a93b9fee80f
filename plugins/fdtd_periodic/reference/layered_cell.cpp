#include "layered_cell.hpp"

namespace plumage::fdtd_reference {

fdtd::Cell layered_cell(double h_um, int nx, double lambda_um) {
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

}  // namespace plumage::fdtd_reference
