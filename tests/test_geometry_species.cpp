// Every shipped species, through its plug-in: all 36 variants present and valid, geometric
// validity over many seeds, determinism across threads, and file:line errors for bad configs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "plumage/cross_section_io.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::registry;

const std::vector<std::string> kSpecies{"rockdove", "starling", "bronzewing", "hummingbird",
                                        "mallard",  "magpie",   "peacock"};

fs::path species_file(const std::string& s) {
  return fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / (s + ".yaml");
}

fs::path write_temp(const std::string& name, const std::string& text) {
  fs::path dir = fs::temp_directory_path() / "plumage-test-geometry-species";
  fs::create_directories(dir);
  fs::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

// Bitwise identity of everything an instance holds.
bool same(const Polyline& a, const Polyline& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](Vec2 p, Vec2 q) {
           return std::memcmp(&p, &q, sizeof(Vec2)) == 0;
         });
}

bool identical(const CrossSection& a, const CrossSection& b) {
  if (a.seed != b.seed || !same(a.top, b.top) || !same(a.bottom, b.bottom)) return false;
  if (a.top_roughness_nm != b.top_roughness_nm || a.regions.size() != b.regions.size()) return false;
  for (std::size_t i = 0; i < a.regions.size(); ++i) {
    if (!same(a.regions[i].outline, b.regions[i].outline) || a.regions[i].parent != b.regions[i].parent ||
        a.regions[i].material.name() != b.regions[i].material.name()) {
      return false;
    }
  }
  if (a.layered.has_value() != b.layered.has_value() || a.crystal.has_value() != b.crystal.has_value()) return false;
  if (a.layered) {
    if (a.layered->boundaries.size() != b.layered->boundaries.size()) return false;
    for (std::size_t i = 0; i < a.layered->boundaries.size(); ++i) {
      if (!same(a.layered->boundaries[i].points, b.layered->boundaries[i].points) ||
          a.layered->boundaries[i].fraction != b.layered->boundaries[i].fraction) {
        return false;
      }
    }
  }
  if (a.crystal && a.crystal->regularity != b.crystal->regularity) return false;
  return true;
}

void sweep(int seeds) {
  for (const auto& s : kSpecies) {
    auto cfg = load_species_config(species_file(s), registry());
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < seeds; ++k) {
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
      const auto problems = validate(cs);
      INFO(s << " instance " << k << ": " << (problems.empty() ? "" : problems.front()));
      REQUIRE(problems.empty());
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    WARN(s << ": " << seeds << " instances generated and validated in " << seconds << " s");
  }
}

}  // namespace

TEST_CASE("all seven species and their 36 variants are configs with a structure", "[geometry][species]") {
  const std::map<std::string, int> expected{{"rockdove", 6}, {"starling", 8}, {"bronzewing", 7},
                                            {"hummingbird", 1}, {"mallard", 4}, {"magpie", 8},
                                            {"peacock", 2}};
  int total = 0;
  for (const auto& [s, n] : expected) {
    INFO(s);
    const auto variants = species_variants(species_file(s));
    CHECK(static_cast<int>(variants.size()) == n);
    for (const auto& v : variants) {
      INFO(v);
      auto cfg = load_species_config(species_file(s), registry(), v);
      REQUIRE(cfg.structure);
      for (std::uint64_t k = 0; k < 2; ++k) CHECK(validate(cfg.structure->generate(k)).empty());
      ++total;
    }
  }
  CHECK(total == 36);
}

// Run as their own ctest entries (tests/CMakeLists.txt): geometry_validity (default suite) and
// geometry_sweep (label `validation`).
TEST_CASE("geometric validity of every species over 100 seeds", "[.][geometry-validity]") {
  sweep(100);
}

TEST_CASE("geometric validity of every species over 1000 seeds", "[.][geometry-sweep]") { sweep(1000); }

TEST_CASE("instances are identical whatever the thread count", "[geometry][species][determinism]") {
  for (const auto& s : {std::string("bronzewing"), std::string("hummingbird"), std::string("magpie")}) {
    auto cfg = load_species_config(species_file(s), registry());
    const int n = 8;
    std::vector<CrossSection> serial(n), parallel(n);
    for (int k = 0; k < n; ++k) serial[static_cast<std::size_t>(k)] = cfg.structure->generate(static_cast<std::uint64_t>(k));
    // Four threads, each taking every fourth instance in reverse order.
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
      threads.emplace_back([&, t] {
        for (int k = n - 1 - t; k >= 0; k -= 4) {
          parallel[static_cast<std::size_t>(k)] = cfg.structure->generate(static_cast<std::uint64_t>(k));
        }
      });
    }
    for (auto& th : threads) th.join();
    for (int k = 0; k < n; ++k) CHECK(identical(serial[static_cast<std::size_t>(k)], parallel[static_cast<std::size_t>(k)]));
    // Instances differ from each other, and a fresh generator reproduces them.
    CHECK_FALSE(identical(serial[0], serial[1]));
    auto again = load_species_config(species_file(s), registry());
    CHECK(identical(again.structure->generate(5), serial[5]));
  }
}

TEST_CASE("bad structure configs fail with file:line", "[geometry][species][config]") {
  const std::string good =
      "species: twofilm\n"
      "structure:\n"
      "  generator: layered_barbule\n"
      "  model: films\n"
      "  cortex_nm: 200\n"
      "  films:\n"
      "    - {material: melanin, thickness_nm: 100}\n"
      "    - {material: melanin, thickness_nm: 100}\n"
      "  film_spacing_nm: 150\n"
      "  outline:\n"
      "    shape: pillow\n"
      "    width_um: 20\n"
      "    thickness_um: 3\n"
      "    roughness: {correlation_um: 1.0, range_um: [-0.1, 0.1]}\n";
  REQUIRE_NOTHROW(load_species_config(write_temp("good.yaml", good), registry()));
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  CHECK_THROWS_WITH(load_species_config(write_temp("neg.yaml", replaced("thickness_nm: 100}\n  film", "thickness_nm: -100}\n  film")), registry()),
                    Catch::Contains("neg.yaml:8:") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(load_species_config(write_temp("empty.yaml", replaced(
                        "    - {material: melanin, thickness_nm: 100}\n    - {material: melanin, thickness_nm: 100}\n", "    []\n")), registry()),
                    Catch::Contains("empty.yaml:7:") && Catch::Contains("empty"));
  CHECK_THROWS_WITH(load_species_config(write_temp("mat.yaml", replaced("material: melanin, thickness_nm: 100}\n  film", "material: melanim, thickness_nm: 100}\n  film")), registry()),
                    Catch::Contains("mat.yaml:8:") && Catch::Contains("melanin"));
  CHECK_THROWS_WITH(load_species_config(write_temp("range.yaml", replaced("[-0.1, 0.1]", "[0.1, -0.1]")), registry()),
                    Catch::Contains("range.yaml:14:") && Catch::Contains("range_um"));
  CHECK_THROWS_WITH(load_species_config(write_temp("thick.yaml", replaced("thickness_um: 3", "thickness_um: -3")), registry()),
                    Catch::Contains("thick.yaml:13:"));
  CHECK_THROWS_WITH(load_species_config(write_temp("gen.yaml", replaced("layered_barbule", "layered_barbul")), registry()),
                    Catch::Contains("gen.yaml:3:") && Catch::Contains("did you mean 'layered_barbule'?"));
  CHECK_THROWS_WITH(load_species_config(write_temp("model.yaml", replaced("model: films", "model: flims")), registry()),
                    Catch::Contains("model.yaml:4:") && Catch::Contains("did you mean 'films'?"));
  CHECK_THROWS_WITH(load_species_config(write_temp("key.yaml", replaced("cortex_nm: 200", "cortex_mn: 200")), registry()),
                    Catch::Contains("key.yaml:3:") && Catch::Contains("missing required key 'cortex_nm'"));
  // A crystal reference that does not exist names the structure's line.
  const std::string crystal =
      "species: x\nstructure:\n  generator: crystal_barbule\n  crystal: nowhere.yaml\n"
      "  outline: {shape: pillow, width_um: 20, thickness_um: 3, roughness: {correlation_um: 1, range_um: [-0.1, 0.1]}}\n";
  CHECK_THROWS_WITH(load_species_config(write_temp("crystal.yaml", crystal), registry()),
                    Catch::Contains("crystal.yaml:4:") && Catch::Contains("no such crystal file"));
}

TEST_CASE("the worked example of docs/species.md passes the same checks", "[geometry][species][example]") {
  const fs::path file = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / "examples" / "twofilm.yaml";
  for (const auto& v : species_variants(file)) {
    INFO(v);
    auto cfg = load_species_config(file, registry(), v);
    REQUIRE(cfg.structure);
    const double cortex = v == "green" ? 190.0 : 150.0;
    for (std::uint64_t k = 0; k < 100; ++k) {
      const CrossSection cs = cfg.structure->generate(k);
      REQUIRE(validate(cs).empty());
      // The first film lies exactly `cortex` under the top along the top's normals.
      const LayerProfile p = layer_profile_at(cs, cs.top.size() / 2);
      REQUIRE(p.layers.size() == 5);
      CHECK(p.layers[0].thickness_nm == Approx(cortex).margin(1e-6));
      CHECK(p.layers[1].material.kind() == Material::Kind::melanin);
      CHECK(p.layers[1].thickness_nm == Approx(40.0).margin(1e-6));
    }
  }
}
