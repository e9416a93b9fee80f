// structure_generator "validation_shape" (core/src/geometry/validation_shape.cpp): its parameter
// table reads each shape's own parameters, defaults the vertex spacing per shape, and refuses
// parameters of another shape and inconsistent values, naming the parameter.
#include <catch2/catch.hpp>

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

}  // namespace

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
