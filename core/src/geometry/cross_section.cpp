// Layer profiles along top-surface normals (wave-simulation spec §2.1) and geometric validity.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <array>
#include <set>
#include <cmath>
#include <sstream>
#include <cstdint>

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
  if ((v0 < 0.0) != (v1 < 0.0) || v0 == 0.0 || v1 == 0.0) {
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

// ---------------------------------------------------------------------------------------------
// Validity

namespace {

struct Segment {
  Vec2 a, b;
  int region;   // −1 top polyline, −2 layered boundary k (see owner)
  std::size_t index;
  std::size_t count;  // vertices in the owner (for adjacency)
  bool closed;
};

int orient(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}

// True if the segments intersect at a point interior to both (a proper crossing) or overlap
// in a way other than sharing an endpoint or being identical.
bool bad_intersection(const Segment& s, const Segment& u) {
  const bool same_ends = (s.a == u.a && s.b == u.b) || (s.a == u.b && s.b == u.a);
  if (same_ends) return false;  // a shared edge
  if (s.a == u.a || s.a == u.b || s.b == u.a || s.b == u.b) return false;  // a shared vertex
  const int o1 = orient(s.a, s.b, u.a), o2 = orient(s.a, s.b, u.b);
  const int o3 = orient(u.a, u.b, s.a), o4 = orient(u.a, u.b, s.b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
  return false;  // touching at endpoints or collinear contact: allowed (shared boundaries)
}


}  // namespace

std::vector<std::string> validate(const CrossSection& cs) {
  std::vector<std::string> problems;
  auto problem = [&](const std::string& m) {
    if (problems.size() < 20) problems.push_back(m);
  };
  if (cs.top.size() < 3) problem("top surface has fewer than 3 vertices");
  for (std::size_t i = 1; i < cs.top.size(); ++i) {
    if (!(cs.top[i].x > cs.top[i - 1].x)) {
      std::ostringstream m;
      m << "top surface not monotone in x at vertex " << i;
      problem(m.str());
      break;
    }
  }
  for (const Vec2& v : cs.top) {
    if (!std::isfinite(v.x) || !std::isfinite(v.z)) { problem("non-finite top vertex"); break; }
  }
  if (cs.regions.empty()) {
    problem("no regions");
    return problems;
  }
  if (cs.regions[0].parent != -1) problem("region 0 (body) has a parent");
  if (cs.regions[0].outline != band_polygon(cs.top, cs.bottom)) {
    problem("body outline is not band_polygon(top, bottom): exact and reduced outlines differ");
  }
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const Region& g = cs.regions[r];
    if (g.outline.size() < 3) problem("region " + std::to_string(r) + " has < 3 vertices");
    if (g.parent >= static_cast<int>(r)) problem("region " + std::to_string(r) + " precedes its parent");
    if (r > 0 && g.parent < 0) problem("region " + std::to_string(r) + " has no parent");
    if (!(signed_area(g.outline) > 0.0)) problem("region " + std::to_string(r) + " is not counter-clockwise");
    for (const Vec2& v : g.outline) {
      if (!std::isfinite(v.x) || !std::isfinite(v.z)) { problem("non-finite vertex in region " + std::to_string(r)); break; }
    }
  }
  if (!problems.empty()) return problems;

  // Segment grid for crossing tests.
  std::vector<Segment> segs;
  double xmin = 1e300, xmax = -1e300, zmin = 1e300, zmax = -1e300;
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const auto& o = cs.regions[r].outline;
    for (std::size_t i = 0; i < o.size(); ++i) {
      const Vec2 a = o[i], b = o[(i + 1) % o.size()];
      segs.push_back({a, b, static_cast<int>(r), i, o.size(), true});
      xmin = std::min(xmin, a.x); xmax = std::max(xmax, a.x);
      zmin = std::min(zmin, a.z); zmax = std::max(zmax, a.z);
    }
  }
  // Bin segments into grid cells (sorted (cell, segment) pairs) and test pairs sharing a cell.
  // Cells about two mean segment lengths wide: each segment falls in a few cells.
  double mean_len = 0.0;
  for (const auto& sg : segs) mean_len += norm(sg.b - sg.a);
  mean_len /= static_cast<double>(std::max<std::size_t>(1, segs.size()));
  const double cell = std::max({2.0 * mean_len, (xmax - xmin) / 65536.0, 1e-6});
  const long long nx = static_cast<long long>((xmax - xmin) / cell) + 1;
  // (cell << 24 | segment) in one 64-bit word: sorting plain integers is several times faster.
  std::vector<std::uint64_t> binned;
  binned.reserve(segs.size() * 3);
  if (segs.size() >= (1u << 24)) throw Error("validate: too many segments");
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const auto& s = segs[k];
    const long long x0 = static_cast<long long>((std::min(s.a.x, s.b.x) - xmin) / cell);
    const long long x1 = static_cast<long long>((std::max(s.a.x, s.b.x) - xmin) / cell);
    const long long z0 = static_cast<long long>((std::min(s.a.z, s.b.z) - zmin) / cell);
    const long long z1 = static_cast<long long>((std::max(s.a.z, s.b.z) - zmin) / cell);
    for (long long zi = z0; zi <= z1; ++zi)
      for (long long xi = x0; xi <= x1; ++xi) {
        binned.push_back((static_cast<std::uint64_t>(zi * nx + xi) << 24) | static_cast<std::uint64_t>(k));
      }
  }
  std::sort(binned.begin(), binned.end());
  std::set<std::pair<int, int>> reported;
  for (std::size_t g0 = 0; g0 < binned.size();) {
    std::size_t g1 = g0;
    while (g1 < binned.size() && (binned[g1] >> 24) == (binned[g0] >> 24)) ++g1;
    for (std::size_t i = g0; i < g1; ++i) {
      for (std::size_t j = i + 1; j < g1; ++j) {
        const Segment& s = segs[binned[i] & 0xffffff];
        const Segment& u = segs[binned[j] & 0xffffff];
        if (s.region == u.region) {
          const std::size_t d = s.index > u.index ? s.index - u.index : u.index - s.index;
          if (d <= 1 || d == s.count - 1) continue;  // neighbours share a vertex
        }
        if (bad_intersection(s, u) &&
            reported.insert({std::min(s.region, u.region), std::max(s.region, u.region)}).second) {
          std::ostringstream m;
          m << "boundaries cross: region " << s.region << " edge " << s.index << " and region "
            << u.region << " edge " << u.index << " near (" << s.a.x << ", " << s.a.z << ") nm";
          problem(m.str());
        }
      }
    }
    g0 = g1;
  }
  if (!problems.empty()) return problems;

  // Nesting: a vertex of each region that no other region shares must lie inside exactly the
  // region's ancestors.
  std::vector<std::array<double, 4>> box(cs.regions.size());
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    double a = 1e300, b = -1e300, c = 1e300, d = -1e300;
    for (const Vec2& v : cs.regions[r].outline) {
      a = std::min(a, v.x); b = std::max(b, v.x); c = std::min(c, v.z); d = std::max(d, v.z);
    }
    box[r] = {a, b, c, d};
  }
  // Spatial bins over x for region boxes.
  const double bin = std::max((xmax - xmin) / 512.0, 1e-6);
  std::vector<std::vector<std::size_t>> bins(513);
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const auto b0 = static_cast<std::size_t>((box[r][0] - xmin) / bin);
    const auto b1 = static_cast<std::size_t>((box[r][1] - xmin) / bin);
    for (std::size_t k = b0; k <= std::min<std::size_t>(b1, 512); ++k) bins[k].push_back(r);
  }
  // Large outlines get an index of their edges by x (vertical-ray point-in-polygon).
  struct EdgeIndex {
    double x0 = 0, dx = 1;
    std::vector<std::vector<std::uint32_t>> bins;
  };
  std::vector<EdgeIndex> index(cs.regions.size());
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const auto& o = cs.regions[r].outline;
    if (o.size() <= 64) continue;
    EdgeIndex& ix = index[r];
    const std::size_t nb = std::max<std::size_t>(8, o.size() / 4);
    ix.x0 = box[r][0];
    ix.dx = std::max((box[r][1] - box[r][0]) / static_cast<double>(nb), 1e-9);
    ix.bins.assign(nb + 1, {});
    for (std::size_t i = 0; i < o.size(); ++i) {
      const Vec2 a = o[i], b = o[(i + 1) % o.size()];
      const auto k0 = static_cast<std::size_t>((std::min(a.x, b.x) - ix.x0) / ix.dx);
      const auto k1 = std::min(nb, static_cast<std::size_t>((std::max(a.x, b.x) - ix.x0) / ix.dx));
      for (std::size_t k = k0; k <= k1; ++k) ix.bins[k].push_back(static_cast<std::uint32_t>(i));
    }
  }
  // 0: outside, 1: inside, 2: on the boundary (a shared vertex or edge).
  auto locate = [&](Vec2 q, std::size_t r) -> int {
    const auto& o = cs.regions[r].outline;
    auto edge_test = [&](std::size_t i, bool& inside) -> bool {
      const Vec2 a = o[i], b = o[(i + 1) % o.size()];
      if (a == q) return true;
      const Vec2 d = b - a;
      const double len = norm(d);
      if (len > 0.0 && std::abs(cross(d, q - a)) / len <= 1e-7 * (1.0 + len)) {
        const double t = dot(q - a, d) / (len * len);
        if (t >= -1e-12 && t <= 1.0 + 1e-12) return true;
      }
      // Vertical ray upward from q.
      if ((a.x > q.x) != (b.x > q.x)) {
        const double z = a.z + (q.x - a.x) / (b.x - a.x) * (b.z - a.z);
        if (z > q.z) inside = !inside;
      }
      return false;
    };
    bool inside = false;
    if (index[r].bins.empty()) {
      for (std::size_t i = 0; i < o.size(); ++i) if (edge_test(i, inside)) return 2;
    } else {
      const EdgeIndex& ix = index[r];
      const auto k = std::min(ix.bins.size() - 1, static_cast<std::size_t>(std::max(0.0, (q.x - ix.x0) / ix.dx)));
      for (std::uint32_t i : ix.bins[k]) if (edge_test(i, inside)) return 2;
    }
    return inside ? 1 : 0;
  };
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const auto& o = cs.regions[r].outline;
    // Test point: a vertex of r on no other region's boundary.
    for (std::size_t vi = 0; vi < o.size(); vi += std::max<std::size_t>(1, o.size() / 7)) {
      const Vec2 q = o[vi];
      const auto bq = std::min<std::size_t>(static_cast<std::size_t>((q.x - xmin) / bin), 512);
      bool shared = false;
      std::vector<int> inside;
      for (std::size_t other : bins[bq]) {
        if (other == r) continue;
        const auto& bb = box[other];
        if (q.x < bb[0] || q.x > bb[1] || q.z < bb[2] || q.z > bb[3]) continue;
        const int where = locate(q, other);
        if (where == 2) { shared = true; break; }
        if (where == 1) inside.push_back(static_cast<int>(other));
      }
      if (shared) continue;
      std::vector<int> ancestors;
      for (int p = cs.regions[r].parent; p >= 0; p = cs.regions[static_cast<std::size_t>(p)].parent) {
        ancestors.push_back(p);
      }
      std::sort(inside.begin(), inside.end());
      std::sort(ancestors.begin(), ancestors.end());
      if (inside != ancestors) {
        std::ostringstream m;
        m << "region " << r << " (" << role_name(cs.regions[r].role) << ") is not properly nested: "
          << "its vertex (" << q.x << ", " << q.z << ") lies in " << inside.size()
          << " region(s), expected its " << ancestors.size() << " ancestor(s)";
        problem(m.str());
      }
      break;
    }
  }

  if (cs.layered) {
    const auto& bs = cs.layered->boundaries;
    if (bs.empty()) problem("layered model without boundaries");
    for (std::size_t i = 0; i < bs.size(); ++i) {
      if (bs[i].points.size() < 2) problem("boundary " + std::to_string(i) + " has < 2 points");
      if (!bs[i].fraction.empty() && bs[i].fraction.size() != bs[i].points.size()) {
        problem("boundary " + std::to_string(i) + ": fraction count differs from point count");
      }
      for (double f : bs[i].fraction) {
        if (!(f >= 0.0 && f <= 1.0)) { problem("boundary " + std::to_string(i) + ": fraction outside [0, 1]"); break; }
      }
      if (bs[i].closes >= 0 && (bs[i].closes <= static_cast<int>(i) || bs[i].closes >= static_cast<int>(bs.size()))) {
        problem("boundary " + std::to_string(i) + ": bad bracket");
      }
    }
    if (!bs.empty() && bs.back().points != cs.bottom) {
      problem("the last layer boundary is not the body's bottom: exact and reduced outlines differ");
    }
  }
  if (cs.crystal) {
    if (cs.crystal->regularity.size() != cs.top.size()) problem("regularity count differs from top vertex count");
    for (double q : cs.crystal->regularity) {
      if (!(q > 0.0 && q <= 1.0)) { problem("regularity outside (0, 1]"); break; }
    }
  }
  if (!cs.top_roughness_nm.empty() && cs.top_roughness_nm.size() != cs.top.size()) {
    problem("top roughness count differs from top vertex count");
  }
  return problems;
}

}  // namespace plumage
