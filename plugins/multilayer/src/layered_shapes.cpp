// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "layered_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace plumage::multilayer::detail {

std::vector<double> xs_of(const Polyline& p) {
  std::vector<double> x(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x[i] = p[i].x;
  return x;
}

Material mixture_of(const MixtureSpec& m, double f) { return Material::mixture(m.host, m.guest, f); }

void renormalise(std::vector<double>& v, double total) {
  const double sum = std::accumulate(v.begin(), v.end(), 0.0);
  if (sum > 0) for (double& x : v) x *= total / sum;
}

double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

std::vector<double> fraction_at(const Polyline& line, const MixtureSpec& m, double width, RandomStream& rng) {
  auto xs = xs_of(line);
  for (double& x : xs) x = std::clamp(x, -0.5 * width, 0.5 * width);
  return rough_profile(xs, -0.5 * width, 0.5 * width, m.fraction.rough, rng);
}

std::vector<double> profile_at(const std::vector<double>& xs_in, double width, const RoughSpec& spec,
                               RandomStream& rng, bool permute) {
  std::vector<double> xs(xs_in);
  for (double& x : xs) x = std::clamp(x, -0.5 * width, 0.5 * width);
  return rough_profile(xs, -0.5 * width, 0.5 * width, spec, rng, permute);
}

Polygon clipped_band(const Polyline& upper, const Polyline& lower, double x_lo, double x_hi) {
  return band_polygon(keep_x(upper, x_lo, x_hi), keep_x(lower, x_lo, x_hi));
}

void append_arc_from(Polyline& out, Vec2 c, double r, Vec2 t, Vec2 n, double ca, double sa, double a0,
                     double a1, double step) {
  const int k = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / step)));
  // Rotate (cos, sin) by a fixed step instead of calling the trigonometric functions per point.
  const double da = (a1 - a0) / k, cd = std::cos(da), sd = std::sin(da);
  for (int j = 0; j <= k; ++j) {
    out.push_back(c + (r * ca) * t + (r * sa) * n);
    const double nc = ca * cd - sa * sd;
    sa = sa * cd + ca * sd;
    ca = nc;
  }
}

void append_arc(Polyline& out, Vec2 c, double r, Vec2 t, Vec2 n, double a0, double a1, double step) {
  append_arc_from(out, c, r, t, n, std::cos(a0), std::sin(a0), a0, a1, step);
}

}  // namespace plumage::multilayer::detail
