// Building blocks of procedural barbule geometry (geometry-and-brdf spec §1.1), shared by the
// structure generator plug-ins. Lengths in nm.
#pragma once

#include <span>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/random.hpp"

namespace plumage {

// A random rough profile with a Gaussian-shaped spectrum (spec §1.1(a)): fixed amplitudes
// A(f) = exp(−π²τ²f²) and random phases, periodic over [x_min, x_max], so its autocorrelation is
// Gaussian, ∝ exp(−Δx²/(2τ²)) (τ = `correlation_nm`). Evaluated at `xs` (inside [x_min, x_max])
// and mapped affinely so that its minimum over `xs` is exactly `lo` and its maximum exactly `hi`.
// With `permute` the profile is shifted circularly so that its minimum sits at x_min.
struct RoughSpec {
  double correlation_nm = 1000.0;
  double lo_nm = 0.0;
  double hi_nm = 0.0;
};
std::vector<double> rough_profile(std::span<const double> xs, double x_min, double x_max,
                                  const RoughSpec& spec, RandomStream& rng, bool permute = false);

// Statistics of rough profiles. `values` at increasing positions `xs` are resampled onto `count`
// uniform points over [xs.front(), xs.back()) and treated as one period; the circular
// autocovariance (mean removed) is returned for lags 0 … max_lag (in grid steps), with the grid
// step in `step_nm`. A power-of-two `count` uses the FFT.
std::vector<double> circular_autocovariance(std::span<const double> xs, std::span<const double> values,
                                            std::size_t count, std::size_t max_lag, double& step_nm);
// The Gaussian correlation parameter τ of C(Δ) ∝ exp(−Δ²/(2τ²)), by a least-squares fit of
// log((C − b)/(C0 − b)) against Δ² over the lags where (C − b)/(C0 − b) > 0.1. The baseline b
// is the mean of C over its second half (lags beyond a quarter period when C reaches half the
// period): a finite periodic profile without DC has C = Gaussian − constant.
double gaussian_correlation_length(std::span<const double> autocovariance, double step_nm);

// Polyline tools.
double polyline_length(const Polyline& line);
// Resampled at uniform arc length: ⌈L/spacing⌉ segments (rounded up to even if `even`).
Polyline resample_uniform(const Polyline& line, double spacing_nm, bool even = false);
// Each vertex moved by `distance[i]` along its inward normal (−normal); conformal offset.
Polyline offset_inward(const Polyline& line, std::span<const double> distance);
Polyline offset_inward(const Polyline& line, double distance);
// z of a polyline monotone in x at `x` (linear interpolation, clamped at the ends).
double z_at(const Polyline& line, double x);
// The part of a polyline (monotone in x) with x in [x_lo, x_hi], cut at interpolated ends.
Polyline clip_x(const Polyline& line, double x_lo, double x_hi);
// The vertices of a polyline with x in [x_lo, x_hi] (no new vertices: pieces cut this way
// share their vertices exactly with the original, so touching regions meet at common vertices).
Polyline keep_x(const Polyline& line, double x_lo, double x_hi);
// Removes vertices so that x is strictly increasing (drops folds of a tight offset).
Polyline make_monotone(const Polyline& line);

// The elliptic-arc top of spec §1.1(b): width W, edge slopes ±tan β, ellipse angle
// φ_e = π/6 + (π/4)·u (u in [0, 1]); sampled at uniform arc length ≈ spacing (even count),
// centred in x; z of the ends = 0 (callers recentre).
Polyline elliptic_arc(double width_nm, double beta_rad, double u, double spacing_nm);

// A flat top with rounded ellipse-quarter shoulders (the upper half of spec §1.1(c)'s pillow):
// flat over |x| ≤ W/2 − a, then dropping by h·(1 − √(1 − s²)) with s = (|x| − (W/2 − a))/a up to
// s = s_max (< 1); uniform arc length ≈ spacing. z = 0 on the flat part.
Polyline shoulder_top(double width_nm, double shoulder_length_nm, double shoulder_height_nm,
                      double s_max, double spacing_nm);

// A polyline parametrised by arc length: position and unit tangent at any s in [0, length()].
class ArcLengthCurve {
 public:
  explicit ArcLengthCurve(Polyline line);
  double length() const { return s_.empty() ? 0.0 : s_.back(); }
  Vec2 point(double s) const;
  // The same for increasing s: `hint` (start at 0) remembers the segment, so a walk along the
  // curve costs O(1) per call instead of a binary search.
  Vec2 point(double s, std::size_t& hint) const;
  Vec2 tangent(double s) const;  // of the segment containing s
  Vec2 normal(double s) const { const Vec2 t = tangent(s); return {-t.z, t.x}; }
  const Polyline& line() const { return line_; }

 private:
  std::size_t segment(double s) const;
  Polyline line_;
  std::vector<double> s_;
};

// Regular polygons approximating circles and ellipses (the ellipse's own x axis rotated by
// `tilt` radians), counter-clockwise, inscribed (vertices on the curve).
Polygon circle_polygon(Vec2 center, double radius, int segments);
Polygon ellipse_polygon(Vec2 center, double semi_x, double semi_z, double tilt, int segments);

// Closes the band between an upper and a lower polyline (both left → right) into a
// counter-clockwise polygon: lower left → right, then upper right → left (a vertex shared by
// both ends, as where a circle's halves meet, appears once).
Polygon band_polygon(const Polyline& upper, const Polyline& lower);

}  // namespace plumage
