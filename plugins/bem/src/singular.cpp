// Closed forms of spec §6.5 for a segment ρ' = a + u ê, w = u − u0, u0 = (p − a)·ê,
// v = signed distance of p from the line, R² = w² + v²:
//   ∫ ln R dw = w ln R − w + v arctan(w/v),   ∫ w ln R dw = ½R² ln R − w²/4,
//   ∫ w/R² dw = ln R,   ∫ v/R² dw = arctan(w/v),   ∫ w²/R² dw = w − v arctan(w/v).
#include "singular.hpp"

#include <cmath>

namespace plumage::bem {

namespace {

struct Prim {
  double lnR, wlnR_minus_w, atan_v, half_r2lnR;  // ln R, w ln R − w, arctan(w/v), ½R² ln R
};

}  // namespace

StaticInner static_inner(Vec2 p, Vec2 a, Vec2 e, double h) {
  const Vec2 nu{-e.z, e.x};
  const double u0 = dot(p - a, e);
  const double v = dot(p - a, nu);
  const bool online = std::abs(v) < 1e-12 * h;
  auto prim = [&](double w) {
    const double r2 = w * w + v * v;
    Prim q{};
    q.lnR = r2 > 0.0 ? 0.5 * std::log(r2) : 0.0;
    q.wlnR_minus_w = (w != 0.0 ? w * q.lnR : 0.0) - w;
    q.atan_v = online ? 0.0 : std::atan(w / v);
    q.half_r2lnR = r2 > 0.0 ? 0.5 * r2 * q.lnR : 0.0;
    return q;
  };
  const double w1 = -u0, w2 = h - u0;
  const Prim A = prim(w1), B = prim(w2);
  const double d_atan = B.atan_v - A.atan_v;
  const double d_lnR = B.lnR - A.lnR;
  // ∫ ln R du and ∫ u ln R du
  const double S0 = (B.wlnR_minus_w - A.wlnR_minus_w) + (online ? 0.0 : v * d_atan);
  const double Sw = (B.half_r2lnR - w2 * w2 / 4.0) - (A.half_r2lnR - w1 * w1 / 4.0);
  const double S1 = Sw + u0 * S0;  // ∫ u ln R du
  // ∫ (p − ρ')/R² du = ∫ (−w ê + v ν)/R² dw
  const double Ie = -d_lnR;  // ê component
  const double In = d_atan;  // ν component (= ∫ v/R²)
  // ∫ u (p − ρ')/R² du, u = w + u0
  const double int_w2 = (w2 - w1) - (online ? 0.0 : v * d_atan);  // ∫ w²/R²
  const double Ue = -int_w2 - u0 * d_lnR;
  const double Un = v * d_lnR + u0 * d_atan;
  StaticInner r;
  r.log[1] = S1 / h;
  r.log[0] = S0 - r.log[1];
  const Vec2 v1 = (1.0 / h) * (Ue * e + Un * nu);
  const Vec2 vall = Ie * e + In * nu;
  r.vec[1] = v1;
  r.vec[0] = vall - v1;
  return r;
}

std::array<std::array<double, 2>, 2> self_log_integral(double h) {
  const double lh = std::log(h), h2 = h * h;
  const double d = h2 * (lh / 3.0 - 7.0 / 16.0), o = h2 * (lh / 6.0 - 5.0 / 16.0);
  return {{{d, o}, {o, d}}};
}

}  // namespace plumage::bem
