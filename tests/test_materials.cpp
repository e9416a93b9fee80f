// Paper Eq. 1 and the mixture rule, and the ways materials are written.
#include <catch2/catch.hpp>

#include "plumage/config_document.hpp"
#include "plumage/materials.hpp"

using namespace plumage;

TEST_CASE("keratin and melanin follow paper Eq. 1", "[materials]") {
  // Reference values computed by hand from Eq. 1.
  CHECK(Material::keratin().index(550.0).real() == Approx(1.532 + 5890.0 / (550.0 * 550.0)).epsilon(1e-15));
  CHECK(Material::keratin().index(550.0).imag() == 0.0);
  const Complex m = Material::melanin().index(550.0);
  CHECK(m.real() == Approx(1.7263).margin(1e-4));
  CHECK(m.imag() == Approx(0.0730).margin(1e-4));
  CHECK(Material::melanin().index(400.0).imag() == Approx(0.56 * std::exp(-400.0 / 270.0)).epsilon(1e-15));
  // Time convention exp(-iωt): absorption is a positive imaginary part.
  for (double l = 400; l <= 700; l += 50) CHECK(Material::melanin().index(l).imag() > 0.0);
  CHECK(Material::air().index(123.0) == Complex(1.0, 0.0));
}

TEST_CASE("mixtures are linear in the refractive index", "[materials]") {
  const auto mix = Material::mixture(Material::air(), Material::melanin(), 0.9);
  const Complex expected = 0.1 * Complex(1.0, 0.0) + 0.9 * Material::melanin().index(500.0);
  CHECK(std::abs(mix.index(500.0) - expected) < 1e-15);
  CHECK(std::abs(mix.with_fraction(0.0).index(500.0) - Complex(1.0, 0.0)) < 1e-15);
  CHECK_THROWS(Material::mixture(Material::air(), Material::melanin(), 1.5));
  CHECK(mix.name() == "mix(air, melanin, 0.9)");
}

TEST_CASE("materials parse from command-line text", "[materials]") {
  CHECK(parse_material_text("keratin").kind() == Material::Kind::keratin);
  CHECK(parse_material_text(" 1.5 ").index(500) == Complex(1.5, 0.0));
  CHECK(parse_material_text("1.7+0.05i").index(500) == Complex(1.7, 0.05));
  CHECK(parse_material_text("mix(keratin, melanin, 0.5)").kind() == Material::Kind::mixture);
  CHECK_THROWS_WITH(parse_material_text("1.7-0.05i"), Catch::Contains("not a passive medium"));
  CHECK_THROWS_WITH(parse_material_text("keratn"), Catch::Contains("did you mean 'keratin'?"));
}

TEST_CASE("materials parse from YAML, with located errors", "[materials]") {
  auto doc = ConfigDocument::parse(
      "a: melanin\nb: {n: 1.6, k: 0.01}\nc: {mix: [keratin, melanin], fraction: 0.3}\n"
      "d: melanine\ne: {mix: [keratin, melanin], fraction: 2}\n",
      "m.yaml");
  auto root = doc.root();
  CHECK(parse_material(root, "a").kind() == Material::Kind::melanin);
  CHECK(parse_material(root, "b").index(600) == Complex(1.6, 0.01));
  CHECK(parse_material(root, "c").fraction() == 0.3);
  CHECK_THROWS_WITH(parse_material(root, "d"),
                    Catch::StartsWith("m.yaml:4:4: d: unknown material 'melanine' (did you mean 'melanin'?)"));
  CHECK_THROWS_WITH(parse_material(root, "e"), Catch::StartsWith("m.yaml:5:"));
}
