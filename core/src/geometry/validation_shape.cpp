// structure_generator "validation_shape" (built into core): shapes with exact solutions for the
// solvers' validation ladder (DESIGN §9, rungs 3–4), usable from configs like a species. Its
// parameters are declared once, in shape_params() (`plumage plugins describe validation_shape`).
//
// Every instance is identical (no randomness: a rough slab's profile is fixed by its `seed`).
// Frame: circles centred at the origin, the top is the upper half circle; the slab's top is
// z = 0, x in [−W/2, W/2]. Rough / curved slab (issue 9's stability study of the approximate
// solver): interface k at depth d_k is z_k(x) = c_k(x) + h(x), with c_k the arc of radius R − d_k
// concentric with the top (c_k = −d_k when flat) and h the rough profile of geometry.hpp
// (Gaussian spectrum, so rms slope = rms_nm / correlation; rescaled to the exact rms over the
// top's vertices). Every layer is a vertical translate of the rough profile, so no roughness
// makes interfaces cross.
// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include <algorithm>
#include <cmath>
#include <vector>
#include <optional>

#include "plumage/builtin_plugins.hpp"
#include "plumage/geometry.hpp"
#include "plumage/param_table.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

namespace {

// How a circle becomes a polygon. Vertices on the circle make the body too small by the
// polygon's area defect 1 − sin(2π/N)/(2π/N) ≈ (2π/N)²/6 (issue 28: the 100 nm melanin cylinder
// was 4e-4–9.5e-4 off the exact series for that alone); the area-preserving polygon puts its
// vertices at r·sqrt((2π/N)/sin(2π/N)), so the body has the circle's area (and, to O(N⁻²), its
// scattering).
enum class CirclePolygon { area_preserving, inscribed };

// Half circle from angle π to 0 (upper, x increasing) or π to 2π (lower, x increasing); the two
// halves of one radius make a regular polygon of 2n vertices.
Polyline half_circle(double r, bool upper, double spacing, CirclePolygon polygon) {
  const int n = std::max(16, static_cast<int>(std::ceil(kPi * r / spacing)));
  const double step = kPi / n;  // = 2π/N with N = 2n vertices in all
  const double rv = polygon == CirclePolygon::area_preserving ? r * std::sqrt(step / std::sin(step)) : r;
  Polyline p;
  for (int k = 0; k <= n; ++k) {
    const double t = kPi - kPi * k / n;
    p.push_back({rv * std::cos(t), (upper ? 1.0 : -1.0) * rv * std::sin(t)});
  }
  p.front() = {-rv, 0.0};
  p.back() = {rv, 0.0};
  return p;
}

enum class Shape { circle, coated_circle, slab };

// Vertex spacing on curves when spacing_nm is not given.
constexpr double kCircleSpacingNm = 5.0, kSlabSpacingNm = 30.0;

struct Roughness {
  double rms_nm;  // 0: none
  double correlation_um;
  std::uint64_t seed;
};

// The parameters as written; ValidationShape checks what one value implies for another.
struct ShapeParams {
  Shape shape;
  double radius_nm;  // circles: outer radius
  Material material;  // circle: the cylinder; coated_circle: the coating
  double coating_nm;
  Material core;
  double width_um;
  LayerProfile stack;
  std::optional<double> spacing_nm;
  CirclePolygon polygon;
  std::optional<double> radius_um;  // slab: curved top
  Roughness roughness;
};

const ParamTable<Roughness>& roughness_params() {
  static const auto table =
      ParamTable<Roughness>{}
          .number("rms_nm", &Roughness::rms_nm, "nm", required, Limits::at_least(0.0), "rms height")
          .number("correlation_um", &Roughness::correlation_um, "um", required, Limits::positive(),
                  "correlation length (Gaussian spectrum: rms slope = rms_nm / correlation)")
          .integer("seed", &Roughness::seed, "-", 1, Limits::at_least(0.0), "seed of the fixed profile");
  return table;
}

// A material-valued parameter (materials.hpp) with its default.
ParamTable<ShapeParams>& material_param(ParamTable<ShapeParams>& t, const char* name, Material ShapeParams::*field,
                                        Material fallback, const char* fallback_name, std::string doc) {
  return t.custom(
      name, "material", "-", fallback_name, std::move(doc),
      [name, field](const ParamView& p, ShapeParams& o) {
        if (p.has(name)) o.*field = parse_material(p, name);
      },
      [field, fallback](ShapeParams& o) { o.*field = fallback; });
}

const ParamTable<ShapeParams>& shape_params() {
  static const auto table = [] {
    const auto is = [](std::vector<Shape> shapes) {
      return [shapes](const ShapeParams& o) { return std::find(shapes.begin(), shapes.end(), o.shape) != shapes.end(); };
    };
    ParamTable<ShapeParams> t;
    t.choice("shape", &ShapeParams::shape,
             std::vector<std::pair<std::string_view, Shape>>{
                 {"circle", Shape::circle}, {"coated_circle", Shape::coated_circle}, {"slab", Shape::slab}},
             required,
             "circle, coated circle or layered slab");
    t.number("radius_nm", &ShapeParams::radius_nm, "nm", required, Limits::positive(), "outer radius")
        .only_if(is({Shape::circle, Shape::coated_circle}), "shape: circle | coated_circle");
    material_param(t, "material", &ShapeParams::material, Material::keratin(), "keratin", "the cylinder's material")
        .only_if(is({Shape::circle}), "shape: circle");
    t.number("coating_nm", &ShapeParams::coating_nm, "nm", required, Limits::positive(),
             "coating thickness (< radius)")
        .only_if(is({Shape::coated_circle}), "shape: coated_circle");
    material_param(t, "core", &ShapeParams::core, Material::melanin(), "melanin", "core material")
        .only_if(is({Shape::coated_circle}), "shape: coated_circle");
    material_param(t, "coating", &ShapeParams::material, Material::keratin(), "keratin", "coating material")
        .only_if(is({Shape::coated_circle}), "shape: coated_circle");
    t.number("width_um", &ShapeParams::width_um, "um", required, Limits::positive(), "width of the top")
        .only_if(is({Shape::slab}), "shape: slab");
    t.custom("stack", "map", "-", "required", "layers (top to bottom) and substrate; ambient and substrate air",
             [](const ParamView& p, ShapeParams& o) { o.stack = parse_layer_profile(p.child("stack")); })
        .only_if(is({Shape::slab}), "shape: slab");
    t.optional_number("spacing_nm", &ShapeParams::spacing_nm, "nm",
                      format_param_number(kCircleSpacingNm) + " (circles), " + format_param_number(kSlabSpacingNm) +
                          " (slab)",
                      Limits::positive(), "vertex spacing on curves");
    t.choice("polygon", &ShapeParams::polygon,
             std::vector<std::pair<std::string_view, CirclePolygon>>{
                 {"area_preserving", CirclePolygon::area_preserving}, {"inscribed", CirclePolygon::inscribed}},
             CirclePolygon::area_preserving,
             "circle as a regular polygon with the circle's area (vertices slightly outside it) or with its "
             "vertices on the circle (a body too small by about (2π/N)²/6 of its area, N vertices)")
        .only_if(is({Shape::circle, Shape::coated_circle}), "shape: circle | coated_circle");
    t.optional_number("radius_um", &ShapeParams::radius_um, "um", "flat", Limits::positive(),
                      "curved top: a circular arc of this radius (apex at z = 0); interfaces are concentric arcs "
                      "(radius > width/2 + stack depth)")
        .only_if(is({Shape::slab}), "shape: slab");
    t.section("roughness", &ShapeParams::roughness, roughness_params(),
              "Gaussian-correlated height profile added to every interface")
        .default_text("none")
        .only_if(is({Shape::slab}), "shape: slab");
    return t;
  }();
  return table;
}

class ValidationShape final : public StructureGenerator {
 public:
  explicit ValidationShape(const ParamView& p) {
    const ShapeParams o = shape_params().read(p);
    shape_ = o.shape;
    if (shape_ != Shape::slab) {
      radius_ = o.radius_nm;
      material_ = o.material;
      if (shape_ == Shape::coated_circle) {
        coating_nm_ = o.coating_nm;
        if (coating_nm_ >= radius_) p.fail("coating_nm", "the coating must be thinner than the radius");
        core_ = o.core;
      }
      spacing_ = o.spacing_nm.value_or(kCircleSpacingNm);
      polygon_ = o.polygon;
    } else {
      width_nm_ = 1000.0 * o.width_um;
      stack_ = o.stack;
      if (stack_.ambient.kind() != Material::Kind::air || stack_.substrate.kind() != Material::Kind::air) {
        p.fail("stack", "a slab stands in air: ambient and substrate must be air");
      }
      spacing_ = o.spacing_nm.value_or(kSlabSpacingNm);
      double depth = 0.0;
      for (const auto& layer : stack_.layers) depth += layer.thickness_nm;
      if (o.radius_um) {
        radius_nm_ = 1000.0 * *o.radius_um;
        if (radius_nm_ - depth <= 0.5 * width_nm_) {
          p.fail("radius_um", "the deepest interface's arc must span the width: radius > width/2 + stack depth");
        }
      }
      // Without `roughness`: rms 0, no profile (correlation and seed unused).
      rms_nm_ = o.roughness.rms_nm;
      correlation_nm_ = 1000.0 * o.roughness.correlation_um;
      seed_ = o.roughness.seed;
    }
  }

  CrossSection generate(std::uint64_t index) const override {
    CrossSection cs = start("validation_shape", index);
    LayeredModel model;
    if (shape_ != Shape::slab) {
      cs.top = half_circle(radius_, true, spacing_, polygon_);
      cs.bottom = half_circle(radius_, false, spacing_, polygon_);
      cs.regions.push_back({band_polygon(cs.top, cs.bottom), material_, RegionRole::body});
      model.below_top = material_;
      if (shape_ == Shape::coated_circle) {
        const double ri = radius_ - coating_nm_;
        Polyline up = half_circle(ri, true, spacing_, polygon_), down = half_circle(ri, false, spacing_, polygon_);
        cs.regions.push_back({band_polygon(up, down), core_, RegionRole::core, 0});
        model.boundaries.push_back({up, core_, {}, 1});
        model.boundaries.push_back({down, material_, {}, -1});
      }
      model.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
    } else {
      const int n = std::max(2, static_cast<int>(std::ceil(width_nm_ / spacing_)));
      std::vector<double> xs(static_cast<std::size_t>(n) + 1), rough(xs.size(), 0.0);
      for (int k = 0; k <= n; ++k) xs[static_cast<std::size_t>(k)] = -0.5 * width_nm_ + width_nm_ * k / n;
      if (rms_nm_ > 0.0) {
        RandomStream rng(seed_, "validation_shape.roughness");
        // Periodic over twice the width, so the two ends are not forced to match.
        rough = rough_profile(xs, -width_nm_, width_nm_, {correlation_nm_, -1.0, 1.0}, rng);
        double mean = 0.0, sq = 0.0;
        for (double v : rough) mean += v;
        mean /= static_cast<double>(rough.size());
        for (double v : rough) sq += (v - mean) * (v - mean);
        const double scale = sq > 0.0 ? rms_nm_ / std::sqrt(sq / static_cast<double>(rough.size())) : 0.0;
        for (double& v : rough) v = (v - mean) * scale;
      }
      auto flat = [&](double z) {  // the interface at depth −z: arc (or line) plus the profile
        Polyline p;
        for (std::size_t k = 0; k < xs.size(); ++k) {
          const double x = xs[k];
          const double base = radius_nm_ > 0.0
                                  ? std::sqrt((radius_nm_ + z) * (radius_nm_ + z) - x * x) - radius_nm_
                                  : z;
          p.push_back({x, base + rough[k]});
        }
        return p;
      };
      cs.top = flat(0.0);
      double depth = 0.0;
      std::vector<Polyline> interfaces;
      for (std::size_t k = 0; k < stack_.layers.size(); ++k) {
        depth += stack_.layers[k].thickness_nm;
        interfaces.push_back(flat(-depth));
      }
      cs.bottom = interfaces.back();
      cs.regions.push_back({band_polygon(cs.top, cs.bottom), stack_.layers[0].material, RegionRole::body});
      model.below_top = stack_.layers[0].material;
      for (std::size_t k = 0; k < interfaces.size(); ++k) {
        const bool last = k + 1 == interfaces.size();
        const Material below = last ? stack_.substrate : stack_.layers[k + 1].material;
        model.boundaries.push_back({interfaces[k], below, {}, -1});
        if (!last) {
          cs.regions.push_back({band_polygon(interfaces[k], interfaces[k + 1]), below, RegionRole::film, 0,
                                static_cast<int>(k + 1)});
        }
      }
    }
    cs.layered = std::move(model);
    return cs;
  }

 private:
  Shape shape_ = Shape::circle;
  double radius_ = 0, coating_nm_ = 0, width_nm_ = 0, spacing_ = 5;
  CirclePolygon polygon_ = CirclePolygon::area_preserving;
  double radius_nm_ = 0;  // slab: curved top (0: flat)
  double rms_nm_ = 0, correlation_nm_ = 1000;  // slab: roughness (rms 0: none)
  std::uint64_t seed_ = 1;
  Material material_ = Material::keratin(), core_ = Material::melanin();
  LayerProfile stack_;
};

}  // namespace

void register_validation_shape(PluginRegistry& registry) {
  registry.builtin_registrar().add<StructureGenerator>(
      {.type = "validation_shape",
       .version = "1.1.0",
       .summary = "shapes with exact solutions (circle, coated circle, flat layered slab) and curved / rough "
                  "slabs for solver validation",
       .params = shape_params().specs()},
      [](const ParamView& p, const PluginContext&) { return std::make_unique<ValidationShape>(p); });
}

}  // namespace plumage
