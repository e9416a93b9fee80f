// Crystal cell → engine cell, our frame ↔ the engine's, and the engine's reflected fields → the
// (s, p) Jones matrix (frame mapping in table_build.hpp).
#include <algorithm>
#include <cmath>

#include "plumage/error.hpp"
#include "table_build.hpp"

namespace plumage::fdtd_table {

namespace {

using fdtd::cplx;
using fdtd::Vec3c;

fdtd::MaterialModel model_of(const Material& m, double lambda_um) {
  if (lambda_um > 0.0) {
    if (m.kind() == Material::Kind::air) return fdtd::air_model();
    const Complex n = m.index(lambda_um * 1000.0);
    return fdtd::constant_model(m.name(), n * n, lambda_um);
  }
  switch (m.kind()) {
    case Material::Kind::air:
      return fdtd::air_model();
    case Material::Kind::keratin:
      return fdtd::keratin_fit().model;
    case Material::Kind::melanin:
      return fdtd::melanin_fit().model;
    case Material::Kind::constant: {
      const Complex n = m.index(550.0);
      if (n.imag() != 0.0)
        throw Error("fdtd_periodic: an absorbing constant material (" + m.name() +
                    ") needs the per-entry mode (k_step_per_um: 0)");
      fdtd::MaterialModel mm;
      mm.name = m.name();
      mm.eps_inf = (n * n).real();
      return mm;
    }
    case Material::Kind::mixture:
      break;
  }
  throw Error("fdtd_periodic: material " + m.name() + " has no broadband model; use k_step_per_um: 0");
}

Complex dot(const Vec3c& a, const double s[3]) { return a[0] * s[0] + a[1] * s[1] + a[2] * s[2]; }

}  // namespace

fdtd::Cell cell_from_crystal(const CrystalCell& c, double lambda_um) {
  fdtd::Cell cell;
  cell.ax = c.a_x_nm * 1e-3;
  cell.materials = {fdtd::air_model(), model_of(c.host, lambda_um), model_of(c.rod, lambda_um),
                    model_of(c.core, lambda_um), model_of(c.channel, lambda_um)};
  cell.ambient = 0;
  cell.substrate = 1;
  double deepest = 0.0;
  for (int j = 0; j < c.rows; ++j) {
    const double zj = c.rod_depth_nm(j) * 1e-3;
    const double xj = c.shifted(j) ? 0.5 * cell.ax : 0.0;
    cell.circles.push_back({xj, zj, 0.5e-3 * c.rod_diameter_nm, 2});
    if (c.core_diameter_nm > 0) cell.circles.push_back({xj, zj, 0.5e-3 * c.core_diameter_nm, 3});
    deepest = std::max(deepest, zj + 0.5e-3 * c.rod_diameter_nm);
    if (c.channel_diameter_nm > 0) {
      const double zc = zj + 0.5e-3 * c.a_z_nm;
      cell.circles.push_back({0.5 * cell.ax, zc, 0.5e-3 * c.channel_diameter_nm, 4});
      deepest = std::max(deepest, zc + 0.5e-3 * c.channel_diameter_nm);
    }
  }
  cell.structure_depth = deepest;
  return cell;
}

std::pair<double, double> engine_k(double lambda_nm, double theta, double phi) {
  const double k0 = 2.0 * fdtd::kPi / (lambda_nm * 1e-3);
  return {-k0 * std::cos(theta) * std::sin(phi), k0 * std::sin(theta)};
}

JonesReflection jones_from_engine(const fdtd::FreqResult& f) {
  const double st = f.sin_theta, ct = f.cos_theta, sp = f.sin_phi, cp = f.cos_phi;
  const double w[3] = {ct * sp, st, -ct * cp};  // ω_i, engine frame
  // ŝ = ω_i × n̂ with n̂ = (0, 0, −1): (−w_y, w_x, 0)
  double s[3] = {-w[1], w[0], 0.0};
  const double len = std::hypot(s[0], s[1]);
  if (len < 1e-4) {
    s[0] = 0.0, s[1] = -1.0;  // R ŷ
  } else {
    s[0] /= len, s[1] /= len;
  }
  Vec3c eb[2], hb[2];
  fdtd::incident_basis(st, ct, sp, cp, eb, hb);
  Complex B[2][2], C[2][2];
  for (int q = 0; q < 2; ++q) {
    B[0][q] = dot(eb[q], s);
    B[1][q] = dot(hb[q], s);
    C[0][q] = dot(f.E[q], s);
    C[1][q] = dot(f.H[q], s);
  }
  const Complex det = B[0][0] * B[1][1] - B[0][1] * B[1][0];
  const Complex Bi[2][2] = {{B[1][1] / det, -B[0][1] / det}, {-B[1][0] / det, B[0][0] / det}};
  Complex J[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) J[a][b] = C[a][0] * Bi[0][b] + C[a][1] * Bi[1][b];
  return {J[0][0], J[0][1], J[1][0], J[1][1]};
}

}  // namespace plumage::fdtd_table
