#include "airy.hpp"

#include <cmath>

namespace plumage::fdtd_reference {

namespace {

cplx q_of(cplx eps, double k0, double kpar) {  // n cosθ = kz / k0, Im >= 0
  cplx q = std::sqrt(eps - kpar * kpar / (k0 * k0));
  if (q.imag() < 0) q = -q;
  return q;
}

V3 crossr(const std::array<double, 3>& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

std::array<cplx, 2> airy(const Stack& s, double k0, double kpar) {
  const int L = static_cast<int>(s.eps.size()) - 2;
  std::vector<cplx> q(s.eps.size());
  for (size_t j = 0; j < q.size(); ++j) q[j] = q_of(s.eps[j], k0, kpar);
  auto rs = [&](int j) { return (q[j - 1] - q[j]) / (q[j - 1] + q[j]); };
  auto rp = [&](int j) {
    return (s.eps[j] * q[j - 1] - s.eps[j - 1] * q[j]) / (s.eps[j] * q[j - 1] + s.eps[j - 1] * q[j]);
  };
  cplx Gs = rs(L + 1), Gp = rp(L + 1);
  for (int j = L; j >= 1; --j) {
    cplx ph = std::exp(cplx(0, 2.0 * k0 * s.thick[j - 1]) * q[j]);
    cplx a = rs(j), b = rp(j);
    Gs = (a + Gs * ph) / (1.0 + a * Gs * ph);
    Gp = (b + Gp * ph) / (1.0 + b * Gp * ph);
  }
  return {Gs, Gp};
}

std::array<V3, 2> reflect(const Stack& s, double k0, double kx, double ky, const V3& Einc) {
  double kpar = std::hypot(kx, ky);
  double kz = std::sqrt(k0 * k0 - kpar * kpar);
  std::array<double, 3> ki = {kx / k0, ky / k0, kz / k0}, kr = {kx / k0, ky / k0, -kz / k0};
  std::array<double, 3> sh;
  if (kpar < 1e-12 * k0) sh = {0, 1, 0};
  else sh = {ky / kpar, -kx / kpar, 0};  // k̂ × ẑ normalised
  V3 Hinc = crossr(ki, Einc);
  auto r = airy(s, k0, kpar);
  cplx es = sh[0] * Einc[0] + sh[1] * Einc[1] + sh[2] * Einc[2];
  cplx hs = sh[0] * Hinc[0] + sh[1] * Hinc[1] + sh[2] * Hinc[2];
  // ŝ × k̂_r
  std::array<double, 3> sxk = {sh[1] * kr[2] - sh[2] * kr[1], sh[2] * kr[0] - sh[0] * kr[2],
                               sh[0] * kr[1] - sh[1] * kr[0]};
  V3 E;
  for (int c = 0; c < 3; ++c) E[c] = r[0] * es * sh[c] + r[1] * hs * sxk[c];
  return {E, crossr(kr, E)};
}

}  // namespace plumage::fdtd_reference
