// Geometric validity of a cross section (cross_section.hpp, validate()): the checks a solver relies
// on, in the order a failure makes the later ones meaningless — structure (counts, orientation,
// finite vertices), crossings of any two boundaries, nesting of every region inside exactly its
// ancestors, and the consistency of the reduced models with the exact outline.
// No fused multiply-add contraction: orientation tests must decide the same on every machine.
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <sstream>

#include "plumage/cross_section.hpp"
#include "plumage/error.hpp"
#include "plumage/geometry.hpp"

namespace plumage {

namespace {

// At most this many problems are listed: the first ones say what is wrong.
constexpr std::size_t kMaxProblems = 20;

class Problems {
 public:
  void add(const std::string& message) {
    if (list_.size() < kMaxProblems) list_.push_back(message);
  }
  bool empty() const { return list_.empty(); }
  std::vector<std::string> take() { return std::move(list_); }

 private:
  std::vector<std::string> list_;
};

struct Segment {
  Vec2 a, b;
  int region;  // index of the region whose outline holds the segment
  std::size_t index;
  std::size_t count;  // vertices in the owner (for adjacency)
  bool closed;
};

struct Extent {
  double xmin = 1e300, xmax = -1e300, zmin = 1e300, zmax = -1e300;
};

int orient(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}

// True if the segments intersect at a point interior to both (a proper crossing). Touching at
// endpoints and collinear contact are allowed: neighbouring regions share boundaries.
bool bad_intersection(const Segment& s, const Segment& u) {
  const bool same_ends = (s.a == u.a && s.b == u.b) || (s.a == u.b && s.b == u.a);
  if (same_ends) return false;  // a shared edge
  if (s.a == u.a || s.a == u.b || s.b == u.a || s.b == u.b) return false;  // a shared vertex
  const int o1 = orient(s.a, s.b, u.a), o2 = orient(s.a, s.b, u.b);
  const int o3 = orient(u.a, u.b, s.a), o4 = orient(u.a, u.b, s.b);
  return o1 * o2 < 0 && o3 * o4 < 0;
}

// Counts, orientation, parents and finite vertices of the top surface and every region.
void check_structure(const CrossSection& cs, Problems& problems) {
  if (cs.top.size() < 3) problems.add("top surface has fewer than 3 vertices");
  for (std::size_t i = 1; i < cs.top.size(); ++i) {
    if (!(cs.top[i].x > cs.top[i - 1].x)) {
      std::ostringstream m;
      m << "top surface not monotone in x at vertex " << i;
      problems.add(m.str());
      break;
    }
  }
  for (const Vec2& v : cs.top) {
    if (!std::isfinite(v.x) || !std::isfinite(v.z)) {
      problems.add("non-finite top vertex");
      break;
    }
  }
  if (cs.regions.empty()) {
    problems.add("no regions");
    return;
  }
  if (cs.regions[0].parent != -1) problems.add("region 0 (body) has a parent");
  if (cs.regions[0].outline != band_polygon(cs.top, cs.bottom)) {
    problems.add("body outline is not band_polygon(top, bottom): exact and reduced outlines differ");
  }
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const Region& g = cs.regions[r];
    if (g.outline.size() < 3) problems.add("region " + std::to_string(r) + " has < 3 vertices");
    if (g.parent >= static_cast<int>(r)) problems.add("region " + std::to_string(r) + " precedes its parent");
    if (r > 0 && g.parent < 0) problems.add("region " + std::to_string(r) + " has no parent");
    if (!(signed_area(g.outline) > 0.0)) problems.add("region " + std::to_string(r) + " is not counter-clockwise");
    for (const Vec2& v : g.outline) {
      if (!std::isfinite(v.x) || !std::isfinite(v.z)) {
        problems.add("non-finite vertex in region " + std::to_string(r));
        break;
      }
    }
  }
}

std::vector<Segment> region_segments(const CrossSection& cs, Extent& extent) {
  std::vector<Segment> segs;
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const auto& o = cs.regions[r].outline;
    for (std::size_t i = 0; i < o.size(); ++i) {
      const Vec2 a = o[i], b = o[(i + 1) % o.size()];
      segs.push_back({a, b, static_cast<int>(r), i, o.size(), true});
      extent.xmin = std::min(extent.xmin, a.x);
      extent.xmax = std::max(extent.xmax, a.x);
      extent.zmin = std::min(extent.zmin, a.z);
      extent.zmax = std::max(extent.zmax, a.z);
    }
  }
  return segs;
}

// Every pair of region edges that cross, found through a uniform grid of cells about two mean
// segment lengths wide (each segment falls in a few cells); one report per pair of regions.
void check_crossings(const std::vector<Segment>& segs, const Extent& extent, Problems& problems) {
  double mean_len = 0.0;
  for (const auto& sg : segs) mean_len += norm(sg.b - sg.a);
  mean_len /= static_cast<double>(std::max<std::size_t>(1, segs.size()));
  const double cell = std::max({2.0 * mean_len, (extent.xmax - extent.xmin) / 65536.0, 1e-6});
  const long long nx = static_cast<long long>((extent.xmax - extent.xmin) / cell) + 1;
  // (cell << 24 | segment) in one 64-bit word: sorting plain integers is several times faster.
  std::vector<std::uint64_t> binned;
  binned.reserve(segs.size() * 3);
  if (segs.size() >= (1u << 24)) throw Error("validate: too many segments");
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const auto& s = segs[k];
    const long long x0 = static_cast<long long>((std::min(s.a.x, s.b.x) - extent.xmin) / cell);
    const long long x1 = static_cast<long long>((std::max(s.a.x, s.b.x) - extent.xmin) / cell);
    const long long z0 = static_cast<long long>((std::min(s.a.z, s.b.z) - extent.zmin) / cell);
    const long long z1 = static_cast<long long>((std::max(s.a.z, s.b.z) - extent.zmin) / cell);
    for (long long zi = z0; zi <= z1; ++zi)
      for (long long xi = x0; xi <= x1; ++xi)
        binned.push_back((static_cast<std::uint64_t>(zi * nx + xi) << 24) | static_cast<std::uint64_t>(k));
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
          m << "boundaries cross: region " << s.region << " edge " << s.index << " and region " << u.region
            << " edge " << u.index << " near (" << s.a.x << ", " << s.a.z << ") nm";
          problems.add(m.str());
        }
      }
    }
    g0 = g1;
  }
}

// Point location in the regions' outlines: bounding boxes, x-bins of boxes over the section, and
// for large outlines an index of their edges by x (vertical-ray point-in-polygon).
class RegionLocator {
 public:
  RegionLocator(const CrossSection& cs, const Extent& extent)
      : cs_(cs), xmin_(extent.xmin), bin_(std::max((extent.xmax - extent.xmin) / 512.0, 1e-6)) {
    box_.resize(cs.regions.size());
    for (std::size_t r = 0; r < cs.regions.size(); ++r) {
      double a = 1e300, b = -1e300, c = 1e300, d = -1e300;
      for (const Vec2& v : cs.regions[r].outline) {
        a = std::min(a, v.x), b = std::max(b, v.x), c = std::min(c, v.z), d = std::max(d, v.z);
      }
      box_[r] = {a, b, c, d};
    }
    bins_.resize(513);
    for (std::size_t r = 0; r < cs.regions.size(); ++r) {
      const auto b0 = static_cast<std::size_t>((box_[r][0] - xmin_) / bin_);
      const auto b1 = static_cast<std::size_t>((box_[r][1] - xmin_) / bin_);
      for (std::size_t k = b0; k <= std::min<std::size_t>(b1, 512); ++k) bins_[k].push_back(r);
    }
    index_.resize(cs.regions.size());
    for (std::size_t r = 0; r < cs.regions.size(); ++r) build_edge_index(r);
  }

  // The regions other than `self` whose bounding box holds q, from q's x-bin.
  const std::vector<std::size_t>& candidates(Vec2 q) const {
    return bins_[std::min<std::size_t>(static_cast<std::size_t>((q.x - xmin_) / bin_), 512)];
  }
  bool in_box(Vec2 q, std::size_t r) const {
    const auto& bb = box_[r];
    return !(q.x < bb[0] || q.x > bb[1] || q.z < bb[2] || q.z > bb[3]);
  }
  // 0: outside, 1: inside, 2: on the boundary (a shared vertex or edge).
  int locate(Vec2 q, std::size_t r) const {
    const auto& o = cs_.regions[r].outline;
    bool inside = false;
    auto edge_test = [&](std::size_t i) -> bool {
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
    if (index_[r].bins.empty()) {
      for (std::size_t i = 0; i < o.size(); ++i)
        if (edge_test(i)) return 2;
    } else {
      const EdgeIndex& ix = index_[r];
      const auto k = std::min(ix.bins.size() - 1, static_cast<std::size_t>(std::max(0.0, (q.x - ix.x0) / ix.dx)));
      for (std::uint32_t i : ix.bins[k])
        if (edge_test(i)) return 2;
    }
    return inside ? 1 : 0;
  }

 private:
  struct EdgeIndex {
    double x0 = 0, dx = 1;
    std::vector<std::vector<std::uint32_t>> bins;
  };

  void build_edge_index(std::size_t r) {
    const auto& o = cs_.regions[r].outline;
    if (o.size() <= 64) return;
    EdgeIndex& ix = index_[r];
    const std::size_t nb = std::max<std::size_t>(8, o.size() / 4);
    ix.x0 = box_[r][0];
    ix.dx = std::max((box_[r][1] - box_[r][0]) / static_cast<double>(nb), 1e-9);
    ix.bins.assign(nb + 1, {});
    for (std::size_t i = 0; i < o.size(); ++i) {
      const Vec2 a = o[i], b = o[(i + 1) % o.size()];
      const auto k0 = static_cast<std::size_t>((std::min(a.x, b.x) - ix.x0) / ix.dx);
      const auto k1 = std::min(nb, static_cast<std::size_t>((std::max(a.x, b.x) - ix.x0) / ix.dx));
      for (std::size_t k = k0; k <= k1; ++k) ix.bins[k].push_back(static_cast<std::uint32_t>(i));
    }
  }

  const CrossSection& cs_;
  double xmin_, bin_;
  std::vector<std::array<double, 4>> box_;
  std::vector<std::vector<std::size_t>> bins_;
  std::vector<EdgeIndex> index_;
};

// Nesting: a vertex of each region that no other region shares must lie inside exactly the
// region's ancestors.
void check_nesting(const CrossSection& cs, const Extent& extent, Problems& problems) {
  const RegionLocator locator(cs, extent);
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const auto& o = cs.regions[r].outline;
    for (std::size_t vi = 0; vi < o.size(); vi += std::max<std::size_t>(1, o.size() / 7)) {
      const Vec2 q = o[vi];
      bool shared = false;
      std::vector<int> inside;
      for (std::size_t other : locator.candidates(q)) {
        if (other == r || !locator.in_box(q, other)) continue;
        const int where = locator.locate(q, other);
        if (where == 2) {
          shared = true;
          break;
        }
        if (where == 1) inside.push_back(static_cast<int>(other));
      }
      if (shared) continue;  // try the next test vertex
      std::vector<int> ancestors;
      for (int p = cs.regions[r].parent; p >= 0; p = cs.regions[static_cast<std::size_t>(p)].parent) {
        ancestors.push_back(p);
      }
      std::sort(inside.begin(), inside.end());
      std::sort(ancestors.begin(), ancestors.end());
      if (inside != ancestors) {
        std::ostringstream m;
        m << "region " << r << " (" << role_name(cs.regions[r].role) << ") is not properly nested: "
          << "its vertex (" << q.x << ", " << q.z << ") lies in " << inside.size() << " region(s), expected its "
          << ancestors.size() << " ancestor(s)";
        problems.add(m.str());
      }
      break;
    }
  }
}

// The reduced models (layer boundaries, crystal regularity, roughness) against the exact one.
void check_reduced_models(const CrossSection& cs, Problems& problems) {
  if (cs.layered) {
    const auto& bs = cs.layered->boundaries;
    if (bs.empty()) problems.add("layered model without boundaries");
    for (std::size_t i = 0; i < bs.size(); ++i) {
      if (bs[i].points.size() < 2) problems.add("boundary " + std::to_string(i) + " has < 2 points");
      if (!bs[i].fraction.empty() && bs[i].fraction.size() != bs[i].points.size()) {
        problems.add("boundary " + std::to_string(i) + ": fraction count differs from point count");
      }
      for (double f : bs[i].fraction) {
        if (!(f >= 0.0 && f <= 1.0)) {
          problems.add("boundary " + std::to_string(i) + ": fraction outside [0, 1]");
          break;
        }
      }
      if (bs[i].closes >= 0 && (bs[i].closes <= static_cast<int>(i) || bs[i].closes >= static_cast<int>(bs.size()))) {
        problems.add("boundary " + std::to_string(i) + ": bad bracket");
      }
    }
    if (!bs.empty() && bs.back().points != cs.bottom) {
      problems.add("the last layer boundary is not the body's bottom: exact and reduced outlines differ");
    }
  }
  if (cs.crystal) {
    if (cs.crystal->regularity.size() != cs.top.size()) problems.add("regularity count differs from top vertex count");
    for (double q : cs.crystal->regularity) {
      if (!(q > 0.0 && q <= 1.0)) {
        problems.add("regularity outside (0, 1]");
        break;
      }
    }
  }
  if (!cs.top_roughness_nm.empty() && cs.top_roughness_nm.size() != cs.top.size()) {
    problems.add("top roughness count differs from top vertex count");
  }
}

}  // namespace

std::vector<std::string> validate(const CrossSection& cs) {
  Problems problems;
  check_structure(cs, problems);
  if (cs.regions.empty() || !problems.empty()) return problems.take();
  Extent extent;
  const std::vector<Segment> segs = region_segments(cs, extent);
  check_crossings(segs, extent, problems);
  if (!problems.empty()) return problems.take();
  check_nesting(cs, extent, problems);
  check_reduced_models(cs, problems);
  return problems.take();
}

}  // namespace plumage
