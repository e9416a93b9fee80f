// Layer profiles along top-surface normals (wave-simulation spec §2.1); validity checks are in
// cross_section_validity.cpp.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <cmath>

#include "plumage/cross_section.hpp"
#include "plumage/error.hpp"
#include "plumage/geometry.hpp"

namespace plumage {

std::string_view role_name(RegionRole role) {
  switch (role) {
    case RegionRole::body: return "body";
    case RegionRole::cortex: return "cortex";
    case RegionRole::melanosome: return "melanosome";
    case RegionRole::air_bubble: return "air_bubble";
    case RegionRole::platelet: return "platelet";
    case RegionRole::air_gap: return "air_gap";
    case RegionRole::granular_layer: return "granular_layer";
    case RegionRole::mixed_core: return "mixed_core";
    case RegionRole::rod: return "rod";
    case RegionRole::core: return "core";
    case RegionRole::channel: return "channel";
    case RegionRole::film: return "film";
  }
  return "?";
}

double signed_area(const Polygon& p) {
  double a = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += cross(p[j], p[i]);
  return 0.5 * a;
}

bool point_in_polygon(Vec2 q, const Polygon& p) {
  bool inside = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    const Vec2 a = p[j], b = p[i];
    if ((a.z > q.z) != (b.z > q.z)) {
      const double x = a.x + (q.z - a.z) / (b.z - a.z) * (b.x - a.x);
      if (q.x < x) inside = !inside;
    }
  }
  return inside;
}

namespace {

// Where the line {r : t·(r − p) = 0} meets a boundary; nullopt if the boundary does not cross
// it (and extrapolation is not allowed).
struct Hit {
  Vec2 point;
  double fraction = -1.0;  // interpolated per-vertex fraction, −1 when none
};

Hit intersect_segment(const LayerBoundary& b, std::size_t i, Vec2 p, Vec2 t) {
  const Vec2 a = b.points[i], c = b.points[i + 1];
  const double va = dot(t, a - p), vc = dot(t, c - p);
  const double denom = va - vc;
  const double s = denom != 0.0 ? va / denom : 0.0;  // may lie outside [0, 1] (extrapolation)
  Hit h{a + s * (c - a), -1.0};
  if (!b.fraction.empty()) {
    const double sc = std::clamp(s, 0.0, 1.0);
    h.fraction = (1.0 - sc) * b.fraction[i] + sc * b.fraction[i + 1];
  }
  return h;
}

bool crosses(const LayerBoundary& b, Vec2 p, Vec2 t) {
  const double v0 = dot(t, b.points.front() - p), v1 = dot(t, b.points.back() - p);
  return (v0 <= 0.0 && v1 >= 0.0) || (v0 >= 0.0 && v1 <= 0.0);
}

Hit intersect(const LayerBoundary& b, Vec2 p, Vec2 t) {
  const auto& pts = b.points;
  const std::size_t n = pts.size();
  const double v0 = dot(t, pts.front() - p), v1 = dot(t, pts.back() - p);
  // The line through an end vertex: that end's segment (the bisection below, which needs a sign
  // change, would otherwise walk to the far end and extrapolate the last segment back).
  if (v0 == 0.0) return intersect_segment(b, 0, p, t);
  if (v1 == 0.0) return intersect_segment(b, n - 2, p, t);
  if ((v0 < 0.0) != (v1 < 0.0)) {
    // Bisection on vertex indices keeps one bracketing segment.
    std::size_t lo = 0, hi = n - 1;
    const bool lo_neg = v0 < 0.0;
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      const double vm = dot(t, pts[mid] - p);
      if ((vm < 0.0) == lo_neg) lo = mid; else hi = mid;
    }
    return intersect_segment(b, lo, p, t);
  }
  // Missed: extend the end segment whose end is closer to the line.
  return std::abs(v0) <= std::abs(v1) ? intersect_segment(b, 0, p, t)
                                      : intersect_segment(b, n - 2, p, t);
}

Material material_below(const LayerBoundary& b, const Hit& h) {
  if (h.fraction >= 0.0 && b.below.kind() == Material::Kind::mixture) {
    return b.below.with_fraction(h.fraction);
  }
  return b.below;
}

}  // namespace

LayerProfile layer_profile_at(const CrossSection& cs, std::size_t node) {
  if (!cs.layered) throw Error("layer_profile_at: " + cs.label + " has no layered model");
  if (node >= cs.top.size() || cs.top.size() < 2) throw Error("layer_profile_at: node out of range");
  const Vec2 p = cs.top[node];
  const Vec2 a = cs.top[node == 0 ? 0 : node - 1];
  const Vec2 c = cs.top[node + 1 == cs.top.size() ? node : node + 1];
  Vec2 t = c - a;
  t = (1.0 / norm(t)) * t;

  const auto& bs = cs.layered->boundaries;
  LayerProfile profile;
  profile.ambient = Material::air();
  Material current = cs.layered->below_top;
  Vec2 previous = p;
  std::size_t i = 0;
  while (i < bs.size()) {
    const LayerBoundary& b = bs[i];
    if (b.points.size() < 2) { ++i; continue; }
    if (b.closes >= 0) {
      const auto& closing = bs[static_cast<std::size_t>(b.closes)];
      if (!crosses(b, p, t) || !crosses(closing, p, t)) {
        i = static_cast<std::size_t>(b.closes) + 1;  // bracket missed: the medium above continues
        continue;
      }
    }
    const Hit h = intersect(b, p, t);
    const double thickness = norm(h.point - previous);
    if (thickness <= 1e-9) {
      // A zero thickness ends the stack (reference behaviour): the medium below is the substrate.
      profile.substrate = material_below(b, h);
      return profile;
    }
    profile.layers.push_back({current, thickness});
    current = material_below(b, h);
    previous = h.point;
    ++i;
  }
  profile.substrate = current;
  return profile;
}

std::vector<LayerProfile> layer_profiles(const CrossSection& cs) {
  std::vector<LayerProfile> out;
  out.reserve(cs.top.size());
  for (std::size_t i = 0; i < cs.top.size(); ++i) out.push_back(layer_profile_at(cs, i));
  return out;
}

}  // namespace plumage
