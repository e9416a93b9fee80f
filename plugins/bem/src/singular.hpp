// Static (wavenumber-independent) parts of the 2D Green's function integrated analytically over a
// straight source segment with linear shape functions (spec §6.5):
//   G = −ln R/(2π) + G_reg,   G'(R) R̂ = −(ρ − ρ')/(2π R²) + G'_reg R̂.
#pragma once

#include <array>

#include "plumage/cross_section.hpp"

namespace plumage::bem {

// Source segment ρ'(u) = a + u ê, u ∈ [0, h], shape functions N0 = 1 − u/h, N1 = u/h;
// observation point p (may lie on the segment's line, but not at an end point for `vec`).
struct StaticInner {
  std::array<double, 2> log;   // ∫ N_j(u) ln R du
  std::array<Vec2, 2> vec;     // ∫ N_j(u) (p − ρ'(u))/R² du
};
StaticInner static_inner(Vec2 p, Vec2 a, Vec2 e, double h);

// ∫∫ N_i(u) N_j(u') ln|u − u'| du du' over one segment of length h (closed form):
// h²(ln h · M_ij + L_ij), M = [[1/3, 1/6], [1/6, 1/3]], L = [[−7/16, −5/16], [−5/16, −7/16]].
std::array<std::array<double, 2>, 2> self_log_integral(double h);

}  // namespace plumage::bem
