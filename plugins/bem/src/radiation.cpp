#include "radiation.hpp"

#include <cmath>
#include <numbers>

#include "assembly.hpp"
#include "quadrature.hpp"

namespace plumage::bem {

Eigen::MatrixXcd far_field_operator(const Mesh& mesh, double k0, double theta, std::span<const double> phi_o) {
  const int nd = static_cast<int>(phi_o.size());
  Eigen::MatrixXcd F = Eigen::MatrixXcd::Zero(3 * nd, mesh.unknowns());
  const double ct = std::cos(theta), st = std::sin(theta);
  const double g0 = k0 * ct;
  const cplx pref = std::sqrt(2.0 / (std::numbers::pi * g0)) * std::polar(1.0, -std::numbers::pi / 4);
  const Rule& g = gauss_legendre(6);
  for (int d = 0; d < nd; ++d) {
    const double sp = std::sin(phi_o[d]), cp = std::cos(phi_o[d]);
    const double o[3] = {ct * sp, -st, ct * cp};
    for (const Segment& S : mesh.segments) {
      if (S.a != 0) continue;
      cplx s[2] = {0.0, 0.0};
      for (std::size_t q = 0; q < g.x.size(); ++q) {
        const Vec2 p = S.p0 + (g.x[q] * S.h) * S.t;
        const cplx gq = g.w[q] * S.h * std::polar(1.0, -g0 * (sp * p.x + cp * p.z));
        s[0] += (1.0 - g.x[q]) * gq;
        s[1] += g.x[q] * gq;
      }
      const double t[3] = {S.t.x, 0.0, S.t.z}, y[3] = {0.0, 1.0, 0.0};
      // (I − ôô)·v and ô × v for v = t̂, ŷ
      auto proj = [&](const double* v, double* r) {
        const double ov = o[0] * v[0] + o[1] * v[1] + o[2] * v[2];
        for (int c = 0; c < 3; ++c) r[c] = v[c] - ov * o[c];
      };
      auto crs = [&](const double* v, double* r) {
        r[0] = o[1] * v[2] - o[2] * v[1];
        r[1] = o[2] * v[0] - o[0] * v[2];
        r[2] = o[0] * v[1] - o[1] * v[0];
      };
      double pt[3], py[3], xt[3], xy[3];
      proj(t, pt), proj(y, py), crs(t, xt), crs(y, xy);
      for (int j = 0; j < 2; ++j) {
        const cplx a = pref * (k0 / 4.0) * s[j];
        const int vj = j ? S.v1 : S.v0;
        for (int c = 0; c < 3; ++c) {
          F(3 * d + c, mesh.jt(vj)) += -a * pt[c];
          F(3 * d + c, mesh.jz(S.zdof[j])) += -a * py[c];
          F(3 * d + c, mesh.mt(vj)) += a * xt[c];
          F(3 * d + c, mesh.mz(S.zdof[j])) += a * xy[c];
        }
      }
    }
  }
  return F;
}

}  // namespace plumage::bem
