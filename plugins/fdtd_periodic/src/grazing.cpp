#include "grazing.hpp"

#include <array>
#include <cmath>

#include "plumage/error.hpp"
#include "plumage/reflection_table.hpp"

namespace plumage::fdtd_table {

namespace {

using M2 = std::array<Complex, 4>;  // row-major [ss sp; ps pp]

M2 mat(const JonesReflection& J) { return {J.ss, J.sp, J.ps, J.pp}; }
M2 mul(const M2& a, const M2& b) {
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2],
          a[2] * b[1] + a[3] * b[3]};
}
M2 inv(const M2& a) {
  const Complex d = a[0] * a[3] - a[1] * a[2];
  if (std::abs(d) < 1e-14) throw Error("fdtd_periodic: singular matrix in the grazing continuation");
  return {a[3] / d, -a[1] / d, -a[2] / d, a[0] / d};
}
M2 add_identity(const M2& a, double s) { return {a[0] + s, a[1], a[2], a[3] + s}; }  // a + s I
M2 scale(const M2& a, Complex s) { return {a[0] * s, a[1] * s, a[2] * s, a[3] * s}; }

}  // namespace

std::vector<double> anchor_kappas(double kz_min, int count) {
  std::vector<double> k;
  for (int m = 0; m < count; ++m) k.push_back(kz_min + 0.01 + 0.05 * m);
  return k;
}

std::pair<double, double> radial_point(double theta, double phi, double kappa) {
  const double ux0 = std::cos(theta) * std::sin(phi), uy0 = std::sin(theta);
  const double rho0 = std::hypot(ux0, uy0);
  const double rho = std::sqrt(std::max(0.0, 1.0 - kappa * kappa));
  if (rho0 < 1e-12) return {0.0, std::acos(std::min(1.0, kappa))};  // normal incidence: any line
  const double ux = rho * ux0 / rho0, uy = rho * uy0 / rho0;
  return {std::asin(std::min(1.0, uy)), std::atan2(ux, kappa)};
}

JonesReflection impedance_of(const JonesReflection& J, double kappa) {
  const M2 j = mat(J);
  const M2 Z = scale(mul(add_identity(j, 1.0), inv(add_identity(scale(j, -1.0), 1.0))), 1.0 / kappa);
  return {Z[0], Z[1], Z[2], Z[3]};
}

JonesReflection jones_of(const JonesReflection& Z, double kappa) {
  if (kappa <= 0.0) return grazing_jones();
  const M2 kZ = scale(mat(Z), kappa);
  const M2 J = mul(add_identity(kZ, -1.0), inv(add_identity(kZ, 1.0)));
  return {J[0], J[1], J[2], J[3]};
}

JonesReflection continue_to_grazing(std::span<const GrazingAnchor> anchors, double kappa) {
  if (anchors.empty()) throw Error("fdtd_periodic: grazing continuation without anchors");
  if (kappa <= 0.0) return grazing_jones();
  // Z_m = (I + J)(I − J)⁻¹ / κ_m at every anchor.
  std::vector<M2> Z;
  for (const auto& a : anchors) {
    const M2 J = mat(a.J);
    Z.push_back(scale(mul(add_identity(J, 1.0), inv(add_identity(scale(J, -1.0), 1.0))), 1.0 / a.kappa));
  }
  // Lagrange interpolation of Z in x = κ² through the anchors, evaluated at x = kappa².
  const double x = kappa * kappa;
  M2 Ze{};
  for (std::size_t m = 0; m < anchors.size(); ++m) {
    double w = 1.0;
    const double xm = anchors[m].kappa * anchors[m].kappa;
    for (std::size_t n = 0; n < anchors.size(); ++n)
      if (n != m) w *= (x - anchors[n].kappa * anchors[n].kappa) / (xm - anchors[n].kappa * anchors[n].kappa);
    for (int c = 0; c < 4; ++c) Ze[c] += w * Z[m][c];
  }
  const M2 kZ = scale(Ze, kappa);
  const M2 J = mul(add_identity(kZ, -1.0), inv(add_identity(kZ, 1.0)));
  return {J[0], J[1], J[2], J[3]};
}

}  // namespace plumage::fdtd_table
