#include <catch2/catch.hpp>

#include "plumage/config_document.hpp"
#include "plumage/layer_profile.hpp"

using namespace plumage;

TEST_CASE("stacks parse from command-line text", "[stack]") {
  auto p = parse_stack_text("air | keratin 300 | {melanin 90 | keratin 100}*3 | air");
  REQUIRE(p.layers.size() == 7);
  CHECK(p.layers[0].thickness_nm == 300.0);
  CHECK(p.layers[1].material.kind() == Material::Kind::melanin);
  CHECK(p.layers[6].thickness_nm == 100.0);
  CHECK(p.total_thickness_nm() == Approx(300 + 3 * 190));
  CHECK(describe(parse_stack_text("air|keratin 300|air")) == "air | keratin 300 | air");
  CHECK(parse_stack_text("air | keratin").layers.empty());  // a single interface
  CHECK_THROWS_WITH(parse_stack_text("air | keratin thick | air"), Catch::Contains("not a number"));
  CHECK_THROWS_WITH(parse_stack_text("air | keratin -3 | air"), Catch::Contains("negative"));
  CHECK_THROWS_WITH(parse_stack_text("air | {keratin 3 | air"), Catch::Contains("unbalanced"));
  CHECK_THROWS(parse_stack_text("air"));
}

TEST_CASE("stacks parse from YAML with repeat groups and located errors", "[stack]") {
  auto doc = ConfigDocument::parse(
      "ok:\n"
      "  layers:\n"
      "    - {material: keratin, thickness_nm: 12}\n"
      "    - {repeat: 2, layers: [{material: melanin, thickness_nm: 90}, {material: keratin, thickness_nm: 100}]}\n"
      "  substrate: keratin\n"
      "empty: {layers: []}\n"
      "negative: {layers: [{material: keratin, thickness_nm: -1}]}\n"
      "typo: {layers: [{material: keratin, thicknes_nm: 1}]}\n",
      "s.yaml");
  auto root = doc.root();
  auto p = parse_layer_profile(root.child("ok"));
  CHECK(p.layers.size() == 5);
  CHECK(p.substrate.kind() == Material::Kind::keratin);
  CHECK_THROWS_WITH(parse_layer_profile(root.child("empty")), Catch::StartsWith("s.yaml:6:") && Catch::Contains("no layers"));
  CHECK_THROWS_WITH(parse_layer_profile(root.child("negative")), Catch::StartsWith("s.yaml:7:") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(parse_layer_profile(root.child("typo")), Catch::StartsWith("s.yaml:8:"));
}
