#include "incident.hpp"

#include <cmath>
#include <numbers>

#include "assembly.hpp"
#include "quadrature.hpp"

namespace plumage::bem {

void IncidentField::fields(double k0, Vec2 rho, CVec3& e, CVec3& h) const {
  e = {0.0, 0.0, 0.0};
  h = {0.0, 0.0, 0.0};
  const double ct = std::cos(theta);
  const Vec2 r = rho - focus;
  for (std::size_t q = 0; q < alpha.size(); ++q) {
    const PlaneWavePolarization p = incident_polarization(pol, {theta, alpha[q]});
    // k_i = −k0 ω_i; in-plane phase −k0 cos θ (sin α x + cos α z); e^{iβy} is common.
    const double phase = -k0 * ct * (std::sin(alpha[q]) * r.x + std::cos(alpha[q]) * r.z);
    const std::complex<double> f = amp[q] * std::polar(1.0, phase);
    for (int c = 0; c < 3; ++c) {
      e[c] += f * p.e[c];
      h[c] += f * p.eta0_h[c];
    }
  }
}

IncidentField plane_wave(double theta, double phi, int pol) {
  IncidentField f;
  f.theta = theta;
  f.pol = pol;
  f.alpha = {phi};
  f.amp = {1.0};
  return f;
}

IncidentField gaussian_beam(double k0, double theta, double phi, int pol, double s_b, Vec2 focus,
                            double extent) {
  IncidentField f;
  f.theta = theta;
  f.pol = pol;
  f.focus = focus;
  const double g0 = k0 * std::cos(theta);
  const double width = 2.0 / (g0 * s_b);            // 1/e half width of A in sin(α − φ)
  const double half = std::min(6.0 * width, 0.5 * std::numbers::pi);  // A < e^{−36} beyond
  const double dalpha = std::min(width / 2.0, 2.0 * std::numbers::pi / (g0 * 4.0 * extent));
  const int n = static_cast<int>(std::ceil(half / dalpha));
  const double step = half / n;
  const double a0 = g0 * s_b / (2.0 * std::sqrt(std::numbers::pi));
  for (int q = -n; q <= n; ++q) {
    const double d = q * step;
    const double s = std::sin(d);
    f.alpha.push_back(phi + d);
    f.amp.push_back(step * a0 * std::exp(-g0 * g0 * s_b * s_b * s * s / 4.0));
  }
  return f;
}

void fill_rhs(const Mesh& mesh, double k0, const IncidentField& inc, Eigen::Ref<Eigen::VectorXcd> b) {
  b.setZero();
  const Rule& g = gauss_legendre(6);
  for (const Segment& S : mesh.segments) {
    if (S.a != 0) continue;  // σ_{0,i} = +1 on every air interface (a = 0 is the air side)
    int idx[8];
    for (int l = 0; l < 8; ++l) idx[l] = global_index(mesh, S, l);
    for (std::size_t q = 0; q < g.x.size(); ++q) {
      const Vec2 p = S.p0 + (g.x[q] * S.h) * S.t;
      CVec3 e, h;
      inc.fields(k0, p, e, h);
      const double N[2] = {1.0 - g.x[q], g.x[q]};
      const double w = g.w[q] * S.h;
      const std::complex<double> et = e[0] * S.t.x + e[2] * S.t.z, ht = h[0] * S.t.x + h[2] * S.t.z;
      for (int i = 0; i < 2; ++i) {
        b[idx[0 + i]] -= (w * N[i]) * et;
        b[idx[2 + i]] -= (w * N[i]) * e[1];
        b[idx[4 + i]] -= (w * N[i]) * ht;
        b[idx[6 + i]] -= (w * N[i]) * h[1];
      }
    }
  }
}

}  // namespace plumage::bem
