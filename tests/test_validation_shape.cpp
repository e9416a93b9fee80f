// structure_generator "validation_shape" (core/src/geometry/validation_shape.cpp): its parameter
// table reads each shape's own parameters, defaults the vertex spacing per shape, and refuses
// parameters of another shape and inconsistent values, naming the parameter.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "plumage/config_document.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;

namespace {

CrossSection generate(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "shape.yaml");
  const PluginRegistry& registry = plumage::testing::registry();
  return registry.create_named<StructureGenerator>("validation_shape", doc.root(), registry.context())->generate(0);
}

std::string error_of(const std::string& yaml) {
  try {
    generate(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

// Shoelace area of a closed outline (either orientation).
double polygon_area(const Polygon& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % p.size()];
    a += u.x * v.z - v.x * u.z;
  }
  return 0.5 * std::abs(a);
}

}  // namespace

// Issue 28: the validation circles have the circle's area by default (the exact series is for the
// circle, and an inscribed polygon is smaller by ≈ (2π/N)²/6); `polygon: inscribed` keeps the
// vertices on the circle.
TEST_CASE("validation_shape: circles are area-preserving polygons unless inscribed is asked", "[validation-shape]") {
  const double pi = std::acos(-1.0);
  for (const double r : {100.0, 250.0, 1000.0}) {
    const std::string base = "{shape: circle, radius_nm: " + std::to_string(r) + ", spacing_nm: 20";
    const CrossSection exact = generate(base + "}");
    const CrossSection inscribed = generate(base + ", polygon: inscribed}");
    const double disc = pi * r * r;
    CHECK(polygon_area(exact.regions[0].outline) == Approx(disc).epsilon(1e-12));
    const double n_total = 2.0 * static_cast<double>(inscribed.top.size() - 1);
    CHECK(polygon_area(inscribed.regions[0].outline) ==
          Approx(0.5 * n_total * r * r * std::sin(2.0 * pi / n_total)).epsilon(1e-12));
    for (const Vec2& v : inscribed.top) CHECK(std::hypot(v.x, v.z) == Approx(r).epsilon(1e-12));
    CHECK(polygon_area(inscribed.regions[0].outline) < disc * (1.0 - 1e-5));
  }
  const CrossSection coated = generate("{shape: coated_circle, radius_nm: 350, coating_nm: 100, spacing_nm: 10}");
  CHECK(polygon_area(coated.regions[1].outline) == Approx(pi * 250.0 * 250.0).epsilon(1e-12));
  CHECK_THAT(error_of("{shape: slab, width_um: 1, polygon: inscribed, stack: {layers: [{material: keratin, "
                      "thickness_nm: 300}]}}"),
             Catch::Contains("polygon"));
}

TEST_CASE("validation_shape: each shape reads its parameters, spacing defaults per shape", "[validation-shape]") {
  // half circle of radius 250 nm at 5 nm: ceil(pi 250 / 5) = 158 segments
  CHECK(generate("{shape: circle, radius_nm: 250}").top.size() == 159);
  CHECK(generate("{shape: circle, radius_nm: 250, spacing_nm: 10}").top.size() == 80);
  const CrossSection coated = generate("{shape: coated_circle, radius_nm: 350, coating_nm: 100}");
  REQUIRE(coated.regions.size() == 2);
  CHECK(coated.regions[1].material.kind() == Material::Kind::melanin);  // core default
  CHECK(coated.regions[0].material.kind() == Material::Kind::keratin);  // coating default
  // slab 4 um wide at 30 nm: ceil(4000 / 30) = 134 segments
  const std::string slab = "{shape: slab, width_um: 4, stack: {layers: [{material: keratin, thickness_nm: 300}]}";
  CHECK(generate(slab + "}").top.size() == 135);
  const CrossSection rough = generate(slab + ", roughness: {rms_nm: 20, correlation_um: 0.5}}");
  double dz = 0.0;
  for (const Vec2& v : rough.top) dz = std::max(dz, std::abs(v.z));
  CHECK(dz > 10.0);  // a fixed rough profile of rms 20 nm (seed 1)
}

TEST_CASE("validation_shape: parameters of another shape and inconsistent values are errors", "[validation-shape]") {
  CHECK_THAT(error_of("{shape: circle, radius_nm: 250, coating_nm: 10}"), Catch::Contains("unknown key 'coating_nm'"));
  CHECK_THAT(error_of("{shape: slab, width_um: 4}"), Catch::Contains("stack"));
  CHECK_THAT(error_of("{shape: coated_circle, radius_nm: 100, coating_nm: 100}"),
             Catch::Contains("coating_nm") && Catch::Contains("thinner than the radius"));
  CHECK_THAT(error_of("{shape: ellipse, radius_nm: 100}"), Catch::Contains("shape"));
  CHECK_THAT(error_of("{shape: slab, width_um: 4, stack: {layers: [{material: keratin, thickness_nm: 300}]}, "
                      "roughness: {rms_nm: 20}}"),
             Catch::Contains("roughness.correlation_um"));
  CHECK_THAT(error_of("{shape: slab, width_um: 4, stack: {layers: [{material: keratin, thickness_nm: 300}]}, "
                      "radius_um: 1}"),
             Catch::Contains("radius_um"));
}

TEST_CASE("validation_shape: the registry documents the table, nested rows included", "[validation-shape]") {
  const auto* entry = plumage::testing::registry().find(StructureGenerator::plugin_kind, "validation_shape");
  REQUIRE(entry != nullptr);
  bool spacing = false, seed = false;
  for (const ParamSpec& p : entry->info.params) {
    if (p.name == "spacing_nm") spacing = p.default_value == "5 (circles), 30 (slab)" && p.range == "> 0";
    if (p.name == "roughness.seed") seed = p.default_value == "1" && p.condition == "shape: slab";
  }
  CHECK(spacing);
  CHECK(seed);
}
