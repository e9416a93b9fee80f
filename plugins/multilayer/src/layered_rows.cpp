// layered_barbule, model melanosome_rows (types 2–3 of spec geometry-and-brdf §1.3): rows of
// touching melanosomes under the top and over the bottom around a mixed core.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <cmath>

#include "layered_barbule.hpp"
#include "layered_shapes.hpp"
#include "plumage/geometry.hpp"

namespace plumage::multilayer {

using namespace detail;

namespace {

// A row of touching discs along a guide and its necklace outline (spec §1.1(e)).
struct Necklace {
  Polyline upper, lower;
  std::vector<Disc> discs;
};

Necklace grow_row(const Polyline& guide, double mean_d, double jitter, double neck_fraction,
                  double arc_step, int row, RandomStream& rng) {
  Necklace nk;
  ArcLengthCurve curve(guide);
  const double L = curve.length();
  std::vector<double> s_c, d;
  double s = 0.0;
  double prev = 0.0;
  for (;;) {
    const double dn = mean_d * rng.uniform(1.0 - jitter, 1.0 + jitter);
    const double next = s_c.empty() ? 0.5 * dn : s + 0.5 * (prev + dn);
    if (next + 0.5 * dn > L) break;
    s_c.push_back(next);
    d.push_back(dn);
    s = next;
    prev = dn;
  }
  const std::size_t n = s_c.size();
  if (n == 0) return nk;
  const std::size_t per_disc = static_cast<std::size_t>(std::ceil(kPi * 0.5 * mean_d * (1.0 + jitter) / arc_step)) + 4;
  nk.upper.reserve(n * per_disc);
  nk.lower.reserve(n * per_disc);
  nk.discs.reserve(n);
  const double delta = 0.5 * mean_d;
  std::vector<Vec2> c(n), t(n), nn(n);
  std::size_t h_c = 0, h_plus = 0, h_minus = 0;  // walking hints along the guide
  for (std::size_t i = 0; i < n; ++i) {
    c[i] = curve.point(s_c[i], h_c);
    Vec2 tg = curve.point(std::min(L, s_c[i] + delta), h_plus) - curve.point(std::max(0.0, s_c[i] - delta), h_minus);
    tg = (1.0 / norm(tg)) * tg;
    t[i] = tg;
    nn[i] = {-tg.z, tg.x};
    nk.discs.push_back({c[i], d[i], row});
  }
  for (int side = 0; side < 2; ++side) {
    Polyline& out = side == 0 ? nk.upper : nk.lower;
    const double sg = side == 0 ? 1.0 : -1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = 0.5 * d[i];
      const double hl = i == 0 ? 0.0 : neck_fraction * std::min(d[i - 1], d[i]);
      const double hr = i + 1 == n ? 0.0 : neck_fraction * std::min(d[i], d[i + 1]);
      const double sl = std::min(1.0, hl / r), sr = std::min(1.0, hr / r);
      const double a0 = kPi - std::asin(sl);
      const double a1 = std::asin(sr);
      // Upper arcs run from a0 down to a1 in (t, n); lower arcs mirror n. cos a0 = −√(1 − sl²).
      append_arc_from(out, c[i], r, t[i], sg * nn[i], -std::sqrt(1.0 - sl * sl), sl, a0, a1, arc_step);
      if (i + 1 < n) {
        const Vec2 m = 0.5 * ((c[i] + r * t[i]) + (c[i + 1] - 0.5 * d[i + 1] * t[i + 1]));
        const Vec2 navg = 0.5 * (nn[i] + nn[i + 1]);
        out.push_back(m + (sg * hr) * navg);
      }
    }
  }
  nk.lower.front() = nk.upper.front();
  nk.lower.back() = nk.upper.back();
  return nk;
}

}  // namespace

// Types 2–3: rows of melanosomes under the top and over the bottom around a mixed core.
void LayeredBarbule::build_rows(CrossSection& cs) const {
  Outline o = make_outline(p_.outline, cs.seed);
  RandomStream disc_rng(cs.seed, "rows.diameters"), frac_rng(cs.seed, "rows.fraction");
  const double xl = o.interior_half_width;
  const double period = p_.diameter_nm + p_.row_spacing_nm;
  std::vector<Necklace> top_rows, bottom_rows;
  // Bottom normals point down-out when the bottom is walked right → left; offsetting the
  // bottom "inward" by −d with left → right order moves it up into the body.
  for (int i = 0; i < p_.rows; ++i) {
    const double depth = p_.cortex_nm + 0.5 * p_.diameter_nm + i * period;
    Polyline g = clip_x(make_monotone(offset_inward(o.top, depth)), -xl, xl);
    top_rows.push_back(grow_row(g, p_.diameter_nm, p_.jitter, p_.neck_fraction, p_.arc_step_nm, i, disc_rng));
  }
  for (int i = p_.rows - 1; i >= 0; --i) {
    const double depth = p_.cortex_nm + 0.5 * p_.diameter_nm + i * period;
    Polyline g = clip_x(make_monotone(offset_inward(o.bottom, -depth)), -xl, xl);
    bottom_rows.push_back(grow_row(g, p_.diameter_nm, p_.jitter, p_.neck_fraction, p_.arc_step_nm,
                                   2 * p_.rows - 1 - i, disc_rng));
  }
  const Polyline& core_top = top_rows.back().lower;
  std::vector<double> fraction = fraction_at(core_top, p_.core, p_.outline.width_nm, frac_rng);
  const Material core_mix = mixture_of(p_.core, mean_of(fraction));
  finish_outline(cs, std::move(o));

  LayeredModel m;
  m.below_top = p_.body;
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), p_.body, RegionRole::body});
  const Material melanin = p_.core.guest;
  // Exact regions first (they copy the necklaces), then the reduced boundaries take them over.
  auto add_row = [&](const Necklace& nk, int layer) {
    Region r{band_polygon(nk.upper, nk.lower), melanin, RegionRole::melanosome, 0, layer,
             static_cast<int>(nk.discs.size()), p_.diameter_nm};
    cs.regions.push_back(std::move(r));
    cs.melanosomes.insert(cs.melanosomes.end(), nk.discs.begin(), nk.discs.end());
  };
  for (int i = 0; i < p_.rows; ++i) add_row(top_rows[static_cast<std::size_t>(i)], i);
  // The mixed core between the innermost rows, cut square where both rows are present.
  const Polyline& core_bottom = bottom_rows.front().upper;
  const double margin = p_.diameter_nm;
  const double x_lo = std::max(core_top.front().x, core_bottom.front().x) + margin;
  const double x_hi = std::min(core_top.back().x, core_bottom.back().x) - margin;
  cs.regions.push_back({clipped_band(core_top, core_bottom, x_lo, x_hi), core_mix,
                        RegionRole::mixed_core, 0, -1});
  for (int i = 0; i < p_.rows; ++i) add_row(bottom_rows[static_cast<std::size_t>(i)], p_.rows + i);
  m.boundaries.reserve(4 * static_cast<std::size_t>(p_.rows) + 1);
  for (int i = 0; i < p_.rows; ++i) {
    Necklace& nk = top_rows[static_cast<std::size_t>(i)];
    m.boundaries.push_back({std::move(nk.upper), melanin, {}, -1});
    if (i + 1 < p_.rows) m.boundaries.push_back({std::move(nk.lower), p_.body, {}, -1});
    else m.boundaries.push_back({std::move(nk.lower), core_mix, std::move(fraction), -1});
  }
  for (int i = 0; i < p_.rows; ++i) {
    Necklace& nk = bottom_rows[static_cast<std::size_t>(i)];
    m.boundaries.push_back({std::move(nk.upper), melanin, {}, -1});
    m.boundaries.push_back({std::move(nk.lower), p_.body, {}, -1});
  }
  m.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(m);
}

}  // namespace plumage::multilayer
