// structure_generator "layered_barbule": barbules whose local structure is a layer stack
// (types 1–4 of spec geometry-and-brdf §1.3). Every number comes from the YAML `structure:`
// section; `model:` selects the interior. The outline (top and bottom surfaces) is described by
// the `outline:` map of core's barbule_outline.hpp.
//
// | name                      | type     | unit | default      | meaning                                               |
// |---------------------------|----------|------|--------------|-------------------------------------------------------|
// | model                     | text     | -    | required     | granule_gap, melanosome_rows, platelets or films      |
// | outline                   | map      | -    | required     | top and bottom surfaces (see barbule_outline.hpp)     |
// | cortex_nm                 | number   | nm   | required     | keratin cortex under the top (all models)             |
// | body                      | material | -    | keratin      | material of the barbule body                          |
// | gap                       | map      | -    | required (1) | granule_gap: {correlation_um, range_um} of the air gap |
// | granules                  | map      | -    | required (1) | granule_gap: {host, guest, fraction: {correlation_um, range}} |
// | lower_cortex_nm           | number   | nm   | cortex_nm    | granule_gap: cortex above the bottom                  |
// | melanosome_diameter_nm    | number   | nm   | required (2) | melanosome_rows: mean diameter D                      |
// | diameter_jitter           | number   | -    | 0.2          | melanosome_rows: diameters ~ U[(1−ρ)D, (1+ρ)D]        |
// | row_spacing_nm            | number   | nm   | 0            | melanosome_rows: keratin between rows (period D + s)  |
// | rows_per_side             | integer  | -    | 1            | melanosome_rows: rows under the top and over the bottom |
// | neck_fraction             | number   | -    | 1/3          | melanosome_rows: neck half-thickness / smaller D      |
// | core                      | map      | -    | required (2) | melanosome_rows: {host, guest, fraction: {...}} mixture between the rows |
// | layers                    | integer  | -    | required (4) | platelets: layers of platelets                        |
// | first_layer_nm            | number   | nm   | required (4) | platelets: thickness of layer 1 (walls + air)         |
// | wall_nm                   | number   | nm   | required (4) | platelets: melanin wall thickness t_w                 |
// | bubble_nm                 | number   | nm   | required (4) | platelets: mean air-core thickness t_b (layers ≥ 3)   |
// | second_layer_blend        | number   | -    | 0.2          | platelets: layer 2 air = blend·air₁ + (1−blend)·t_b   |
// | bubble_jitter             | interval | -    | [0.95, 1.05] | platelets: air_i / t_b for layers ≥ 3                 |
// | spacer_nm                 | number   | nm   | required (4) | platelets: keratin spacer between layers              |
// | first_spacers             | list     | -    | [0.9, 0.95]  | platelets: first spacers / spacer_nm                  |
// | spacer_jitter             | interval | -    | [0.95, 1.05] | platelets: later spacers / spacer_nm                  |
// | membrane_nm               | number   | nm   | required (4) | platelets: melanin between neighbouring bubbles       |
// | platelet_length_um        | number   | um   | required (4) | platelets: mean platelet length                       |
// | coverage                  | list     | -    | [0.85, 0.9]  | platelets: platelet fraction of the layer (layer 1, others) |
// | length_jitter             | interval | -    | [2/3, 4/3]   | platelets: length / mean before renormalising         |
// | gap_jitter                | interval | -    | [2/3, 4/3]   | platelets: gap / mean gap before renormalising        |
// | end_gap_um                | interval | um   | [0.08, 0.12] | platelets: keratin before the first and after the last platelet |
// | bubble_length_jitter      | interval | -    | [0.7, 1.3]   | platelets: bubble length / mean                       |
// | bubble_height_jitter_nm   | number   | nm   | 10           | platelets: bubble height ~ air ± this (air > 30 nm)   |
// | films                     | list     | -    | required (f) | films: [{material, thickness_nm}] conformal films under the cortex, separated by `film_spacing_nm` |
// | film_spacing_nm           | number   | nm   | 0            | films: keratin between films                          |
// | arc_spacing_nm            | number   | nm   | 10           | vertex spacing on melanosome and bubble outlines      |
//
// (1) granule_gap, (2) melanosome_rows, (4) platelets, (f) films.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "layered_barbule.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "plumage/error.hpp"
#include "plumage/geometry.hpp"

namespace plumage::multilayer {

namespace {

std::vector<double> xs_of(const Polyline& p) {
  std::vector<double> x(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x[i] = p[i].x;
  return x;
}

Material mixture_of(const MixtureSpec& m, double f) { return Material::mixture(m.host, m.guest, f); }

MixtureSpec parse_mixture(const ParamView& node) {
  MixtureSpec m;
  m.host = parse_material(node, "host");
  m.guest = parse_material(node, "guest");
  ParamView f = node.child("fraction");
  m.fraction.rough.correlation_nm = 1000.0 * f.number("correlation_um", Limits::positive());
  const auto [lo, hi] = f.interval("range", Limits::unit_interval());
  m.fraction.rough.lo_nm = lo;  // a fraction, not a length: the profile is unitless here
  m.fraction.rough.hi_nm = hi;
  return m;
}

std::pair<double, double> interval_or(const ParamView& p, std::string_view key,
                                      std::pair<double, double> fallback, Limits limits) {
  return p.has(key) ? p.interval(key, limits) : fallback;
}

// Renormalise values so they sum to `total`.
void renormalise(std::vector<double>& v, double total) {
  const double sum = std::accumulate(v.begin(), v.end(), 0.0);
  if (sum > 0) for (double& x : v) x *= total / sum;
}

// Per-vertex fraction values of a mixture profile over [−W/2, W/2] at the vertices of `line`.
std::vector<double> fraction_at(const Polyline& line, const MixtureSpec& m, double width,
                                RandomStream& rng) {
  auto xs = xs_of(line);
  for (double& x : xs) x = std::clamp(x, -0.5 * width, 0.5 * width);
  return rough_profile(xs, -0.5 * width, 0.5 * width, m.fraction.rough, rng);
}

double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

// The band between two boundaries cut to their vertices in [x_lo, x_hi] (closed by nearly
// vertical segments between vertices shared with the neighbouring regions).
Polygon clipped_band(const Polyline& upper, const Polyline& lower, double x_lo, double x_hi) {
  return band_polygon(keep_x(upper, x_lo, x_hi), keep_x(lower, x_lo, x_hi));
}

// A row of touching discs along a guide and its necklace outline (spec §1.1(e)).
struct Necklace {
  Polyline upper, lower;
  std::vector<Disc> discs;
};

// Arc of radius r around c from angle a0 to a1 in the frame (t, n), starting from the known
// cosine and sine of a0 (no trigonometric call for the start; one for the step).
void append_arc_from(Polyline& out, Vec2 c, double r, Vec2 t, Vec2 n, double ca, double sa, double a0,
                     double a1, double step) {
  const int k = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) * r / step)));
  // Rotate (cos, sin) by a fixed step instead of calling the trigonometric functions per point.
  const double da = (a1 - a0) / k, cd = std::cos(da), sd = std::sin(da);
  for (int j = 0; j <= k; ++j) {
    out.push_back(c + (r * ca) * t + (r * sa) * n);
    const double nc = ca * cd - sa * sd;
    sa = sa * cd + ca * sd;
    ca = nc;
  }
}

void append_arc(Polyline& out, Vec2 c, double r, Vec2 t, Vec2 n, double a0, double a1, double step) {
  append_arc_from(out, c, r, t, n, std::cos(a0), std::sin(a0), a0, a1, step);
}

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

// Rough values of a profile over [−W/2, W/2] at arbitrary x (clamped).
std::vector<double> profile_at(const std::vector<double>& xs_in, double width, const RoughSpec& spec,
                               RandomStream& rng, bool permute = false) {
  std::vector<double> xs(xs_in);
  for (double& x : xs) x = std::clamp(x, -0.5 * width, 0.5 * width);
  return rough_profile(xs, -0.5 * width, 0.5 * width, spec, rng, permute);
}

}  // namespace

LayeredBarbule::LayeredBarbule(const ParamView& p) {
  static constexpr std::array<std::string_view, 4> models{"granule_gap", "melanosome_rows",
                                                          "platelets", "films"};
  const std::string model = p.choice("model", models);
  model_ = model == "granule_gap"       ? Model::granule_gap
           : model == "melanosome_rows" ? Model::melanosome_rows
           : model == "platelets"       ? Model::platelets
                                        : Model::films;
  cortex_nm_ = p.number("cortex_nm", Limits::non_negative());
  outline_ = parse_outline_spec(p.child("outline"), model_ != Model::platelets);
  body_ = p.has("body") ? parse_material(p, "body") : Material::keratin();
  arc_step_ = p.number_or("arc_spacing_nm", 10.0, Limits::positive());
  const double T = outline_.thickness_nm;
  switch (model_) {
    case Model::granule_gap: {
      if (outline_.shape != OutlineSpec::Shape::elliptic_arc) {
        p.child("outline").fail("shape", "granule_gap needs an elliptic_arc outline (arc bottom)");
      }
      gap_ = parse_roughness(p.child("gap"));
      if (gap_.rough.lo_nm < 0.0) p.child("gap").fail("range_um", "a gap cannot be negative");
      granules_ = parse_mixture(p.child("granules"));
      lower_cortex_nm_ = p.number_or("lower_cortex_nm", cortex_nm_, Limits::non_negative());
      if (cortex_nm_ + gap_.rough.hi_nm >= T) p.fail("cortex_nm", "cortex and gap exceed the thickness");
      break;
    }
    case Model::melanosome_rows: {
      diameter_nm_ = p.number("melanosome_diameter_nm", Limits::positive());
      jitter_ = p.number_or("diameter_jitter", 0.2, Limits{0.0, 1.0, false, true});
      row_spacing_nm_ = p.number_or("row_spacing_nm", 0.0, Limits::non_negative());
      rows_ = static_cast<int>(p.integer_or("rows_per_side", 1, Limits::closed(1, 100)));
      neck_fraction_ = p.number_or("neck_fraction", 1.0 / 3.0, Limits{0.0, 0.5, true, false});
      core_ = parse_mixture(p.child("core"));
      const double depth = cortex_nm_ + rows_ * (diameter_nm_ * (1.0 + jitter_)) + (rows_ - 1) * row_spacing_nm_;
      if (2.0 * depth >= T) p.fail("rows_per_side", "the rows do not fit in the thickness");
      if (row_spacing_nm_ > 0.0 && row_spacing_nm_ < diameter_nm_ * jitter_ * 2.0 && rows_ > 1) {
        // Rows of period D + s hold discs up to (1 + ρ)D: they must not touch.
        if (diameter_nm_ + row_spacing_nm_ <= diameter_nm_ * (1.0 + jitter_)) {
          p.fail("row_spacing_nm", "rows overlap: spacing below the diameter jitter");
        }
      }
      break;
    }
    case Model::platelets: {
      layers_ = static_cast<int>(p.integer("layers", Limits::closed(1, 200)));
      first_layer_nm_ = p.number("first_layer_nm", Limits::positive());
      wall_nm_ = p.number("wall_nm", Limits::positive());
      bubble_nm_ = p.number("bubble_nm", Limits::positive());
      blend_ = p.number_or("second_layer_blend", 0.2, Limits::unit_interval());
      bubble_jitter_ = interval_or(p, "bubble_jitter", {0.95, 1.05}, Limits::positive());
      spacer_nm_ = p.number("spacer_nm", Limits::positive());
      first_spacers_ = p.has("first_spacers") ? p.numbers("first_spacers", Limits::positive())
                                              : std::vector<double>{0.9, 0.95};
      spacer_jitter_ = interval_or(p, "spacer_jitter", {0.95, 1.05}, Limits::positive());
      membrane_nm_ = p.number("membrane_nm", Limits::positive());
      platelet_nm_ = 1000.0 * p.number("platelet_length_um", Limits::positive());
      coverage_ = p.has("coverage") ? p.numbers("coverage", Limits{0.0, 1.0, true, true})
                                    : std::vector<double>{0.85, 0.9};
      if (coverage_.size() != 2) p.fail("coverage", "give two fractions: layer 1, other layers");
      length_jitter_ = interval_or(p, "length_jitter", {2.0 / 3.0, 4.0 / 3.0}, Limits::positive());
      gap_jitter_ = interval_or(p, "gap_jitter", {2.0 / 3.0, 4.0 / 3.0}, Limits::positive());
      auto eg = interval_or(p, "end_gap_um", {0.08, 0.12}, Limits::non_negative());
      end_gap_nm_ = {1000.0 * eg.first, 1000.0 * eg.second};
      bubble_length_jitter_ = interval_or(p, "bubble_length_jitter", {0.7, 1.3}, Limits::positive());
      bubble_height_jitter_nm_ = p.number_or("bubble_height_jitter_nm", 10.0, Limits::non_negative());
      if (first_layer_nm_ <= 2.0 * wall_nm_) p.fail("first_layer_nm", "thinner than its two melanin walls");
      if (bubble_height_jitter_nm_ >= wall_nm_) p.fail("bubble_height_jitter_nm", "bubbles would pierce the walls");
      break;
    }
    case Model::films: {
      for (const ParamView& f : p.items("films")) {
        films_.push_back({parse_material(f, "material"), f.number("thickness_nm", Limits::positive())});
      }
      if (films_.empty()) p.fail("films", "the film list is empty");
      film_spacing_nm_ = p.number_or("film_spacing_nm", 0.0, Limits::non_negative());
      double depth = cortex_nm_;
      for (const auto& f : films_) depth += f.thickness_nm + film_spacing_nm_;
      if (depth >= T) p.fail("films", "the films do not fit in the thickness");
      break;
    }
  }
}

CrossSection LayeredBarbule::generate(std::uint64_t index) const {
  CrossSection cs = start("layered_barbule", index);
  switch (model_) {
    case Model::granule_gap: build_granule_gap(cs); break;
    case Model::melanosome_rows: build_rows(cs); break;
    case Model::platelets: build_platelets(cs); break;
    case Model::films: build_films(cs); break;
  }
  return cs;
}

void LayeredBarbule::finish_outline(CrossSection& cs, Outline&& o) const {
  cs.top = std::move(o.top);
  cs.top_roughness_nm = std::move(o.top_roughness);
  cs.bottom = std::move(o.bottom);
}

// Type 1: cortex | air gap | granules in air (mixture) | lower cortex (spec §1.3(1)).
void LayeredBarbule::build_granule_gap(CrossSection& cs) const {
  Outline o = make_outline(outline_, cs.seed);
  RandomStream gap_rng(cs.seed, "granule_gap.gap"), frac_rng(cs.seed, "granule_gap.fraction");
  const Polyline inner = make_monotone(offset_inward(o.top, cortex_nm_));
  const auto gap = profile_at(xs_of(inner), outline_.width_nm, gap_.rough, gap_rng);
  const Polyline granule_top = make_monotone(offset_inward(inner, gap));
  const Polyline lower_inner = o.bottom;
  const Polyline bottom = make_monotone(offset_inward(lower_inner, lower_cortex_nm_));  // down
  auto fraction = fraction_at(granule_top, granules_, outline_.width_nm, frac_rng);
  finish_outline(cs, std::move(o));
  cs.bottom = bottom;

  LayeredModel m;
  m.below_top = body_;
  const Material cavity = granules_.host;
  m.boundaries.push_back({inner, cavity, {}, -1});
  m.boundaries.push_back({granule_top, mixture_of(granules_, mean_of(fraction)), fraction, -1});
  m.boundaries.push_back({lower_inner, body_, {}, -1});
  m.boundaries.push_back({bottom, Material::air(), {}, -1});

  cs.regions.push_back({band_polygon(cs.top, cs.bottom), body_, RegionRole::body});
  const double margin = 4.0 * outline_.spacing_nm;
  // The lower cortex narrows an arch (its outward normals lean inward at the ends): the cavity
  // stays within the narrowest of the curves.
  const double x_lo = std::max({inner.front().x, granule_top.front().x, lower_inner.front().x,
                                bottom.front().x}) + margin;
  const double x_hi = std::min({inner.back().x, granule_top.back().x, lower_inner.back().x,
                                bottom.back().x}) - margin;
  cs.regions.push_back({clipped_band(inner, granule_top, x_lo, x_hi), cavity, RegionRole::air_gap, 0});
  cs.regions.push_back({clipped_band(granule_top, lower_inner, x_lo, x_hi),
                        mixture_of(granules_, mean_of(fraction)), RegionRole::granular_layer, 0});
  cs.layered = std::move(m);
}

// Types 2–3: rows of melanosomes under the top and over the bottom around a mixed core.
void LayeredBarbule::build_rows(CrossSection& cs) const {
  Outline o = make_outline(outline_, cs.seed);
  RandomStream disc_rng(cs.seed, "rows.diameters"), frac_rng(cs.seed, "rows.fraction");
  const double xl = o.interior_half_width;
  const double period = diameter_nm_ + row_spacing_nm_;
  std::vector<Necklace> top_rows, bottom_rows;
  // Bottom normals point down-out when the bottom is walked right → left; offsetting the
  // bottom "inward" by −d with left → right order moves it up into the body.
  for (int i = 0; i < rows_; ++i) {
    const double depth = cortex_nm_ + 0.5 * diameter_nm_ + i * period;
    Polyline g = clip_x(make_monotone(offset_inward(o.top, depth)), -xl, xl);
    top_rows.push_back(grow_row(g, diameter_nm_, jitter_, neck_fraction_, arc_step_, i, disc_rng));
  }
  for (int i = rows_ - 1; i >= 0; --i) {
    const double depth = cortex_nm_ + 0.5 * diameter_nm_ + i * period;
    Polyline g = clip_x(make_monotone(offset_inward(o.bottom, -depth)), -xl, xl);
    bottom_rows.push_back(grow_row(g, diameter_nm_, jitter_, neck_fraction_, arc_step_,
                                   2 * rows_ - 1 - i, disc_rng));
  }
  const Polyline& core_top = top_rows.back().lower;
  std::vector<double> fraction = fraction_at(core_top, core_, outline_.width_nm, frac_rng);
  const Material core_mix = mixture_of(core_, mean_of(fraction));
  finish_outline(cs, std::move(o));

  LayeredModel m;
  m.below_top = body_;
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), body_, RegionRole::body});
  const Material melanin = core_.guest;
  // Exact regions first (they copy the necklaces), then the reduced boundaries take them over.
  auto add_row = [&](const Necklace& nk, int layer) {
    Region r{band_polygon(nk.upper, nk.lower), melanin, RegionRole::melanosome, 0, layer,
             static_cast<int>(nk.discs.size()), diameter_nm_};
    cs.regions.push_back(std::move(r));
    cs.melanosomes.insert(cs.melanosomes.end(), nk.discs.begin(), nk.discs.end());
  };
  for (int i = 0; i < rows_; ++i) add_row(top_rows[static_cast<std::size_t>(i)], i);
  // The mixed core between the innermost rows, cut square where both rows are present.
  const Polyline& core_bottom = bottom_rows.front().upper;
  const double margin = diameter_nm_;
  const double x_lo = std::max(core_top.front().x, core_bottom.front().x) + margin;
  const double x_hi = std::min(core_top.back().x, core_bottom.back().x) - margin;
  cs.regions.push_back({clipped_band(core_top, core_bottom, x_lo, x_hi), core_mix,
                        RegionRole::mixed_core, 0, -1});
  for (int i = 0; i < rows_; ++i) add_row(bottom_rows[static_cast<std::size_t>(i)], rows_ + i);
  m.boundaries.reserve(4 * static_cast<std::size_t>(rows_) + 1);
  for (int i = 0; i < rows_; ++i) {
    Necklace& nk = top_rows[static_cast<std::size_t>(i)];
    m.boundaries.push_back({std::move(nk.upper), melanin, {}, -1});
    if (i + 1 < rows_) m.boundaries.push_back({std::move(nk.lower), body_, {}, -1});
    else m.boundaries.push_back({std::move(nk.lower), core_mix, std::move(fraction), -1});
  }
  for (int i = 0; i < rows_; ++i) {
    Necklace& nk = bottom_rows[static_cast<std::size_t>(i)];
    m.boundaries.push_back({std::move(nk.upper), melanin, {}, -1});
    m.boundaries.push_back({std::move(nk.lower), body_, {}, -1});
  }
  m.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(m);
}

// Type 4: layers of hollow melanin platelets (spec §1.3(4)).
void LayeredBarbule::build_platelets(CrossSection& cs) const {
  RandomStream layer_rng(cs.seed, "platelets.layers"), plate_rng(cs.seed, "platelets.platelets");
  RandomStream bubble_rng(cs.seed, "platelets.bubbles");
  const int n = layers_;
  std::vector<double> air(static_cast<std::size_t>(n)), spacer(static_cast<std::size_t>(std::max(0, n - 1)));
  double air1 = first_layer_nm_ - 2.0 * wall_nm_;
  if (air1 < 20.0) air1 += 10.0;
  for (int i = 0; i < n; ++i) {
    air[static_cast<std::size_t>(i)] =
        i == 0 ? air1
        : i == 1 ? blend_ * air1 + (1.0 - blend_) * bubble_nm_
                 : bubble_nm_ * layer_rng.uniform(bubble_jitter_.first, bubble_jitter_.second);
  }
  for (int i = 0; i + 1 < n; ++i) {
    spacer[static_cast<std::size_t>(i)] =
        spacer_nm_ * (static_cast<std::size_t>(i) < first_spacers_.size()
                          ? first_spacers_[static_cast<std::size_t>(i)]
                          : layer_rng.uniform(spacer_jitter_.first, spacer_jitter_.second));
  }
  double T = 2.0 * cortex_nm_;
  for (int i = 0; i < n; ++i) T += 2.0 * wall_nm_ + air[static_cast<std::size_t>(i)];
  for (double s : spacer) T += s;

  Outline o = make_outline(outline_, cs.seed, T);
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
  m.below_top = body_;
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), body_, RegionRole::body});
  const Material melanin = Material::melanin(), air_m = Material::air();
  double h1 = cortex_nm_;
  for (int layer = 0; layer < n; ++layer) {
    const double a = air[static_cast<std::size_t>(layer)];
    const double h2 = h1 + 2.0 * wall_nm_ + a;
    const Polyline up = guide(h1), down = guide(h2), mid = guide(0.5 * (h1 + h2));
    const double extent = 2.0 * xl;
    const double total = (layer == 0 ? coverage_[0] : coverage_[1]) * extent;
    const int count = std::max(1, static_cast<int>(std::lround(total / platelet_nm_)));
    std::vector<double> lengths(static_cast<std::size_t>(count));
    for (double& l : lengths) l = platelet_nm_ * plate_rng.uniform(length_jitter_.first, length_jitter_.second);
    renormalise(lengths, total);
    const double end_l = plate_rng.uniform(end_gap_nm_.first, end_gap_nm_.second);
    const double end_r = plate_rng.uniform(end_gap_nm_.first, end_gap_nm_.second);
    const double rest = extent - total - end_l - end_r;
    std::vector<double> gaps(static_cast<std::size_t>(std::max(0, count - 1)));
    for (double& g : gaps) g = plate_rng.uniform(gap_jitter_.first, gap_jitter_.second);
    renormalise(gaps, rest);
    double x = -xl + end_l;
    const double rr = 0.5 * (h2 - h1);
    for (int k = 0; k < count; ++k) {
      const double xa = x, xb = x + lengths[static_cast<std::size_t>(k)];
      x = xb + (k + 1 < count ? gaps[static_cast<std::size_t>(k)] : 0.0);
      // Box: guides between the rounded ends, half circles of radius rr at the ends.
      auto end_center = [&](double xc) { return Vec2{xc, z_at(mid, xc)}; };
      const Vec2 cl = end_center(xa + rr), cr = end_center(xb - rr);
      Polyline upper, lower;
      append_arc(upper, cl, rr, {1, 0}, {0, 1}, kPi, 0.5 * kPi, arc_step_);
      for (const Vec2& p : clip_x(up, xa + rr, xb - rr)) upper.push_back(p);
      append_arc(upper, cr, rr, {1, 0}, {0, 1}, 0.5 * kPi, 0.0, arc_step_);
      append_arc(lower, cl, rr, {1, 0}, {0, -1}, kPi, 0.5 * kPi, arc_step_);
      for (const Vec2& p : clip_x(down, xa + rr, xb - rr)) lower.push_back(p);
      append_arc(lower, cr, rr, {1, 0}, {0, -1}, 0.5 * kPi, 0.0, arc_step_);
      upper = make_monotone(upper);
      lower = make_monotone(lower);
      lower.front() = upper.front();
      lower.back() = upper.back();
      // Bubbles inside the box along its midline.
      const double len = xb - xa;
      const int nb = std::max(1, static_cast<int>(std::lround((len - 2.0 * wall_nm_ + membrane_nm_) /
                                                              (a + membrane_nm_))));
      std::vector<double> bl(static_cast<std::size_t>(nb));
      for (double& b : bl) b = bubble_length_jitter_.first +
                               (bubble_length_jitter_.second - bubble_length_jitter_.first) * bubble_rng.uniform();
      renormalise(bl, len - 2.0 * wall_nm_ - (nb - 1) * membrane_nm_);
      Polyline bu, bd;
      double bx = xa + wall_nm_;
      const double cut = kPi / 12.0;
      const double cos_cut = std::cos(cut), sin_cut = std::sin(cut);
      for (int j = 0; j < nb; ++j) {
        const double l = bl[static_cast<std::size_t>(j)];
        const double height = a > 30.0 ? a + bubble_rng.uniform(-bubble_height_jitter_nm_, bubble_height_jitter_nm_) : a;
        const double xc = bx + 0.5 * l;
        const Vec2 c{xc, z_at(mid, xc)};
        Vec2 t{l, z_at(mid, xc + 0.5 * l) - z_at(mid, xc - 0.5 * l)};  // local midline direction
        t = (1.0 / norm(t)) * t;
        const Vec2 nn{-t.z, t.x};
        const double a0 = j == 0 ? kPi : kPi - cut, a1 = j + 1 == nb ? 0.0 : cut;
        // Ellipse arcs: scale the unit-circle arc to semi-axes (l/2, height/2).
        auto ellipse_arc = [&](Polyline& out, double sg) {
          const int kk = std::max(4, static_cast<int>(std::ceil((a0 - a1) * 0.5 * std::max(l, height) / arc_step_)));
          const double da = (a1 - a0) / kk, cd = std::cos(da), sd = std::sin(da);
          double ca = j == 0 ? -1.0 : -cos_cut, sa = j == 0 ? 0.0 : sin_cut;  // cos, sin of a0
          for (int q = 0; q <= kk; ++q) {
            out.push_back(c + (0.5 * l * ca) * t + (sg * 0.5 * height * sa) * nn);
            const double nc = ca * cd - sa * sd;
            sa = sa * cd + ca * sd;
            ca = nc;
          }
        };
        ellipse_arc(bu, 1.0);
        ellipse_arc(bd, -1.0);
        bx += l + membrane_nm_;
      }
      bd.front() = bu.front();
      bd.back() = bu.back();
      const int base = static_cast<int>(m.boundaries.size());
      m.boundaries.push_back({upper, melanin, {}, base + 3});
      m.boundaries.push_back({bu, air_m, {}, base + 2});
      m.boundaries.push_back({bd, melanin, {}, -1});
      m.boundaries.push_back({lower, body_, {}, -1});
      const int plate_index = static_cast<int>(cs.regions.size());
      cs.regions.push_back({band_polygon(upper, lower), melanin, RegionRole::platelet, 0, layer, 1, len});
      cs.regions.push_back({band_polygon(bu, bd), air_m, RegionRole::air_bubble, plate_index, layer, nb, a});
    }
    h1 = h2 + (layer + 1 < n ? spacer[static_cast<std::size_t>(layer)] : 0.0);
  }
  m.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(m);
}

// A worked-example model: conformal films under the cortex (e.g. a two-film barbule).
void LayeredBarbule::build_films(CrossSection& cs) const {
  Outline o = make_outline(outline_, cs.seed);
  const double xl = o.interior_half_width;
  const Polyline top = o.top;
  finish_outline(cs, std::move(o));
  LayeredModel m;
  m.below_top = body_;
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), body_, RegionRole::body});
  double depth = cortex_nm_;
  int k = 0;
  for (const auto& f : films_) {
    Polyline up = clip_x(make_monotone(offset_inward(top, depth)), -xl, xl);
    Polyline down = clip_x(make_monotone(offset_inward(top, depth + f.thickness_nm)), -xl, xl);
    m.boundaries.push_back({up, f.material, {}, -1});
    m.boundaries.push_back({down, body_, {}, -1});
    // Square ends: both edges cut at the same x.
    cs.regions.push_back({band_polygon(up, down), f.material, RegionRole::film, 0, k++, 1, f.thickness_nm});
    depth += f.thickness_nm + film_spacing_nm_;
  }
  m.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(m);
}

std::vector<ParamSpec> LayeredBarbule::param_table() {
  std::vector<ParamSpec> t{
      {"model", "text", "-", "required", "granule_gap, melanosome_rows, platelets or films"},
      {"outline", "map", "-", "required", "top and bottom surfaces (rows outline.*)"},
      {"cortex_nm", "number", "nm", "required", "keratin cortex under the top"},
      {"body", "material", "-", "keratin", "material of the barbule body"},
      {"gap", "map", "-", "required (granule_gap)", "{correlation_um, range_um} of the air gap"},
      {"granules", "map", "-", "required (granule_gap)", "{host, guest, fraction: {correlation_um, range}}"},
      {"lower_cortex_nm", "number", "nm", "cortex_nm", "granule_gap: cortex above the bottom"},
      {"melanosome_diameter_nm", "number", "nm", "required (rows)", "mean melanosome diameter D"},
      {"diameter_jitter", "number", "-", "0.2", "rows: diameters ~ U[(1-j)D, (1+j)D]"},
      {"row_spacing_nm", "number", "nm", "0", "rows: keratin between rows (period D + s)"},
      {"rows_per_side", "integer", "-", "1", "rows: rows under the top and over the bottom"},
      {"neck_fraction", "number", "-", "1/3", "rows: neck half-thickness / smaller diameter"},
      {"core", "map", "-", "required (rows)", "{host, guest, fraction: {correlation_um, range}} between rows"},
      {"layers", "integer", "-", "required (platelets)", "number of platelet layers"},
      {"first_layer_nm", "number", "nm", "required (platelets)", "layer 1 thickness (walls + air)"},
      {"wall_nm", "number", "nm", "required (platelets)", "melanin wall thickness"},
      {"bubble_nm", "number", "nm", "required (platelets)", "mean air thickness of layers >= 3"},
      {"second_layer_blend", "number", "-", "0.2", "layer 2 air = b*air1 + (1-b)*bubble_nm"},
      {"bubble_jitter", "interval", "-", "[0.95, 1.05]", "air_i / bubble_nm for layers >= 3"},
      {"spacer_nm", "number", "nm", "required (platelets)", "keratin spacer between layers"},
      {"first_spacers", "list", "-", "[0.9, 0.95]", "first spacers / spacer_nm"},
      {"spacer_jitter", "interval", "-", "[0.95, 1.05]", "later spacers / spacer_nm"},
      {"membrane_nm", "number", "nm", "required (platelets)", "melanin between neighbouring bubbles"},
      {"platelet_length_um", "number", "um", "required (platelets)", "mean platelet length"},
      {"coverage", "list", "-", "[0.85, 0.9]", "platelet fraction of a layer (layer 1, others)"},
      {"length_jitter", "interval", "-", "[2/3, 4/3]", "platelet length / mean before renormalising"},
      {"gap_jitter", "interval", "-", "[2/3, 4/3]", "gap / mean gap before renormalising"},
      {"end_gap_um", "interval", "um", "[0.08, 0.12]", "keratin before the first / after the last platelet"},
      {"bubble_length_jitter", "interval", "-", "[0.7, 1.3]", "bubble length / mean"},
      {"bubble_height_jitter_nm", "number", "nm", "10", "bubble height ~ air +- this (air > 30 nm)"},
      {"films", "list", "-", "required (films)", "[{material, thickness_nm}] conformal films under the cortex"},
      {"film_spacing_nm", "number", "nm", "0", "films: keratin between films"},
      {"arc_spacing_nm", "number", "nm", "10", "vertex spacing on melanosome and bubble outlines"},
  };
  for (auto& row : outline_param_table()) t.push_back(row);
  return t;
}

}  // namespace plumage::multilayer
