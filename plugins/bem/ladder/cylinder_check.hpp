// The cylinder cases of the accuracy ladder (bem_ladder.cpp) and of the solver tests: layered
// circular cylinders as polygons, their plane-wave solve, and the comparison of the far field with
// the exact series of reference/cylinder_series (which knows nothing of the solver).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <vector>

#include "bem_solver.hpp"
#include "cylinder_series.hpp"
#include "radiation.hpp"

namespace plumage::bem {

// Regular polygon with the circle's area (radius scaled by sqrt(2π/(N sin(2π/N)))), CCW.
inline Polygon circle_polygon(double r_nm, int n) {
  const double rr = r_nm * std::sqrt(2.0 * std::numbers::pi / (n * std::sin(2.0 * std::numbers::pi / n)));
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    p.push_back({rr * std::cos(t), rr * std::sin(t)});
  }
  return p;
}

// Vertices for a circle of radius r at spacing ≈ λ/(|n| ppw), and at least `min_vertices` so that
// small circles are resolved geometrically (64: ≤ 5.6° per segment).
inline int circle_vertices(double r_nm, double lambda_nm, std::complex<double> index, double ppw,
                           int min_vertices = 64) {
  return std::max(min_vertices, static_cast<int>(std::ceil(2.0 * std::numbers::pi * r_nm * std::abs(index) * ppw / lambda_nm)));
}

// Concentric layered cylinder: radii (inner → outer) and materials.
inline CrossSection layered_cylinder(const std::vector<double>& radii, const std::vector<Material>& mats,
                                     double lambda_nm, double ppw, int min_vertices = 64) {
  CrossSection cs;
  cs.label = "test cylinder";
  std::complex<double> nmax = 1.0;
  for (const auto& m : mats) {
    if (std::abs(m.index(lambda_nm)) > std::abs(nmax)) nmax = m.index(lambda_nm);
  }
  for (int k = static_cast<int>(radii.size()) - 1; k >= 0; --k) {
    Region reg;
    reg.outline = circle_polygon(radii[k], circle_vertices(radii[k], lambda_nm, nmax, ppw, min_vertices));
    reg.material = mats[k];
    reg.parent = static_cast<int>(cs.regions.size()) - 1;
    cs.regions.push_back(reg);
  }
  return cs;
}

struct PlaneWaveResult {
  std::unique_ptr<System> sys;
  Eigen::MatrixXcd x;      // columns: pol 0, pol 1
  Eigen::MatrixXcd field;  // 3·#dirs × 2
};

inline PlaneWaveResult solve_plane_wave(const CrossSection& cs, double lambda_nm, double theta, double phi_i,
                                        const std::vector<double>& phi_o, const BemOptions& opt) {
  PlaneWaveResult r;
  const auto prep = prepare_geometry(cs);
  r.sys = build_system(prep->geometry, lambda_nm, theta, opt);
  const int n = r.sys->mesh.unknowns();
  Eigen::MatrixXcd B(n, 2);
  for (int pol = 0; pol < 2; ++pol) fill_rhs(r.sys->mesh, r.sys->k0, plane_wave(theta, phi_i, pol), B.col(pol));
  r.x = r.sys->solve(B, opt);
  r.field = far_field_operator(r.sys->mesh, r.sys->k0, theta, phi_o) * r.x;
  return r;
}

inline std::vector<double> full_circle(int count) {
  std::vector<double> v;
  for (int k = 0; k < count; ++k) v.push_back(-std::numbers::pi + 2.0 * std::numbers::pi * k / count);
  return v;
}

// 𝓔 of the series in the project's polarisation convention (far_field.hpp pol 2 = −oracle pol 2)
// and units (the oracle works in µm: 𝓔 ∝ length^{1/2}, so × sqrt(1000) for nm).
inline std::array<std::complex<double>, 3> series_field(const oracle::CylinderSolution& s, int pol, double phi_i,
                                                        double phi_o) {
  const oracle::Vec3c v = oracle::far_field_vector(s, phi_i, phi_o);
  const double sg = (pol == 1 ? -1.0 : 1.0) * std::sqrt(1000.0);
  return {sg * v.x, sg * v.y, sg * v.z};
}

struct Compare {
  double intensity_l2 = 0;  // relative L2 of |𝓔|² over the directions
  double field_l2 = 0;      // relative L2 of the complex vector 𝓔
};

inline Compare compare_with_series(const Eigen::MatrixXcd& field, int pol, const oracle::CylinderSolution& s,
                                   double phi_i, const std::vector<double>& phi_o) {
  double num_i = 0, den_i = 0, num_f = 0, den_f = 0;
  for (std::size_t d = 0; d < phi_o.size(); ++d) {
    const auto ref = series_field(s, pol, phi_i, phi_o[d]);
    double ib = 0, ir = 0;
    for (int c = 0; c < 3; ++c) {
      const auto b = field(3 * d + c, pol);
      ib += std::norm(b);
      ir += std::norm(ref[c]);
      num_f += std::norm(b - ref[c]);
      den_f += std::norm(ref[c]);
    }
    num_i += (ib - ir) * (ib - ir);
    den_i += ir * ir;
  }
  return {std::sqrt(num_i / den_i), std::sqrt(num_f / den_f)};
}

}  // namespace plumage::bem
