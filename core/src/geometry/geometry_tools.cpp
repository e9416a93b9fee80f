// Procedural geometry building blocks (spec geometry-and-brdf §1.1).
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "plumage/error.hpp"
#include "plumage/geometry.hpp"
#include "fft/real_fft.hpp"

namespace plumage {

double RandomStream::normal() {
  // Box-Muller; u1 in (0, 1] so the logarithm is finite.
  const double u1 = 1.0 - uniform();
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

std::vector<double> rough_profile(std::span<const double> xs, double x_min, double x_max,
                                  const RoughSpec& spec, RandomStream& rng, bool permute) {
  const double length = x_max - x_min;
  if (!(length > 0.0)) throw Error("rough_profile: empty domain");
  if (!(spec.correlation_nm > 0.0)) throw Error("rough_profile: correlation length must be > 0");
  if (spec.lo_nm > spec.hi_nm) throw Error("rough_profile: inverted range");
  // Grid: spacing at most τ/10 and 30 nm, a power of two.
  const double target = std::min(spec.correlation_nm / 10.0, 30.0);
  std::size_t n = 64;
  while (static_cast<double>(n) * target < length) n <<= 1;
  std::vector<Complex> spectrum(n / 2 + 1, Complex(0.0, 0.0));
  const double tau = spec.correlation_nm;
  // Hermitian spectrum: bins k = 1 … n/2−1 get random phases (−k the conjugate, implied by the
  // real inverse transform); DC and Nyquist 0.
  for (std::size_t k = 1; k < n / 2; ++k) {
    const double f = static_cast<double>(k) / length;
    const double amplitude = std::exp(-kPi * kPi * tau * tau * f * f);
    const double phase = rng.uniform(-kPi, kPi);
    if (amplitude < 1e-300) continue;
    spectrum[k] = std::polar(amplitude, phase);
  }
  std::vector<double> grid;
  detail::RealFft(n).inverse(spectrum, grid);
  if (permute) {
    auto it = std::min_element(grid.begin(), grid.end());
    std::rotate(grid.begin(), it, grid.end());
  }
  std::vector<double> out(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    double u = (xs[i] - x_min) / length * static_cast<double>(n);
    u = std::clamp(u, 0.0, static_cast<double>(n));
    std::size_t i0 = static_cast<std::size_t>(std::floor(u));
    const double t = u - static_cast<double>(i0);
    i0 %= n;
    const std::size_t i1 = (i0 + 1) % n;
    out[i] = (1.0 - t) * grid[i0] + t * grid[i1];
  }
  if (out.empty()) return out;
  const auto [mn, mx] = std::minmax_element(out.begin(), out.end());
  const double lo = *mn, hi = *mx;
  const double scale = hi > lo ? (spec.hi_nm - spec.lo_nm) / (hi - lo) : 0.0;
  for (double& v : out) v = spec.lo_nm + (v - lo) * scale;
  // Exact ends (no rounding residue): the extreme samples are the configured bounds.
  if (hi > lo) {
    out[static_cast<std::size_t>(mn - out.begin())] = spec.lo_nm;
    out[static_cast<std::size_t>(mx - out.begin())] = spec.hi_nm;
  }
  return out;
}

std::vector<double> circular_autocovariance(std::span<const double> xs, std::span<const double> v,
                                            std::size_t count, std::size_t max_lag, double& step_nm) {
  if (xs.size() != v.size() || xs.size() < 2 || count < 2) throw Error("circular_autocovariance: bad input");
  const double x0 = xs.front(), x1 = xs.back();
  step_nm = (x1 - x0) / static_cast<double>(count);
  std::vector<double> g(count);
  std::size_t j = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const double x = x0 + step_nm * static_cast<double>(i);
    while (j + 2 < xs.size() && xs[j + 1] < x) ++j;
    const double dx = xs[j + 1] - xs[j];
    const double t = dx > 0 ? std::clamp((x - xs[j]) / dx, 0.0, 1.0) : 0.0;
    g[i] = (1.0 - t) * v[j] + t * v[j + 1];
  }
  double mean = 0.0;
  for (double x : g) mean += x;
  mean /= static_cast<double>(count);
  for (double& x : g) x -= mean;
  max_lag = std::min(max_lag, count - 1);
  std::vector<double> c(max_lag + 1, 0.0);
  if ((count & (count - 1)) == 0) {  // power of two: Wiener-Khinchin with the FFT
    const detail::RealFft fft(count);
    std::vector<Complex> f;
    fft.forward(g, f);
    for (auto& v : f) v = std::norm(v);
    std::vector<double> acf;
    fft.inverse(f, acf);
    const double scale = 1.0 / (static_cast<double>(count) * static_cast<double>(count));
    for (std::size_t k = 0; k <= max_lag; ++k) c[k] = acf[k] * scale;
    return c;
  }
  for (std::size_t k = 0; k <= max_lag; ++k) {
    double acc = 0.0;
    for (std::size_t i = 0; i < count; ++i) acc += g[i] * g[(i + k) % count];
    c[k] = acc / static_cast<double>(count);
  }
  return c;
}

double gaussian_correlation_length(std::span<const double> c, double step_nm) {
  if (c.size() < 4 || !(c[0] > 0.0)) return 0.0;
  double b = 0.0;
  for (std::size_t k = c.size() / 2; k < c.size(); ++k) b += c[k];
  b /= static_cast<double>(c.size() - c.size() / 2);
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 1; k < c.size(); ++k) {
    const double r = (c[k] - b) / (c[0] - b);
    if (r <= 0.1) break;
    const double x = std::pow(step_nm * static_cast<double>(k), 2.0);
    sxx += x * x;
    sxy += x * std::log(r);
  }
  if (sxx == 0.0) return 0.0;
  const double slope = sxy / sxx;  // through the origin: log r = −x/(2τ²)
  return slope < 0.0 ? std::sqrt(-1.0 / (2.0 * slope)) : 0.0;
}

double polyline_length(const Polyline& line) {
  double l = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) l += norm(line[i] - line[i - 1]);
  return l;
}

Polyline resample_uniform(const Polyline& line, double spacing_nm, bool even) {
  if (line.size() < 2) return line;
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + norm(line[i] - line[i - 1]);
  const double total = s.back();
  std::size_t segments = static_cast<std::size_t>(std::ceil(total / spacing_nm - 1e-9));
  segments = std::max<std::size_t>(segments, 1);
  if (even && segments % 2) ++segments;
  Polyline out;
  out.reserve(segments + 1);
  std::size_t j = 0;
  for (std::size_t k = 0; k <= segments; ++k) {
    const double target = total * static_cast<double>(k) / static_cast<double>(segments);
    while (j + 2 < line.size() && s[j + 1] < target) ++j;
    const double seg = s[j + 1] - s[j];
    const double t = seg > 0 ? std::clamp((target - s[j]) / seg, 0.0, 1.0) : 0.0;
    out.push_back(line[j] + t * (line[j + 1] - line[j]));
  }
  out.front() = line.front();
  out.back() = line.back();
  return out;
}

std::vector<Vec2> vertex_normals(const Polyline& line) {
  std::vector<Vec2> n(line.size(), Vec2{0.0, 1.0});
  if (line.size() < 2) return n;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const Vec2 a = line[i == 0 ? 0 : i - 1];
    const Vec2 b = line[i + 1 == line.size() ? i : i + 1];
    Vec2 t = b - a;
    const double l = norm(t);
    if (l > 0) t = (1.0 / l) * t;
    n[i] = Vec2{-t.z, t.x};
  }
  return n;
}

Polyline offset_inward(const Polyline& line, std::span<const double> distance) {
  if (distance.size() != line.size()) throw Error("offset_inward: one distance per vertex");
  const auto n = vertex_normals(line);
  Polyline out(line.size());
  for (std::size_t i = 0; i < line.size(); ++i) out[i] = line[i] - distance[i] * n[i];
  return out;
}

Polyline offset_inward(const Polyline& line, double distance) {
  std::vector<double> d(line.size(), distance);
  return offset_inward(line, d);
}

double z_at(const Polyline& line, double x) {
  if (line.empty()) throw Error("z_at: empty polyline");
  if (x <= line.front().x) return line.front().z;
  if (x >= line.back().x) return line.back().z;
  auto it = std::upper_bound(line.begin(), line.end(), x,
                             [](double v, const Vec2& p) { return v < p.x; });
  const Vec2 b = *it, a = *(it - 1);
  const double t = b.x > a.x ? (x - a.x) / (b.x - a.x) : 0.0;
  return a.z + t * (b.z - a.z);
}

Polyline clip_x(const Polyline& line, double x_lo, double x_hi) {
  Polyline out;
  if (line.size() < 2 || x_lo >= x_hi) return out;
  out.push_back({x_lo, z_at(line, x_lo)});
  auto first = std::upper_bound(line.begin(), line.end(), x_lo, [](double v, const Vec2& p) { return v < p.x; });
  for (auto it = first; it != line.end() && it->x < x_hi; ++it) out.push_back(*it);
  out.push_back({x_hi, z_at(line, x_hi)});
  return out;
}

Polyline keep_x(const Polyline& line, double x_lo, double x_hi) {
  Polyline out;
  for (const Vec2& p : line) {
    if (p.x >= x_lo && p.x <= x_hi) out.push_back(p);
  }
  return out;
}

Polyline make_monotone(const Polyline& line) {
  Polyline out;
  out.reserve(line.size());
  for (const Vec2& p : line) {
    if (out.empty() || p.x > out.back().x) out.push_back(p);
  }
  return out;
}

Polyline elliptic_arc(double width_nm, double beta_rad, double u, double spacing_nm) {
  const double phi_e = kPi / 6.0 + (kPi / 4.0) * u;
  const double a0 = 0.5 * width_nm / std::cos(phi_e);
  const double b0 = a0 * std::tan(phi_e) * std::tan(beta_rad);
  // Dense sampling of t from π − φ_e down to φ_e (x increasing), then uniform arc length.
  const int dense = 4096;
  Polyline p;
  p.reserve(dense + 1);
  for (int k = 0; k <= dense; ++k) {
    const double t = (kPi - phi_e) + (2.0 * phi_e - kPi) * k / dense;
    p.push_back({a0 * std::cos(t), b0 * std::sin(t) - b0 * std::sin(phi_e)});
  }
  p.front().x = -0.5 * width_nm;
  p.back().x = 0.5 * width_nm;
  return resample_uniform(p, spacing_nm, true);
}

Polyline shoulder_top(double width_nm, double a, double h, double s_max, double spacing_nm) {
  const double half = 0.5 * width_nm;
  const double flat = half - a;
  // Parametrise each shoulder by the ellipse angle so the near-vertical end is sampled well.
  const double ang_max = std::asin(std::clamp(s_max, 0.0, 1.0));
  const int dense_sh = 1024;
  Polyline right;
  for (int k = 0; k <= dense_sh; ++k) {
    const double ang = ang_max * k / dense_sh;
    const double s = std::sin(ang);
    right.push_back({flat + a * s, -h * (1.0 - std::cos(ang))});
  }
  // Scale x so the top spans exactly the width.
  const double x_end = right.back().x;
  Polyline p;
  for (auto it = right.rbegin(); it != right.rend(); ++it) p.push_back({-it->x, it->z});
  for (std::size_t k = 1; k < right.size(); ++k) p.push_back(right[k]);
  for (Vec2& v : p) v.x *= half / x_end;
  return resample_uniform(p, spacing_nm, true);
}

ArcLengthCurve::ArcLengthCurve(Polyline line) : line_(std::move(line)), s_(line_.size(), 0.0) {
  if (line_.size() < 2) throw Error("ArcLengthCurve: needs at least two points");
  for (std::size_t i = 1; i < line_.size(); ++i) s_[i] = s_[i - 1] + norm(line_[i] - line_[i - 1]);
}

std::size_t ArcLengthCurve::segment(double s) const {
  auto it = std::upper_bound(s_.begin(), s_.end(), s);
  std::size_t i = it == s_.begin() ? 0 : static_cast<std::size_t>(it - s_.begin()) - 1;
  return std::min(i, line_.size() - 2);
}

Vec2 ArcLengthCurve::point(double s) const {
  const std::size_t i = segment(s);
  const double len = s_[i + 1] - s_[i];
  const double t = len > 0 ? (s - s_[i]) / len : 0.0;
  return line_[i] + t * (line_[i + 1] - line_[i]);
}

Vec2 ArcLengthCurve::point(double s, std::size_t& hint) const {
  std::size_t i = std::min(hint, line_.size() - 2);
  if (s < s_[i]) i = segment(s);
  while (i + 2 < line_.size() && s_[i + 1] <= s) ++i;
  hint = i;
  const double len = s_[i + 1] - s_[i];
  const double t = len > 0 ? (s - s_[i]) / len : 0.0;
  return line_[i] + t * (line_[i + 1] - line_[i]);
}

Vec2 ArcLengthCurve::tangent(double s) const {
  const std::size_t i = segment(s);
  Vec2 d = line_[i + 1] - line_[i];
  const double l = norm(d);
  return l > 0 ? (1.0 / l) * d : Vec2{1.0, 0.0};
}

Polygon circle_polygon(Vec2 center, double radius, int segments) {
  return ellipse_polygon(center, radius, radius, 0.0, segments);
}

Polygon ellipse_polygon(Vec2 c, double sx, double sz, double tilt, int segments) {
  Polygon out(static_cast<std::size_t>(segments));
  const double ct = std::cos(tilt), st = std::sin(tilt);
  for (int k = 0; k < segments; ++k) {
    const double t = 2.0 * kPi * k / segments;
    const double ex = sx * std::cos(t), ez = sz * std::sin(t);
    out[static_cast<std::size_t>(k)] = {c.x + ct * ex - st * ez, c.z + st * ex + ct * ez};
  }
  return out;
}

Polygon band_polygon(const Polyline& upper, const Polyline& lower) {
  Polygon out;
  out.reserve(upper.size() + lower.size());
  for (const Vec2& p : lower) out.push_back(p);
  for (auto it = upper.rbegin(); it != upper.rend(); ++it) {
    if (out.empty() || !(*it == out.back())) out.push_back(*it);
  }
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

}  // namespace plumage
