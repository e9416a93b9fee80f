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

// In-place radix-2 complex FFT (size a power of two); inverse without 1/N scaling.
void fft_radix2(std::vector<Complex>& data, bool inverse);

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

// Regular polygons approximating circles and ellipses (the ellipse's own x axis rotated by
// `tilt` radians), counter-clockwise, inscribed (vertices on the curve).
Polygon circle_polygon(Vec2 center, double radius, int segments);
Polygon ellipse_polygon(Vec2 center, double semi_x, double semi_z, double tilt, int segments);

// Closes the band between an upper and a lower polyline (both left → right) into a
// counter-clockwise polygon: lower left → right, then upper right → left (a vertex shared by
// both ends, as where a circle's halves meet, appears once).
Polygon band_polygon(const Polyline& upper, const Polyline& lower);

}  // namespace plumage
