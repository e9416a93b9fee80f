// The reduced layered model as region polygons (reduced_regions.hpp).
#pragma GCC optimize("fp-contract=off")
#include "plumage/reduced_regions.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "plumage/error.hpp"
#include "plumage/geometry.hpp"

namespace plumage {

namespace {

// The vertices of a boundary with x in [lo, hi]. Bands never get new vertices: neighbouring
// regions built from the same boundary then meet at common vertices (an interpolated cut point
// would sit on a neighbour's edge only up to rounding, and validate() would see a crossing),
// and bands of the same boundaries as the exact model coincide with it.
// A range reaching both ends keeps the whole boundary (arcs near rounded ends may step back
// in x).
Polyline part(const Polyline& line, double lo, double hi) {
  if (lo <= line.front().x && hi >= line.back().x) return line;
  return keep_x(line, lo, hi);
}

constexpr double kEndZone_nm = 3000.0;   // only vertices this close to a band's ends are tested
constexpr double kShrinkStep_nm = 15.0;

// True if v is a vertex of the outline (bands may share vertices with their parent).
bool on_outline(Vec2 v, const Polygon& outline) {
  return std::find(outline.begin(), outline.end(), v) != outline.end();
}

class Builder {
 public:
  Builder(const CrossSection& cs, const ReducedRegionOptions& o)
      : bs_(cs.layered->boundaries), options_(o) {
    regions_.push_back({band_polygon(cs.top, cs.bottom), cs.layered->below_top, RegionRole::body, -1});
  }

  // Boundaries [a, end) of one level; `terminal` ends the last layer (the bracket's closing
  // boundary, −1 at the outer level: below the last boundary is the ambient air).
  void level(int a, int end, int terminal, const Material& enclosing, int parent, bool inside_bracket) {
    // Items of this level: plain boundaries, and brackets [opener, closer].
    struct Item { int first, last; bool bracket; };
    std::vector<Item> items;
    for (int i = a; i < end;) {
      const LayerBoundary& b = bs_[static_cast<std::size_t>(i)];
      if (b.points.size() < 2) { ++i; continue; }
      if (b.closes > i && b.closes < end) {
        items.push_back({i, b.closes, true});
        i = b.closes + 1;
      } else {
        items.push_back({i, i, false});
        ++i;
      }
    }
    int owner = parent;  // where brackets go: the layer currently open, else the parent
    for (std::size_t k = 0; k < items.size(); ++k) {
      const Item& it = items[k];
      if (it.bracket) {
        bracket(it.first, it.last, owner);
        continue;
      }
      // A plain boundary: its layer reaches the next plain boundary of this level.
      owner = parent;
      int next = terminal;
      for (std::size_t q = k + 1; q < items.size(); ++q) {
        if (!items[q].bracket) { next = items[q].first; break; }
      }
      if (next < 0) continue;  // below the bottom: outside the body
      const LayerBoundary& upper = bs_[static_cast<std::size_t>(it.first)];
      if (upper.below.name() == enclosing.name() && upper.fraction.empty()) continue;
      const bool has_children = std::any_of(items.begin() + static_cast<std::ptrdiff_t>(k) + 1, items.end(),
                                             [&](const Item& x) { return x.bracket && x.first < next; });
      const RegionRole role = upper.below.kind() == Material::Kind::air
                                  ? (inside_bracket ? RegionRole::air_bubble : RegionRole::air_gap)
                              : upper.below.kind() == Material::Kind::mixture ? RegionRole::granular_layer
                                                                              : RegionRole::film;
      const int made = layer(upper, bs_[static_cast<std::size_t>(next)], role, parent, !has_children);
      if (made >= 0) owner = made;
    }
  }

  std::vector<Region> take() { return std::move(regions_); }

 private:
  void bracket(int opener, int closer, int parent) {
    const LayerBoundary& upper = bs_[static_cast<std::size_t>(opener)];
    const RegionRole role = upper.below.kind() == Material::Kind::melanin ? RegionRole::platelet : RegionRole::film;
    const int made = layer(upper, bs_[static_cast<std::size_t>(closer)], role, parent, false);
    if (made < 0) return;
    level(opener + 1, closer, closer, regions_[static_cast<std::size_t>(made)].material, made, true);
  }

  // Adds the band between two boundaries (material of `upper`); returns its region index, or
  // −1 when the boundaries do not overlap in x. With piecewise mixtures (and `may_split`) the
  // band becomes several slabs and the first slab's index is returned.
  int layer(const LayerBoundary& upper, const LayerBoundary& lower, RegionRole role, int parent, bool may_split) {
    double lo = std::max(upper.points.front().x, lower.points.front().x);
    double hi = std::min(upper.points.back().x, lower.points.back().x);
    if (!(hi > lo)) return -1;
    // Near the barbule's ends a boundary may leave the parent (an offset curve of a steep arch
    // end, the original outline under a lower cortex): shorten the band from the side where it
    // does, in steps, until every vertex lies inside the parent.
    // Boundaries that meet at both ends (a platelet, a chain of bubbles, a row of melanosomes)
    // already close a lens: kept whole, as in the exact model.
    const bool lens = upper.points.front() == lower.points.front() && upper.points.back() == lower.points.back();
    const Polygon& outer = regions_[static_cast<std::size_t>(parent)].outline;
    for (int attempt = 0; attempt < 400 && hi > lo && !lens; ++attempt) {
      const Polygon trial = band_polygon(part(upper.points, lo, hi), part(lower.points, lo, hi));
      bool left_out = false, right_out = false;
      const double mid = 0.5 * (lo + hi);
      for (const Vec2& v : trial) {
        if (v.x > lo + kEndZone_nm && v.x < hi - kEndZone_nm) continue;
        if (!point_in_polygon(v, outer) && !on_outline(v, outer)) (v.x < mid ? left_out : right_out) = true;
      }
      // The upper boundary must stay above the lower one (offset curves fold over each other
      // at steep ends), except where they meet at the band's ends.
      auto check_order = [&](const Polyline& line, const Polyline& other, bool line_is_upper) {
        for (const Vec2& v : line) {
          if (!(v.x > lo && v.x < hi) || (v.x > lo + kEndZone_nm && v.x < hi - kEndZone_nm)) continue;
          const double zo = z_at(other, v.x);
          if (line_is_upper ? !(v.z > zo) : !(v.z < zo)) (v.x < mid ? left_out : right_out) = true;
        }
      };
      check_order(upper.points, lower.points, true);
      check_order(lower.points, upper.points, false);
      // Within the range each boundary must be a graph over x (rounded row ends and arcs step
      // back in x; a closing segment there would cut through the neighbouring region).
      auto check_graph = [&](const Polyline& line) {
        for (std::size_t i = 0; i + 1 < line.size(); ++i) {
          const Vec2 a = line[i], b = line[i + 1];
          if (b.x > a.x) continue;  // a step back (or a vertical step) in x from a to b
          const double x0 = b.x, x1 = a.x;
          if (x1 >= lo && x0 <= std::min(mid, lo + kEndZone_nm)) left_out = true;
          if (x0 <= hi && x1 >= std::max(mid, hi - kEndZone_nm)) right_out = true;
        }
      };
      check_graph(upper.points);
      check_graph(lower.points);
      if (!left_out && !right_out) break;
      if (left_out) lo += kShrinkStep_nm;
      if (right_out) hi -= kShrinkStep_nm;
    }
    if (!(hi > lo)) return -1;
    const bool mixture = upper.below.kind() == Material::Kind::mixture && !upper.fraction.empty();
    const int index = static_cast<int>(regions_.size());
    auto add = [&](double a, double b, Material m) {
      Polygon outline = band_polygon(part(upper.points, a, b), part(lower.points, a, b));
      if (outline.size() < 3 || !(signed_area(outline) > 0.0)) return;
      regions_.push_back({std::move(outline), std::move(m), role, parent, ++layer_count_, 1, b - a});
    };
    if (!mixture) {
      add(lo, hi, upper.below);
    } else if (options_.mixture == ReducedRegionOptions::Mixture::mean || !may_split) {
      const double mean = std::accumulate(upper.fraction.begin(), upper.fraction.end(), 0.0) /
                          static_cast<double>(upper.fraction.size());
      add(lo, hi, upper.below.with_fraction(mean));
    } else {
      // Slabs cut at vertices of both boundaries (the upper's vertex nearest to each cut and
      // the lower's vertex nearest to that): adjacent slabs share their closing edge exactly.
      const Polyline up = part(upper.points, lo, hi), down = part(lower.points, lo, hi);
      if (up.size() < 2 || down.size() < 2) return -1;
      // Fractions of the kept upper vertices.
      const auto first = static_cast<std::size_t>(
          std::find(upper.points.begin(), upper.points.end(), up.front()) - upper.points.begin());
      const int pieces = std::max(1, static_cast<int>(std::lround((hi - lo) / options_.piece_nm)));
      auto nearest = [](const Polyline& line, double x) {
        auto it = std::lower_bound(line.begin(), line.end(), x, [](const Vec2& q, double v) { return q.x < v; });
        std::size_t j = static_cast<std::size_t>(it - line.begin());
        if (j >= line.size()) j = line.size() - 1;
        if (j > 0 && x - line[j - 1].x < line[j].x - x) --j;
        return j;
      };
      std::vector<std::size_t> cut_up{0}, cut_down{0};
      for (int k = 1; k < pieces; ++k) {
        const std::size_t iu = nearest(up, lo + (hi - lo) * k / pieces);
        const std::size_t id = nearest(down, up[iu].x);
        if (iu <= cut_up.back() || id <= cut_down.back() || iu + 1 >= up.size() || id + 1 >= down.size()) continue;
        cut_up.push_back(iu);
        cut_down.push_back(id);
      }
      cut_up.push_back(up.size() - 1);
      cut_down.push_back(down.size() - 1);
      for (std::size_t k = 0; k + 1 < cut_up.size(); ++k) {
        const Polyline u(up.begin() + static_cast<std::ptrdiff_t>(cut_up[k]),
                         up.begin() + static_cast<std::ptrdiff_t>(cut_up[k + 1]) + 1);
        const Polyline d(down.begin() + static_cast<std::ptrdiff_t>(cut_down[k]),
                         down.begin() + static_cast<std::ptrdiff_t>(cut_down[k + 1]) + 1);
        double sum = 0.0;
        for (std::size_t v = cut_up[k]; v <= cut_up[k + 1]; ++v) sum += upper.fraction[first + v];
        const double f = sum / static_cast<double>(cut_up[k + 1] - cut_up[k] + 1);
        Polygon outline = band_polygon(u, d);
        if (outline.size() < 3 || !(signed_area(outline) > 0.0)) continue;
        const double size = u.back().x - u.front().x;
        regions_.push_back({std::move(outline), upper.below.with_fraction(f), role, parent, ++layer_count_, 1, size});
      }
    }
    return static_cast<int>(regions_.size()) > index ? index : -1;
  }

  const std::vector<LayerBoundary>& bs_;
  ReducedRegionOptions options_;
  std::vector<Region> regions_;
  int layer_count_ = -1;
};

}  // namespace

std::vector<Region> reduced_regions(const CrossSection& section, const ReducedRegionOptions& options) {
  if (!section.layered) {
    throw Error("reduced_regions: " + section.label +
                " has no layered model (crystal-type barbules and validation shapes have none)");
  }
  if (!(options.piece_nm > 0.0)) throw Error("reduced_regions: piece_nm must be > 0");
  Builder builder(section, options);
  const auto& bs = section.layered->boundaries;
  builder.level(0, static_cast<int>(bs.size()), -1, section.layered->below_top, 0, false);
  return builder.take();
}

CrossSection with_reduced_regions(const CrossSection& section, const ReducedRegionOptions& options) {
  CrossSection out = section;
  out.regions = reduced_regions(section, options);
  out.melanosomes.clear();  // the reduced model has no individual melanosomes
  out.label += " (reduced layers)";
  return out;
}

}  // namespace plumage
