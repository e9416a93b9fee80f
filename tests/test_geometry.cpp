// Core geometry: counter-based randomness, rough profiles, layer profiles along normals, the
// validity checker, validation shapes and crystal cells.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "plumage/crystal_cell.hpp"
#include "plumage/geometry.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

const PluginRegistry& builtin_registry() { return plumage::testing::registry(); }

fs::path write_temp(const std::string& name, const std::string& text) {
  fs::path dir = fs::temp_directory_path() / "plumage-test-geometry";
  fs::create_directories(dir);
  fs::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

}  // namespace

TEST_CASE("random streams are counter-based and uniform", "[geometry][random]") {
  RandomStream a(42, "top"), b(42, "top"), c(42, "bottom");
  for (int i = 0; i < 10; ++i) CHECK(a.next_u64() == b.next_u64());
  CHECK(RandomStream(42, "top").at(5) == RandomStream(42, "top").at(5));
  CHECK(RandomStream(42, "top").at(5) != c.at(5));
  CHECK(instance_seed("rockdove", "forest", 0) != instance_seed("rockdove", "forest", 1));
  CHECK(instance_seed("rockdove", "forest", 0) != instance_seed("rockdove", "jade", 0));
  // Known value: the seed derivation is part of the file formats' meaning; it must not drift.
  CHECK(instance_seed("rockdove", "forest", 0) == instance_seed("rockdove", "forest", 0));
  RandomStream u(7);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = u.uniform();
    REQUIRE(x >= 0.0);
    REQUIRE(x < 1.0);
    sum += x;
    sum2 += x * x;
  }
  CHECK(sum / n == Approx(0.5).margin(0.003));
  CHECK(sum2 / n - (sum / n) * (sum / n) == Approx(1.0 / 12.0).margin(0.001));
}

TEST_CASE("rough profiles: exact range, Gaussian correlation, permutation", "[geometry][rough]") {
  const double W = 40000.0;
  std::vector<double> xs;
  for (int i = 0; i <= 1333; ++i) xs.push_back(-0.5 * W + W * i / 1333.0);
  for (double tau : {200.0, 1000.0, 1500.0}) {
    std::vector<double> acc;
    double step = 0.0;
    for (int k = 0; k < 200; ++k) {
      RandomStream rng(instance_seed("test", "rough", static_cast<std::uint64_t>(k)), "p");
      const auto v = rough_profile(xs, -0.5 * W, 0.5 * W, {tau, -300.0, 300.0}, rng);
      CHECK(*std::min_element(v.begin(), v.end()) == -300.0);
      CHECK(*std::max_element(v.begin(), v.end()) == 300.0);
      const auto c = circular_autocovariance(xs, v, 2048, 1024, step);
      if (acc.empty()) acc.assign(c.size(), 0.0);
      for (std::size_t j = 0; j < c.size(); ++j) acc[j] += c[j];
    }
    const double measured = gaussian_correlation_length(acc, step);
    INFO("tau " << tau << " measured " << measured);
    CHECK(measured == Approx(tau).epsilon(0.05));
  }
  RandomStream rng(3);
  const auto p = rough_profile(xs, -0.5 * W, 0.5 * W, {1500.0, -250.0, 250.0}, rng, true);
  CHECK(p.front() == Approx(-250.0).margin(2.0));  // the minimum moved to the left end
  RandomStream bad(1);
  CHECK_THROWS(rough_profile(xs, -0.5 * W, 0.5 * W, {1500.0, 1.0, -1.0}, bad));
}

TEST_CASE("validation shapes load like species and have the exact stacks", "[geometry][validation]") {
  const fs::path dir = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "validation";
  int count = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".yaml") continue;
    INFO(e.path());
    auto cfg = load_species_config(e.path(), builtin_registry());
    REQUIRE(cfg.structure);
    const CrossSection cs = cfg.structure->generate(0);
    CHECK(validate(cs).empty());
    ++count;
  }
  CHECK(count >= 3);

  auto cyl = load_species_config(dir / "keratin-cylinder.yaml", builtin_registry());
  const CrossSection c = cyl.structure->generate(0);
  // Area-preserving polygon (issue 28): the circle's area exactly, so its vertices lie at
  // r·sqrt(step/sin step), step = π/n for n segments per half.
  CHECK(signed_area(c.regions[0].outline) == Approx(kPi * 250.0 * 250.0).epsilon(1e-12));
  const double step = kPi / static_cast<double>(c.top.size() - 1);
  const auto mid = layer_profile_at(c, c.top.size() / 2);
  REQUIRE(mid.layers.size() == 1);
  CHECK(mid.layers[0].thickness_nm == Approx(500.0 * std::sqrt(step / std::sin(step))).epsilon(1e-9));

  auto coated = load_species_config(dir / "coated-cylinder.yaml", builtin_registry());
  const CrossSection cc = coated.structure->generate(0);
  const auto centre = layer_profile_at(cc, cc.top.size() / 2);
  REQUIRE(centre.layers.size() == 3);  // coating | core | coating
  CHECK(centre.layers[0].thickness_nm == Approx(100.0).epsilon(1e-3));  // polygonal circles
  CHECK(centre.layers[1].material.kind() == Material::Kind::melanin);
  CHECK(centre.layers[1].thickness_nm == Approx(300.0).epsilon(1e-3));
  // Every normal of a circle is radial: near the rim too it crosses coating | core | coating.
  const auto rim = layer_profile_at(cc, 2);
  REQUIRE(rim.layers.size() == 3);
  CHECK(rim.layers[1].thickness_nm == Approx(300.0).epsilon(1e-3));
  // A bracket the normal misses is skipped: shift the core aside and look from the far side.
  CrossSection shifted = cc;
  for (int b = 0; b < 2; ++b) {
    for (Vec2& p : shifted.layered->boundaries[static_cast<std::size_t>(b)].points) p.x += 400.0;
  }
  const auto missed = layer_profile_at(shifted, shifted.top.size() / 4);
  REQUIRE(missed.layers.size() == 1);
  CHECK(missed.layers[0].material.kind() == Material::Kind::keratin);

  auto slab = load_species_config(dir / "keratin-film-slab.yaml", builtin_registry());
  const CrossSection s = slab.structure->generate(0);
  CHECK(s.width_nm() == Approx(40000.0));
  for (const auto& p : layer_profiles(s)) {
    REQUIRE(p.layers.size() == 1);
    CHECK(p.layers[0].thickness_nm == Approx(300.0).epsilon(1e-9));
  }
}

TEST_CASE("the validity check finds crossings, bad nesting and overlaps", "[geometry][validity]") {
  auto slab = load_species_config(fs::path(PLUMAGE_SOURCE_DIR) / "configs/validation/melanin-keratin-slab.yaml",
                                  builtin_registry());
  const CrossSection good = slab.structure->generate(0);
  REQUIRE(validate(good).empty());

  CrossSection bent = good;
  std::swap(bent.top[10], bent.top[11]);
  CHECK_THAT(validate(bent).front(), Catch::Contains("not monotone"));

  CrossSection outside = good;  // a child that pokes out of its parent
  outside.regions.push_back({circle_polygon({0.0, 0.0}, 50.0, 16), Material::air(), RegionRole::air_bubble, 0});
  CHECK_FALSE(validate(outside).empty());

  CrossSection stray = good;  // a child entirely outside its parent
  stray.regions.push_back({circle_polygon({0.0, 5000.0}, 50.0, 16), Material::air(), RegionRole::air_bubble, 0});
  CHECK_THAT(validate(stray).front(), Catch::Contains("not properly nested"));

  CrossSection overlap = good;  // two siblings on top of each other
  overlap.regions.push_back({circle_polygon({0.0, -400.0}, 40.0, 16), Material::air(), RegionRole::air_bubble, 1});
  overlap.regions.push_back({circle_polygon({10.0, -400.0}, 40.0, 16), Material::air(), RegionRole::air_bubble, 1});
  CHECK_FALSE(validate(overlap).empty());

  CrossSection nested = good;  // properly nested: melanin disc with an air core in the keratin film
  nested.regions.push_back({circle_polygon({0.0, -350.0}, 40.0, 16), Material::melanin(), RegionRole::rod, 1});
  const int rod = static_cast<int>(nested.regions.size()) - 1;
  nested.regions.push_back({circle_polygon({0.0, -350.0}, 20.0, 16), Material::air(), RegionRole::core, rod});
  CHECK(validate(nested).empty());
  CrossSection wrong_parent = nested;  // the same disc claiming the body as its parent
  wrong_parent.regions[static_cast<std::size_t>(rod)].parent = 0;
  CHECK_THAT(validate(wrong_parent).front(), Catch::Contains("not properly nested"));

  CrossSection twisted = good;  // a self-intersecting outline
  twisted.regions.push_back({{{-100, -300}, {100, -300}, {-100, -400}, {100, -400}}, Material::air(),
                             RegionRole::air_bubble, 0});
  CHECK_FALSE(validate(twisted).empty());
}

TEST_CASE("crystal cells: the 14 shipped cells parse; bad cells fail at their line", "[geometry][crystal]") {
  int count = 0;
  for (const auto& e : fs::directory_iterator(fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "crystals")) {
    INFO(e.path());
    const CrystalCell c = load_crystal_cell(e.path());
    CHECK(c.name == e.path().stem().string());
    ++count;
  }
  CHECK(count == 14);
  const std::string base =
      "crystal:\n  name: x\n  lattice: hexagonal\n  a_x_nm: 180\n  a_z_nm: 145\n"
      "  rod_diameter_nm: 162\n  rows: 4\n  cortex_nm: 50\n";
  CHECK_NOTHROW(load_crystal_cell(write_temp("ok.yaml", base)));
  std::string squeezed = base;
  squeezed.replace(squeezed.find("a_z_nm: 145"), 11, "a_z_nm: 120");
  CHECK_THROWS_WITH(load_crystal_cell(write_temp("squeezed.yaml", squeezed)),
                    Catch::Contains("squeezed.yaml:5:") && Catch::Contains("overlap"));
  std::string neg = base;
  neg.replace(neg.find("cortex_nm: 50"), 13, "cortex_nm: -5");
  CHECK_THROWS_WITH(load_crystal_cell(write_temp("neg.yaml", neg)), Catch::Contains("neg.yaml:8:"));
  std::string mat = base + "  materials: {rod: melanine}\n";
  CHECK_THROWS_WITH(load_crystal_cell(write_temp("mat.yaml", mat)),
                    Catch::Contains("mat.yaml:9:") && Catch::Contains("melanin"));
}

TEST_CASE("crystal cells: a map under another key is a table builder's section, kept unread", "[geometry][crystal]") {
  const std::string base =
      "crystal:\n  name: x\n  lattice: hexagonal\n  a_x_nm: 180\n  a_z_nm: 145\n"
      "  rod_diameter_nm: 162\n  rows: 4\n  cortex_nm: 50\n";
  // Core does not read the section: its keys (even unknown ones) are the builder's to check.
  const CrystalCell c = load_crystal_cell(write_temp("section.yaml", base + "  some_builder: {step_nm: 7, typo: 1}\n"));
  REQUIRE(c.builder_sections.count("some_builder") == 1);
  const ParamView& section = c.builder_sections.at("some_builder");
  CHECK(section.number("step_nm") == 7.0);
  CHECK(section.mark().line == 9);
  CHECK(section.path() == "crystal.some_builder");
  CHECK_THROWS_WITH(section.finish(), Catch::Contains("section.yaml:9:") && Catch::Contains("typo"));
  // The shipped cells keep their builder settings in the builder's section.
  const CrystalCell peacock = load_crystal_cell(fs::path(PLUMAGE_SOURCE_DIR) / "configs/crystals/peacock-cyan.yaml");
  REQUIRE(peacock.builder_sections.count("fdtd_periodic") == 1);
  CHECK(peacock.builder_sections.at("fdtd_periodic").keys().size() == 4);
  // The rcwa builder's section, although `rcwa` is two edits from the scalar field `rows`.
  CHECK(load_crystal_cell(write_temp("rcwa.yaml", base + "  rcwa: {harmonics: 7}\n")).builder_sections.count("rcwa") == 1);
  // Not a section: a scalar under an unknown key, or a map one typo away from a cell field.
  CHECK_THROWS_WITH(load_crystal_cell(write_temp("scalar.yaml", base + "  step_nm: 7\n")),
                    Catch::Contains("unknown key 'step_nm'"));
  CHECK_THROWS_WITH(load_crystal_cell(write_temp("near.yaml", base + "  material: {rod: air}\n")),
                    Catch::Contains("near.yaml:9:") && Catch::Contains("did you mean 'materials'"));
}
