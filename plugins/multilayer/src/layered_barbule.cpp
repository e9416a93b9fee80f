// structure_generator "layered_barbule" (layered_barbule.hpp): the parameter table, the checks
// that involve several parameters, and the granule_gap and films models. The melanosome rows are
// in layered_rows.cpp, the platelets in layered_platelets.cpp.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "layered_barbule.hpp"

#include <algorithm>
#include <cmath>

#include "layered_shapes.hpp"
#include "plumage/error.hpp"
#include "plumage/geometry.hpp"

namespace plumage::multilayer {

using namespace detail;

namespace {

using Model = LayeredParams::Model;
using LP = LayeredParams;

// A material parameter (air, keratin, melanin, {n, k} or {mix: [a, b], fraction: f}); absent
// leaves the field at its default.
template <class T>
auto material_reader(std::string key, Material T::*field) {
  return [key, field](const ParamView& p, T& o) {
    if (p.has(key)) o.*field = parse_material(p, key);
  };
}

// The guest fraction of a mixture along x: a rough profile of a fraction, not a length.
const ParamTable<RoughnessSpec>& fraction_table() {
  static const auto table =
      ParamTable<RoughnessSpec>{}
          .number("correlation_um", [](RoughnessSpec& r) { return Scaled{&r.rough.correlation_nm, nullptr, 1000.0}; },
                  "um", required, Limits::positive(), "correlation length of the fraction profile")
          .interval("range", [](RoughnessSpec& r) { return Scaled{&r.rough.lo_nm, &r.rough.hi_nm, 1.0}; }, "1",
                    required, Limits::unit_interval(), "the guest fraction spans exactly [lo, hi]");
  return table;
}

const ParamTable<MixtureSpec>& mixture_table() {
  static const auto table =
      ParamTable<MixtureSpec>{}
          .custom("host", "material", "-", "required", "the host material",
                  [](const ParamView& p, MixtureSpec& m) { m.host = parse_material(p, "host"); })
          .custom("guest", "material", "-", "required", "the guest material",
                  [](const ParamView& p, MixtureSpec& m) { m.guest = parse_material(p, "guest"); })
          .section("fraction", &MixtureSpec::fraction, fraction_table(), "guest fraction along x", true);
  return table;
}

const ParamTable<Film>& film_table() {
  static const auto table =
      ParamTable<Film>{}
          .custom("material", "material", "-", "required", "the film's material",
                  [](const ParamView& p, Film& f) { f.material = parse_material(p, "material"); })
          .number("thickness_nm", &Film::thickness_nm, "nm", required, Limits::positive(), "the film's thickness");
  return table;
}

auto model_is(Model m) {
  return [m](const LP& o) { return o.model == m; };
}

// Rows of the outline, the body and the granule_gap and melanosome_rows models.
ParamTable<LP>& add_common_rows(ParamTable<LP>& t) {
  const auto gap = model_is(Model::granule_gap), rows = model_is(Model::melanosome_rows);
  const std::string in_gap = "model: granule_gap", in_rows = "model: melanosome_rows";
  return t
      .choice("model", &LP::model,
              std::vector<std::pair<std::string_view, Model>>{{"granule_gap", Model::granule_gap},
                                                              {"melanosome_rows", Model::melanosome_rows},
                                                              {"platelets", Model::platelets},
                                                              {"films", Model::films}},
              required,
              "granule_gap (type 1) | melanosome_rows (types 2-3) | platelets (type 4) | films (conformal films)")
      .number("cortex_nm", &LP::cortex_nm, "nm", required, Limits::non_negative(), "keratin cortex under the top")
      .custom("outline", "map", "-", "required",
              "top and bottom surfaces (core barbule_outline.hpp; platelets compute thickness_um)",
              [](const ParamView& p, LP& o) {
                o.outline = parse_outline_spec(p.child("outline"), o.model != Model::platelets);
              })
      .nested_specs(outline_table().specs())
      .custom("body", "material", "-", "keratin", "material of the barbule body", material_reader("body", &LP::body))
      .number("arc_spacing_nm", &LP::arc_step_nm, "nm", 10.0, Limits::positive(),
              "vertex spacing on melanosome and bubble outlines")
      .section("gap", &LP::gap, roughness_table(), "rough thickness of the air gap under the cortex", true)
      .only_if(gap, in_gap)
      .section("granules", &LP::granules, mixture_table(), "granules in air under the gap (a mixture)", true)
      .only_if(gap, in_gap)
      .optional_number("lower_cortex_nm", &LP::lower_cortex_nm, "nm", "cortex_nm", Limits::non_negative(),
                       "cortex above the bottom")
      .only_if(gap, in_gap)
      .number("melanosome_diameter_nm", &LP::diameter_nm, "nm", required, Limits::positive(),
              "mean melanosome diameter D")
      .only_if(rows, in_rows)
      .number("diameter_jitter", &LP::jitter, "1", 0.2, Limits{0.0, 1.0, false, true},
              "diameters ~ U[(1 - j) D, (1 + j) D]")
      .only_if(rows, in_rows)
      .number("row_spacing_nm", &LP::row_spacing_nm, "nm", 0.0, Limits::non_negative(),
              "keratin between rows (period D + s)")
      .only_if(rows, in_rows)
      .integer("rows_per_side", &LP::rows, "1", 1, Limits::closed(1, 100), "rows under the top and over the bottom")
      .only_if(rows, in_rows)
      .number("neck_fraction", &LP::neck_fraction, "1", 1.0 / 3.0, Limits{0.0, 0.5, true, false},
              "neck half-thickness / smaller diameter of two neighbours")
      .default_text("1/3")
      .only_if(rows, in_rows)
      .section("core", &LP::core, mixture_table(), "mixture between the innermost rows", true)
      .only_if(rows, in_rows);
}

// Rows of the platelets and films models.
ParamTable<LP>& add_platelet_rows(ParamTable<LP>& t) {
  const auto plate = model_is(Model::platelets), films = model_is(Model::films);
  const std::string in_plate = "model: platelets", in_films = "model: films";
  return t
      .integer("layers", &LP::layers, "1", required, Limits::closed(1, 200), "layers of platelets")
      .only_if(plate, in_plate)
      .number("first_layer_nm", &LP::first_layer_nm, "nm", required, Limits::positive(),
              "thickness of layer 1 (walls + air)")
      .only_if(plate, in_plate)
      .number("wall_nm", &LP::wall_nm, "nm", required, Limits::positive(), "melanin wall thickness t_w")
      .only_if(plate, in_plate)
      .number("bubble_nm", &LP::bubble_nm, "nm", required, Limits::positive(),
              "mean air-core thickness t_b (layers >= 3)")
      .only_if(plate, in_plate)
      .number("second_layer_blend", &LP::blend, "1", 0.2, Limits::unit_interval(),
              "layer 2 air = blend * air_1 + (1 - blend) * t_b")
      .only_if(plate, in_plate)
      .interval("bubble_jitter", &LP::bubble_jitter, "1", {0.95, 1.05}, Limits::positive(),
                "air_i / t_b ~ U[range] for layers >= 3")
      .only_if(plate, in_plate)
      .number("spacer_nm", &LP::spacer_nm, "nm", required, Limits::positive(), "keratin spacer between layers")
      .only_if(plate, in_plate)
      .numbers("first_spacers", &LP::first_spacers, "1", {0.9, 0.95}, Limits::positive(),
               "the first spacers / spacer_nm")
      .only_if(plate, in_plate)
      .interval("spacer_jitter", &LP::spacer_jitter, "1", {0.95, 1.05}, Limits::positive(),
                "later spacers / spacer_nm ~ U[range]")
      .only_if(plate, in_plate)
      .number("membrane_nm", &LP::membrane_nm, "nm", required, Limits::positive(),
              "melanin between neighbouring bubbles")
      .only_if(plate, in_plate)
      .number("platelet_length_um", scaled(&LP::platelet_nm, 1000.0), "um", required, Limits::positive(),
              "mean platelet length")
      .only_if(plate, in_plate)
      .numbers("coverage", &LP::coverage, "1", {0.85, 0.9}, Limits{0.0, 1.0, true, true},
               "platelet fraction of a layer: layer 1, other layers")
      .only_if(plate, in_plate)
      .interval("length_jitter", &LP::length_jitter, "1", {2.0 / 3.0, 4.0 / 3.0}, Limits::positive(),
                "platelet length / mean ~ U[range] before renormalising")
      .default_text("[2/3, 4/3]")
      .only_if(plate, in_plate)
      .interval("gap_jitter", &LP::gap_jitter, "1", {2.0 / 3.0, 4.0 / 3.0}, Limits::positive(),
                "gap / mean gap ~ U[range] before renormalising")
      .default_text("[2/3, 4/3]")
      .only_if(plate, in_plate)
      .interval("end_gap_um", scaled(&LP::end_gap_nm, 1000.0), "um", {0.08, 0.12}, Limits::non_negative(),
                "keratin before the first and after the last platelet ~ U[range]")
      .only_if(plate, in_plate)
      .interval("bubble_length_jitter", &LP::bubble_length_jitter, "1", {0.7, 1.3}, Limits::positive(),
                "bubble length / mean ~ U[range]")
      .only_if(plate, in_plate)
      .number("bubble_height_jitter_nm", &LP::bubble_height_jitter_nm, "nm", 10.0, Limits::non_negative(),
              "bubble height ~ air +- this (air > 30 nm)")
      .only_if(plate, in_plate)
      .custom("films", "list", "-", "required", "conformal films under the cortex, top first",
              [](const ParamView& p, LP& o) {
                for (const ParamView& f : p.items("films")) o.films.push_back(film_table().read(f));
              })
      .nested_specs(film_table().specs())
      .only_if(films, in_films)
      .number("film_spacing_nm", &LP::film_spacing_nm, "nm", 0.0, Limits::non_negative(), "keratin between films")
      .only_if(films, in_films);
}

// The checks that involve several parameters (each names the field to fix).
void check_granule_gap(const LP& o, const ParamView& p) {
  if (o.outline.shape != OutlineSpec::Shape::elliptic_arc) {
    p.child("outline").fail("shape", "granule_gap needs an elliptic_arc outline (arc bottom)");
  }
  if (o.gap.rough.lo_nm < 0.0) p.child("gap").fail("range_um", "a gap cannot be negative");
  if (o.cortex_nm + o.gap.rough.hi_nm >= o.outline.thickness_nm) {
    p.fail("cortex_nm", "cortex and gap exceed the thickness");
  }
}

void check_rows(const LP& o, const ParamView& p) {
  const double depth = o.cortex_nm + o.rows * (o.diameter_nm * (1.0 + o.jitter)) + (o.rows - 1) * o.row_spacing_nm;
  if (2.0 * depth >= o.outline.thickness_nm) p.fail("rows_per_side", "the rows do not fit in the thickness");
  if (o.row_spacing_nm > 0.0 && o.row_spacing_nm < o.diameter_nm * o.jitter * 2.0 && o.rows > 1) {
    // Rows of period D + s hold discs up to (1 + ρ)D: they must not touch.
    if (o.diameter_nm + o.row_spacing_nm <= o.diameter_nm * (1.0 + o.jitter)) {
      p.fail("row_spacing_nm", "rows overlap: spacing below the diameter jitter");
    }
  }
}

void check_platelets(const LP& o, const ParamView& p) {
  if (o.coverage.size() != 2) p.fail("coverage", "give two fractions: layer 1, other layers");
  if (o.first_layer_nm <= 2.0 * o.wall_nm) p.fail("first_layer_nm", "thinner than its two melanin walls");
  if (o.bubble_height_jitter_nm >= o.wall_nm) p.fail("bubble_height_jitter_nm", "bubbles would pierce the walls");
}

void check_films(const LP& o, const ParamView& p) {
  if (o.films.empty()) p.fail("films", "the film list is empty");
  double depth = o.cortex_nm;
  for (const auto& f : o.films) depth += f.thickness_nm + o.film_spacing_nm;
  if (depth >= o.outline.thickness_nm) p.fail("films", "the films do not fit in the thickness");
}

}  // namespace

const ParamTable<LayeredParams>& layered_table() {
  static const ParamTable<LayeredParams> table = [] {
    ParamTable<LayeredParams> t;
    add_common_rows(t);
    add_platelet_rows(t);
    return t;
  }();
  return table;
}

LayeredBarbule::LayeredBarbule(const ParamView& params) : p_(layered_table().read(params)) {
  switch (p_.model) {
    case Model::granule_gap: check_granule_gap(p_, params); break;
    case Model::melanosome_rows: check_rows(p_, params); break;
    case Model::platelets: check_platelets(p_, params); break;
    case Model::films: check_films(p_, params); break;
  }
}

CrossSection LayeredBarbule::generate(std::uint64_t index) const {
  CrossSection cs = start("layered_barbule", index);
  switch (p_.model) {
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
  Outline o = make_outline(p_.outline, cs.seed);
  RandomStream gap_rng(cs.seed, "granule_gap.gap"), frac_rng(cs.seed, "granule_gap.fraction");
  const Polyline inner = make_monotone(offset_inward(o.top, p_.cortex_nm));
  const auto gap = profile_at(xs_of(inner), p_.outline.width_nm, p_.gap.rough, gap_rng, p_.gap.permute);
  const Polyline granule_top = make_monotone(offset_inward(inner, gap));
  const Polyline lower_inner = o.bottom;
  const Polyline bottom = make_monotone(offset_inward(lower_inner, p_.lower_cortex_nm.value_or(p_.cortex_nm)));  // down
  auto fraction = fraction_at(granule_top, p_.granules, p_.outline.width_nm, frac_rng);
  finish_outline(cs, std::move(o));
  cs.bottom = bottom;

  LayeredModel m;
  m.below_top = p_.body;
  const Material cavity = p_.granules.host;
  m.boundaries.push_back({inner, cavity, {}, -1});
  m.boundaries.push_back({granule_top, mixture_of(p_.granules, mean_of(fraction)), fraction, -1});
  m.boundaries.push_back({lower_inner, p_.body, {}, -1});
  m.boundaries.push_back({bottom, Material::air(), {}, -1});

  cs.regions.push_back({band_polygon(cs.top, cs.bottom), p_.body, RegionRole::body});
  const double margin = 4.0 * p_.outline.spacing_nm;
  // The lower cortex narrows an arch (its outward normals lean inward at the ends): the cavity
  // stays within the narrowest of the curves.
  const double x_lo = std::max({inner.front().x, granule_top.front().x, lower_inner.front().x,
                                bottom.front().x}) + margin;
  const double x_hi = std::min({inner.back().x, granule_top.back().x, lower_inner.back().x,
                                bottom.back().x}) - margin;
  cs.regions.push_back({clipped_band(inner, granule_top, x_lo, x_hi), cavity, RegionRole::air_gap, 0});
  cs.regions.push_back({clipped_band(granule_top, lower_inner, x_lo, x_hi),
                        mixture_of(p_.granules, mean_of(fraction)), RegionRole::granular_layer, 0});
  cs.layered = std::move(m);
}

// A worked-example model: conformal films under the cortex (e.g. a two-film barbule).
void LayeredBarbule::build_films(CrossSection& cs) const {
  Outline o = make_outline(p_.outline, cs.seed);
  const double xl = o.interior_half_width;
  const Polyline top = o.top;
  finish_outline(cs, std::move(o));
  LayeredModel m;
  m.below_top = p_.body;
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), p_.body, RegionRole::body});
  double depth = p_.cortex_nm;
  int k = 0;
  for (const auto& f : p_.films) {
    Polyline up = clip_x(make_monotone(offset_inward(top, depth)), -xl, xl);
    Polyline down = clip_x(make_monotone(offset_inward(top, depth + f.thickness_nm)), -xl, xl);
    m.boundaries.push_back({up, f.material, {}, -1});
    m.boundaries.push_back({down, p_.body, {}, -1});
    // Square ends: both edges cut at the same x.
    cs.regions.push_back({band_polygon(up, down), f.material, RegionRole::film, 0, k++, 1, f.thickness_nm});
    depth += f.thickness_nm + p_.film_spacing_nm;
  }
  m.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(m);
}

}  // namespace plumage::multilayer
