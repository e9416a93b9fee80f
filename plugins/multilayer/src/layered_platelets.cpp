// layered_barbule, model platelets (type 4 of spec geometry-and-brdf §1.3): layers of hollow
// melanin platelets, each a rounded box with a row of air bubbles along its midline.
// Two models of the bubbles (paper §4.2, Fig. 4(b) and the three-way test of Fig. 8): the exact
// geometry (the regions, for the full-wave BEM) has each bubble as its own ellipse, separated from
// its neighbours by a melanin membrane; the reduced layered model joins the bubbles of a platelet
// into one chain (neighbouring ellipses cut at ±π/12 and joined), a connected air layer.
// Random draws: "platelets.layers" (air cores and spacers), "platelets.platelets" (lengths and
// gaps per layer), "platelets.bubbles" (bubble lengths and heights per platelet), in that order.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <cmath>
#include <utility>

#include "layered_barbule.hpp"
#include "layered_shapes.hpp"
#include "plumage/geometry.hpp"

namespace plumage::multilayer {

using namespace detail;

namespace {

// The layer thicknesses of one instance: the air core of each layer, the keratin spacers between
// layers, and the barbule thickness T they add up to (cortex, walls, cores, spacers).
struct PlateletStack {
  std::vector<double> air, spacer;
  double thickness_nm = 0;
};

PlateletStack draw_stack(const LayeredParams& p, RandomStream& layer_rng) {
  const int n = p.layers;
  PlateletStack s;
  s.air.resize(static_cast<std::size_t>(n));
  s.spacer.resize(static_cast<std::size_t>(std::max(0, n - 1)));
  double air1 = p.first_layer_nm - 2.0 * p.wall_nm;
  if (air1 < 20.0) air1 += 10.0;
  for (int i = 0; i < n; ++i) {
    s.air[static_cast<std::size_t>(i)] =
        i == 0 ? air1
        : i == 1 ? p.blend * air1 + (1.0 - p.blend) * p.bubble_nm
                 : p.bubble_nm * layer_rng.uniform(p.bubble_jitter.first, p.bubble_jitter.second);
  }
  for (int i = 0; i + 1 < n; ++i) {
    s.spacer[static_cast<std::size_t>(i)] =
        p.spacer_nm * (static_cast<std::size_t>(i) < p.first_spacers.size()
                           ? p.first_spacers[static_cast<std::size_t>(i)]
                           : layer_rng.uniform(p.spacer_jitter.first, p.spacer_jitter.second));
  }
  double T = 2.0 * p.cortex_nm;
  for (int i = 0; i < n; ++i) T += 2.0 * p.wall_nm + s.air[static_cast<std::size_t>(i)];
  for (double sp : s.spacer) T += sp;
  s.thickness_nm = T;
  return s;
}

// The x-extents [xa, xb] of the platelets of one layer across the interior [−xl, xl]: the
// coverage of the layer split into platelets of jittered length, the rest into end gaps and
// jittered gaps between them.
std::vector<std::pair<double, double>> draw_platelets(const LayeredParams& p, int layer, double xl,
                                                      RandomStream& plate_rng) {
  const double extent = 2.0 * xl;
  const double total = (layer == 0 ? p.coverage[0] : p.coverage[1]) * extent;
  const int count = std::max(1, static_cast<int>(std::lround(total / p.platelet_nm)));
  std::vector<double> lengths(static_cast<std::size_t>(count));
  for (double& l : lengths) l = p.platelet_nm * plate_rng.uniform(p.length_jitter.first, p.length_jitter.second);
  renormalise(lengths, total);
  const double end_l = plate_rng.uniform(p.end_gap_nm.first, p.end_gap_nm.second);
  const double end_r = plate_rng.uniform(p.end_gap_nm.first, p.end_gap_nm.second);
  const double rest = extent - total - end_l - end_r;
  std::vector<double> gaps(static_cast<std::size_t>(std::max(0, count - 1)));
  for (double& g : gaps) g = plate_rng.uniform(p.gap_jitter.first, p.gap_jitter.second);
  renormalise(gaps, rest);
  std::vector<std::pair<double, double>> extents;
  double x = -xl + end_l;
  for (int k = 0; k < count; ++k) {
    const double xa = x, xb = x + lengths[static_cast<std::size_t>(k)];
    x = xb + (k + 1 < count ? gaps[static_cast<std::size_t>(k)] : 0.0);
    extents.emplace_back(xa, xb);
  }
  return extents;
}

// Upper and lower outline of a closed band (their end vertices shared).
struct Band {
  Polyline upper, lower;
};

// One platelet's box: the layer's guides `up` and `down` between rounded ends, half circles of
// radius rr centred on the midline `mid`.
Band platelet_box(const Polyline& up, const Polyline& down, const Polyline& mid, double xa, double xb, double rr,
                  double arc_step) {
  auto end_center = [&](double xc) { return Vec2{xc, z_at(mid, xc)}; };
  const Vec2 cl = end_center(xa + rr), cr = end_center(xb - rr);
  Band box;
  append_arc(box.upper, cl, rr, {1, 0}, {0, 1}, kPi, 0.5 * kPi, arc_step);
  for (const Vec2& q : clip_x(up, xa + rr, xb - rr)) box.upper.push_back(q);
  append_arc(box.upper, cr, rr, {1, 0}, {0, 1}, 0.5 * kPi, 0.0, arc_step);
  append_arc(box.lower, cl, rr, {1, 0}, {0, -1}, kPi, 0.5 * kPi, arc_step);
  for (const Vec2& q : clip_x(down, xa + rr, xb - rr)) box.lower.push_back(q);
  append_arc(box.lower, cr, rr, {1, 0}, {0, -1}, 0.5 * kPi, 0.0, arc_step);
  box.upper = make_monotone(box.upper);
  box.lower = make_monotone(box.lower);
  box.lower.front() = box.upper.front();
  box.lower.back() = box.upper.back();
  return box;
}

// The row of air bubbles inside a platelet [xa, xb] with air core `a`: ellipses along the
// midline, as one band cut where neighbours meet (π/12 from the axis: the layered model) and each
// whole (the exact regions); and their count.
struct Bubbles {
  Band band;
  std::vector<Polygon> each;
  int count = 0;
};

Bubbles platelet_bubbles(const LayeredParams& p, const Polyline& mid, double xa, double xb, double a,
                         RandomStream& bubble_rng) {
  const double len = xb - xa;
  const int nb = std::max(1, static_cast<int>(std::lround((len - 2.0 * p.wall_nm + p.membrane_nm) /
                                                          (a + p.membrane_nm))));
  std::vector<double> bl(static_cast<std::size_t>(nb));
  for (double& b : bl) b = p.bubble_length_jitter.first +
                           (p.bubble_length_jitter.second - p.bubble_length_jitter.first) * bubble_rng.uniform();
  renormalise(bl, len - 2.0 * p.wall_nm - (nb - 1) * p.membrane_nm);
  Bubbles out;
  out.count = nb;
  Polyline& bu = out.band.upper;
  Polyline& bd = out.band.lower;
  double bx = xa + p.wall_nm;
  const double cut = kPi / 12.0;
  const double cos_cut = std::cos(cut), sin_cut = std::sin(cut);
  for (int j = 0; j < nb; ++j) {
    const double l = bl[static_cast<std::size_t>(j)];
    const double height = a > 30.0 ? a + bubble_rng.uniform(-p.bubble_height_jitter_nm, p.bubble_height_jitter_nm) : a;
    const double xc = bx + 0.5 * l;
    const Vec2 c{xc, z_at(mid, xc)};
    Vec2 t{l, z_at(mid, xc + 0.5 * l) - z_at(mid, xc - 0.5 * l)};  // local midline direction
    t = (1.0 / norm(t)) * t;
    const Vec2 nn{-t.z, t.x};
    const double a0 = j == 0 ? kPi : kPi - cut, a1 = j + 1 == nb ? 0.0 : cut;
    // Ellipse arcs: scale the unit-circle arc to semi-axes (l/2, height/2).
    auto ellipse_arc = [&](Polyline& line, double sg) {
      const int kk = std::max(4, static_cast<int>(std::ceil((a0 - a1) * 0.5 * std::max(l, height) / p.arc_step_nm)));
      const double da = (a1 - a0) / kk, cd = std::cos(da), sd = std::sin(da);
      double ca = j == 0 ? -1.0 : -cos_cut, sa = j == 0 ? 0.0 : sin_cut;  // cos, sin of a0
      for (int q = 0; q <= kk; ++q) {
        line.push_back(c + (0.5 * l * ca) * t + (sg * 0.5 * height * sa) * nn);
        const double nc = ca * cd - sa * sd;
        sa = sa * cd + ca * sd;
        ca = nc;
      }
    };
    ellipse_arc(bu, 1.0);
    ellipse_arc(bd, -1.0);
    // The whole ellipse, counter-clockwise (t ≈ +x, nn ≈ +z), at the arcs' vertex spacing.
    const int kw = std::max(8, static_cast<int>(std::ceil(kPi * std::max(l, height) / p.arc_step_nm)));
    Polygon& e = out.each.emplace_back();
    for (int q = 0; q < kw; ++q) {
      const double ang = 2.0 * kPi * q / kw;
      e.push_back(c + (0.5 * l * std::cos(ang)) * t + (0.5 * height * std::sin(ang)) * nn);
    }
    bx += l + p.membrane_nm;
  }
  bd.front() = bu.front();
  bd.back() = bu.back();
  return out;
}

}  // namespace

// Type 4: layers of hollow melanin platelets (spec §1.3(4)).
void LayeredBarbule::build_platelets(CrossSection& cs) const {
  RandomStream layer_rng(cs.seed, "platelets.layers"), plate_rng(cs.seed, "platelets.platelets");
  RandomStream bubble_rng(cs.seed, "platelets.bubbles");
  const int n = p_.layers;
  const PlateletStack stack = draw_stack(p_, layer_rng);
  const double T = stack.thickness_nm;

  Outline o = make_outline(p_.outline, cs.seed, T);
  const Polyline top = o.top, bottom = o.bottom;
  const double xl = o.interior_half_width;
  finish_outline(cs, std::move(o));
  cs.bottom = bottom;
  // Guide at fractional depth h: (1 − h/T)·top + (h/T)·bottom, on the top's x grid.
  auto guide = [&](double h) {
    Polyline g(top.size());
    const double w = h / T;
    for (std::size_t i = 0; i < top.size(); ++i) g[i] = {top[i].x, (1.0 - w) * top[i].z + w * bottom[i].z};
    return g;
  };
  LayeredModel m;
  m.below_top = p_.body;
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), p_.body, RegionRole::body});
  const Material melanin = Material::melanin(), air_m = Material::air();
  double h1 = p_.cortex_nm;
  for (int layer = 0; layer < n; ++layer) {
    const double a = stack.air[static_cast<std::size_t>(layer)];
    const double h2 = h1 + 2.0 * p_.wall_nm + a;
    const Polyline up = guide(h1), down = guide(h2), mid = guide(0.5 * (h1 + h2));
    const double rr = 0.5 * (h2 - h1);
    for (const auto& [xa, xb] : draw_platelets(p_, layer, xl, plate_rng)) {
      Band box = platelet_box(up, down, mid, xa, xb, rr, p_.arc_step_nm);
      Bubbles bubbles = platelet_bubbles(p_, mid, xa, xb, a, bubble_rng);
      const int base = static_cast<int>(m.boundaries.size());
      m.boundaries.push_back({box.upper, melanin, {}, base + 3});
      m.boundaries.push_back({bubbles.band.upper, air_m, {}, base + 2});
      m.boundaries.push_back({bubbles.band.lower, melanin, {}, -1});
      m.boundaries.push_back({box.lower, p_.body, {}, -1});
      const int plate_index = static_cast<int>(cs.regions.size());
      cs.regions.push_back({band_polygon(box.upper, box.lower), melanin, RegionRole::platelet, 0, layer, 1, xb - xa});
      for (Polygon& bubble : bubbles.each) {
        cs.regions.push_back({std::move(bubble), air_m, RegionRole::air_bubble, plate_index, layer, 1, a});
      }
    }
    h1 = h2 + (layer + 1 < n ? stack.spacer[static_cast<std::size_t>(layer)] : 0.0);
  }
  m.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(m);
}

}  // namespace plumage::multilayer
