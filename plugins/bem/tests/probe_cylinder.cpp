#include "bem_test_support.hpp"
#include <cstdio>
#include <cstdlib>
using namespace plumage;
using namespace plumage::bem;
using namespace plumage::bem::testing;
int main(int argc, char** argv) {
  double r = argc > 1 ? atof(argv[1]) : 250, lam = argc > 2 ? atof(argv[2]) : 550, th = argc > 3 ? atof(argv[3]) : 0,
         ppw = argc > 4 ? atof(argv[4]) : 20;
  int mat = argc > 5 ? atoi(argv[5]) : 0;
  Material m = mat == 0 ? Material::keratin() : Material::melanin();
  const bool coated = mat == 2;
  auto cs = coated ? layered_cylinder({r, r + 100}, {Material::keratin(), Material::melanin()}, lam, ppw)
                   : layered_cylinder({r}, {m}, lam, ppw);
  BemOptions opt;
  opt.points_per_wavelength = ppw;
  auto phi_o = full_circle(360);
  double phi_i = 0.3, theta = th * std::numbers::pi / 180;
  auto res = solve_plane_wave(cs, lam, theta, phi_i, phi_o, opt);
  printf("unknowns %d assembly %.2fs factor %.2fs\n", res.sys->mesh.unknowns(), res.sys->assembly_seconds, res.sys->factor_seconds);
  for (int pol = 0; pol < 2; ++pol) {
    auto s = coated ? oracle::solve_layered({r / 1000, (r + 100) / 1000},
                                            {Material::keratin().index(lam), Material::melanin().index(lam)},
                                            lam / 1000, theta, pol + 1)
                    : oracle::solve_homogeneous_bh(r / 1000, m.index(lam), lam / 1000, theta, pol + 1);
    auto c = compare_with_series(res.field, pol, s, phi_i, phi_o);
    auto ref = series_field(s, pol, phi_i, phi_o[100]);
    printf("pol %d: intensity L2 %.3e field L2 %.3e   sample bem (%g,%g) ser (%g,%g)\n", pol + 1, c.intensity_l2, c.field_l2,
           res.field(300, pol).real(), res.field(300, pol).imag(), ref[0].real(), ref[0].imag());
  }
}
