// structure_generator "validation_shape" (built into core): shapes with exact solutions for the
// solvers' validation ladder (DESIGN §9, rungs 3–4), usable from configs like a species.
//
// | name        | type     | unit | default  | meaning                                                  |
// |-------------|----------|------|----------|----------------------------------------------------------|
// | shape       | text     | -    | required | circle, coated_circle or slab                            |
// | radius_nm   | number   | nm   | required | circle, coated_circle: outer radius                      |
// | material    | material | -    | keratin  | circle: the cylinder's material                          |
// | coating_nm  | number   | nm   | required | coated_circle: coating thickness (< radius)              |
// | core        | material | -    | melanin  | coated_circle: core material                             |
// | coating     | material | -    | keratin  | coated_circle: coating material                          |
// | width_um    | number   | um   | required | slab: width of the flat top                              |
// | stack       | map      | -    | required | slab: layers (top → bottom) and substrate (air only)     |
// | spacing_nm  | number   | nm   | 5 / 30   | vertex spacing on curves (circles 5, slab 30)            |
// | radius_um   | number   | um   | flat     | slab: curved top, a circular arc of this radius (apex at |
// |             |          |      |          | z = 0); interfaces are concentric arcs (> W/2 + depth)   |
// | roughness   | map      | -    | none     | slab: {rms_nm, correlation_um, seed}: a Gaussian-        |
// |             |          |      |          | correlated height profile added to every interface       |
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
#include <array>
#include <cmath>

#include "plumage/builtin_plugins.hpp"
#include "plumage/geometry.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

namespace {

// Half circle from angle π to 0 (upper, x increasing) or π to 2π (lower, x increasing).
Polyline half_circle(double r, bool upper, double spacing) {
  const int n = std::max(16, static_cast<int>(std::ceil(kPi * r / spacing)));
  Polyline p;
  for (int k = 0; k <= n; ++k) {
    const double t = kPi - kPi * k / n;
    p.push_back({r * std::cos(t), (upper ? 1.0 : -1.0) * r * std::sin(t)});
  }
  p.front() = {-r, 0.0};
  p.back() = {r, 0.0};
  return p;
}

class ValidationShape final : public StructureGenerator {
 public:
  explicit ValidationShape(const ParamView& p) {
    static constexpr std::array<std::string_view, 3> shapes{"circle", "coated_circle", "slab"};
    shape_ = p.choice("shape", shapes);
    if (shape_ == "circle") {
      radius_ = p.number("radius_nm", Limits::positive());
      material_ = p.has("material") ? parse_material(p, "material") : Material::keratin();
      spacing_ = p.number_or("spacing_nm", 5.0, Limits::positive());
    } else if (shape_ == "coated_circle") {
      radius_ = p.number("radius_nm", Limits::positive());
      coating_nm_ = p.number("coating_nm", Limits::positive());
      if (coating_nm_ >= radius_) p.fail("coating_nm", "the coating must be thinner than the radius");
      core_ = p.has("core") ? parse_material(p, "core") : Material::melanin();
      material_ = p.has("coating") ? parse_material(p, "coating") : Material::keratin();
      spacing_ = p.number_or("spacing_nm", 5.0, Limits::positive());
    } else {
      width_nm_ = 1000.0 * p.number("width_um", Limits::positive());
      stack_ = parse_layer_profile(p.child("stack"));
      if (stack_.ambient.kind() != Material::Kind::air || stack_.substrate.kind() != Material::Kind::air) {
        p.fail("stack", "a slab stands in air: ambient and substrate must be air");
      }
      spacing_ = p.number_or("spacing_nm", 30.0, Limits::positive());
      double depth = 0.0;
      for (const auto& layer : stack_.layers) depth += layer.thickness_nm;
      if (p.has("radius_um")) {
        radius_nm_ = 1000.0 * p.number("radius_um", Limits::positive());
        if (radius_nm_ - depth <= 0.5 * width_nm_) {
          p.fail("radius_um", "the deepest interface's arc must span the width: radius > width/2 + stack depth");
        }
      }
      if (auto r = p.child_if("roughness")) {
        rms_nm_ = r->number("rms_nm", Limits::at_least(0.0));
        correlation_nm_ = 1000.0 * r->number("correlation_um", Limits::positive());
        seed_ = static_cast<std::uint64_t>(r->integer_or("seed", 1, Limits::at_least(0.0)));
      }
    }
  }

  CrossSection generate(std::uint64_t index) const override {
    CrossSection cs = start("validation_shape", index);
    LayeredModel model;
    if (shape_ == "circle" || shape_ == "coated_circle") {
      cs.top = half_circle(radius_, true, spacing_);
      cs.bottom = half_circle(radius_, false, spacing_);
      cs.regions.push_back({band_polygon(cs.top, cs.bottom), material_, RegionRole::body});
      model.below_top = material_;
      if (shape_ == "coated_circle") {
        const double ri = radius_ - coating_nm_;
        Polyline up = half_circle(ri, true, spacing_), down = half_circle(ri, false, spacing_);
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
  std::string shape_;
  double radius_ = 0, coating_nm_ = 0, width_nm_ = 0, spacing_ = 5;
  double radius_nm_ = 0;  // slab: curved top (0: flat)
  double rms_nm_ = 0, correlation_nm_ = 1000;  // slab: roughness (rms 0: none)
  std::uint64_t seed_ = 1;
  Material material_ = Material::keratin(), core_ = Material::melanin();
  LayerProfile stack_;
};

}  // namespace

void register_validation_shape(PluginRegistry& registry) {
  registry.builtin_registrar().add<StructureGenerator>(
      {.kind = "",
       .type = "validation_shape",
       .version = "1.1.0",
       .summary = "shapes with exact solutions (circle, coated circle, flat layered slab) and curved / rough "
                  "slabs for solver validation",
       .params = {
           {"shape", "text", "-", "required", "circle, coated_circle or slab"},
           {"radius_nm", "number", "nm", "required", "circle, coated_circle: outer radius"},
           {"material", "material", "-", "keratin", "circle: the cylinder's material"},
           {"coating_nm", "number", "nm", "required", "coated_circle: coating thickness (< radius)"},
           {"core", "material", "-", "melanin", "coated_circle: core material"},
           {"coating", "material", "-", "keratin", "coated_circle: coating material"},
           {"width_um", "number", "um", "required", "slab: width of the flat top"},
           {"stack", "map", "-", "required", "slab: layers (top to bottom) and substrate (air)"},
           {"spacing_nm", "number", "nm", "5 / 30", "vertex spacing (circles 5, slab 30)"},
           {"radius_um", "number", "um", "flat", "slab: curved top, circular arc of this radius; concentric interfaces"},
           {"roughness", "map", "-", "none",
            "slab: {rms_nm, correlation_um, seed}: Gaussian-correlated height profile added to every interface"},
       }},
      [](const ParamView& p, const PluginContext&) { return std::make_unique<ValidationShape>(p); });
}

}  // namespace plumage
