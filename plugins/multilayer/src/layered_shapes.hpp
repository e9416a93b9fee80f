// Shapes shared by the layered_barbule models (layered_barbule.cpp, layered_rows.cpp,
// layered_platelets.cpp): arcs, bands between boundaries, mixture profiles along x.
#pragma once

#include <vector>

#include "layered_barbule.hpp"
#include "plumage/geometry.hpp"

namespace plumage::multilayer::detail {

std::vector<double> xs_of(const Polyline& p);

Material mixture_of(const MixtureSpec& m, double fraction);

// Renormalise values so they sum to `total`.
void renormalise(std::vector<double>& v, double total);

double mean_of(const std::vector<double>& v);

// Per-vertex fraction values of a mixture profile over [−W/2, W/2] at the vertices of `line`.
std::vector<double> fraction_at(const Polyline& line, const MixtureSpec& m, double width, RandomStream& rng);

// Rough values of a profile over [−W/2, W/2] at arbitrary x (clamped).
std::vector<double> profile_at(const std::vector<double>& xs_in, double width, const RoughSpec& spec,
                               RandomStream& rng, bool permute = false);

// The band between two boundaries cut to their vertices in [x_lo, x_hi] (closed by nearly
// vertical segments between vertices shared with the neighbouring regions).
Polygon clipped_band(const Polyline& upper, const Polyline& lower, double x_lo, double x_hi);

// Arc of radius r around c from angle a0 to a1 in the frame (t, n), starting from the known
// cosine and sine of a0 (no trigonometric call for the start; one for the step).
void append_arc_from(Polyline& out, Vec2 c, double r, Vec2 t, Vec2 n, double ca, double sa, double a0,
                     double a1, double step);
void append_arc(Polyline& out, Vec2 c, double r, Vec2 t, Vec2 n, double a0, double a1, double step);

}  // namespace plumage::multilayer::detail
