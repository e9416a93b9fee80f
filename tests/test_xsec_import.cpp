// Imported cross sections (issue 25 (a)): read_cross_section_text reads back exactly what
// write_cross_section_text wrote (instance 0 of every variant of every shipped layered species,
// and a crystal species, field by field, bit for bit); a species config whose structure is
// `xsec_file` over the files `plumage geometry` writes simulates to the procedural species' far
// field; damaged files are refused with InputFileError naming the file and the line.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "plumage/cross_section_io.hpp"
#include "plumage/input_file.hpp"
#include "plumage/instance_geometry.hpp"
#include "plumage/simulation.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

const fs::path kSpecies = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "species";

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

void check_same(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!same_bits(a[k], b[k])) FAIL("value " << k << ": " << a[k] << " != " << b[k]);
  }
}

void check_same(const Polyline& a, const Polyline& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!same_bits(a[k].x, b[k].x) || !same_bits(a[k].z, b[k].z)) FAIL("vertex " << k << " differs");
  }
}

bool same_material(const Material& a, const Material& b) {
  if (a.kind() != b.kind()) return false;
  if (a.kind() == Material::Kind::constant) {
    return same_bits(a.index(550).real(), b.index(550).real()) && same_bits(a.index(550).imag(), b.index(550).imag());
  }
  if (a.kind() == Material::Kind::mixture) {
    return same_bits(a.fraction(), b.fraction()) && same_material(a.host(), b.host()) && same_material(a.guest(), b.guest());
  }
  return true;
}

// Every field of a CrossSection, exactly.
void check_same(const CrossSection& a, const CrossSection& b) {
  CHECK(a.generator == b.generator);
  CHECK(a.label == b.label);
  CHECK(a.instance == b.instance);
  CHECK(a.seed == b.seed);
  check_same(a.top, b.top);
  check_same(a.bottom, b.bottom);
  check_same(a.top_roughness_nm, b.top_roughness_nm);
  REQUIRE(a.regions.size() == b.regions.size());
  for (std::size_t i = 0; i < a.regions.size(); ++i) {
    INFO("region " << i);
    const Region &ra = a.regions[i], &rb = b.regions[i];
    check_same(ra.outline, rb.outline);
    CHECK(same_material(ra.material, rb.material));
    CHECK(ra.role == rb.role);
    CHECK(ra.parent == rb.parent);
    CHECK(ra.layer == rb.layer);
    CHECK(ra.members == rb.members);
    CHECK(same_bits(ra.size_nm, rb.size_nm));
  }
  REQUIRE(a.layered.has_value() == b.layered.has_value());
  if (a.layered) {
    CHECK(same_material(a.layered->below_top, b.layered->below_top));
    REQUIRE(a.layered->boundaries.size() == b.layered->boundaries.size());
    for (std::size_t j = 0; j < a.layered->boundaries.size(); ++j) {
      INFO("boundary " << j);
      const LayerBoundary &ba = a.layered->boundaries[j], &bb = b.layered->boundaries[j];
      check_same(ba.points, bb.points);
      CHECK(same_material(ba.below, bb.below));
      check_same(ba.fraction, bb.fraction);
      CHECK(ba.closes == bb.closes);
    }
  }
  REQUIRE(a.crystal.has_value() == b.crystal.has_value());
  if (a.crystal) {
    CHECK(a.crystal->crystal == b.crystal->crystal);
    CHECK(a.crystal->crystal_name == b.crystal->crystal_name);
    check_same(a.crystal->regularity, b.crystal->regularity);
  }
  REQUIRE(a.melanosomes.size() == b.melanosomes.size());
  for (std::size_t k = 0; k < a.melanosomes.size(); ++k) {
    const Disc &da = a.melanosomes[k], &db = b.melanosomes[k];
    CHECK((same_bits(da.center.x, db.center.x) && same_bits(da.center.z, db.center.z) &&
           same_bits(da.diameter_nm, db.diameter_nm) && da.row == db.row));
  }
}

CrossSection round_trip(const CrossSection& cs) {
  std::ostringstream text;
  write_cross_section_text(text, cs);
  return parse_cross_section_text(text.str(), "memory.xsec");
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-xsec-import" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// The text of `cs` with `edit` applied to it.
template <class Edit>
std::string edited(const CrossSection& cs, Edit edit) {
  std::ostringstream text;
  write_cross_section_text(text, cs);
  std::string s = text.str();
  edit(s);
  return s;
}

std::string error_of(const std::string& text) {
  const fs::path file = scratch("bad") / "bad.xsec";
  write_text(file, text);
  try {
    read_cross_section_text(file);
  } catch (const InputFileError& e) {
    CHECK(e.file() == file.string());
    return e.message();
  }
  return "no error";
}

}  // namespace

TEST_CASE("xsec import: every shipped layered variant and a crystal species read back exactly", "[xsec-import]") {
  for (const char* name : {"bronzewing", "hummingbird", "rockdove", "starling", "mallard"}) {
    for (const std::string& variant : species_variants(kSpecies / (std::string(name) + ".yaml"))) {
      INFO(name << "/" << variant);
      const SpeciesConfig config = testing::species(name, variant);
      const CrossSection cs = config.structure->generate(0);
      check_same(round_trip(cs), cs);
      // Written again, the bytes are the same (nothing is lost or reformatted).
      std::ostringstream once, twice;
      write_cross_section_text(once, cs);
      write_cross_section_text(twice, round_trip(cs));
      CHECK(once.str() == twice.str());
      if (std::string(name) == "mallard") CHECK(cs.crystal.has_value());
    }
  }
}

TEST_CASE("xsec import: constant and mixture materials keep every bit", "[xsec-import]") {
  CrossSection cs = testing::species("rockdove").structure->generate(0);
  cs.regions[0].material = Material::constant({1.0 / 3.0 + 1.0, 0.1 / 7.0});
  cs.layered->below_top = Material::mixture(Material::keratin(), Material::melanin(), 2.0 / 3.0);
  const CrossSection back = round_trip(cs);
  CHECK(same_material(back.regions[0].material, cs.regions[0].material));
  CHECK(same_material(back.layered->below_top, cs.layered->below_top));
}

TEST_CASE("xsec import: xsec_file over `plumage geometry`'s files simulates to the procedural far field",
          "[xsec-import]") {
  const fs::path dir = scratch("import");
  const SpeciesConfig procedural = testing::species("rockdove");
  constexpr int kInstances = 2;
  for (int n = 0; n < kInstances; ++n) {
    // What `plumage geometry --no-svg --no-png` does per instance (core/cli/cmd_geometry.cpp).
    const CheckedInstance checked = generate_checked(*procedural.structure, n);
    REQUIRE(checked.problems.empty());
    write_cross_section_files(checked.section, dir / ("rockdove-forest-" + std::to_string(n)),
                              {.svg = false, .png = false});
  }
  write_text(dir / "imported.yaml",
             "species: rockdove-imported\n"
             "reflection: {model: multilayer}\n"
             "structure: {generator: xsec_file, files: \"rockdove-forest-{index}.xsec\"}\n");
  const SpeciesConfig imported = load_species_config(dir / "imported.yaml", testing::registry());
  check_same(imported.structure->generate(1), procedural.structure->generate(1));

  SimulationRequest request;
  request.lambdas_nm = {450.0, 600.0};
  request.theta_deg = {20.0};
  request.instances = kInstances;
  const FarFieldSet a = simulate(procedural, request), b = simulate(imported, request);
  REQUIRE(a.units.size() == b.units.size());
  REQUIRE(a.units.size() == 2);
  double worst = 0.0;
  for (std::size_t u = 0; u < a.units.size(); ++u) {
    REQUIRE(a.units[u].instances.size() == kInstances);
    REQUIRE(b.units[u].instances.size() == kInstances);
    for (int n = 0; n < kInstances; ++n) {
      const FarField &fa = a.units[u].instances[n], &fb = b.units[u].instances[n];
      check_same(fa.phi_o_rad, fb.phi_o_rad);
      CHECK(fa.incident_power == fb.incident_power);
      for (int pol = 0; pol < 2; ++pol) {
        REQUIRE(fa.field[pol].size() == fb.field[pol].size());
        double scale = 0.0;
        for (const auto& e : fa.field[pol]) scale = std::max({scale, std::abs(e[0]), std::abs(e[1]), std::abs(e[2])});
        REQUIRE(scale > 0.0);
        for (std::size_t d = 0; d < fa.field[pol].size(); ++d) {
          for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(fa.field[pol][d][c] - fb.field[pol][d][c]) / scale);
        }
      }
    }
  }
  // The section is the same bit for bit, so the fields are too.
  CHECK(worst <= 1e-12);
  CHECK(worst == 0.0);
}

TEST_CASE("xsec import: xsec_file refuses missing files at `files` and instances past a list", "[xsec-import]") {
  const fs::path dir = scratch("config");
  write_text(dir / "missing.yaml",
             "species: missing\nreflection: {model: multilayer}\n"
             "structure: {generator: xsec_file, files: \"nowhere/x-{index}.xsec\"}\n");
  try {
    load_species_config(dir / "missing.yaml", testing::registry());
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("missing.yaml:3") && Catch::Contains("files") && Catch::Contains("x-0.xsec"));
  }
  const CrossSection cs = testing::species("rockdove").structure->generate(0);
  write_text(dir / "one.xsec", edited(cs, [](std::string&) {}));
  write_text(dir / "list.yaml",
             "species: list\nreflection: {model: multilayer}\n"
             "structure: {generator: xsec_file, files: [one.xsec, one.xsec]}\n");
  const SpeciesConfig listed = load_species_config(dir / "list.yaml", testing::registry());
  check_same(listed.structure->generate(1), cs);
  CHECK_THROWS_WITH(listed.structure->generate(2), Catch::Contains("instance 2") && Catch::Contains("lists 2"));
}

TEST_CASE("xsec import: damaged files are refused with the file and the line", "[xsec-import]") {
  const CrossSection cs = testing::species("rockdove").structure->generate(0);
  auto replace = [](std::string from, std::string to) {
    return [from, to](std::string& s) {
      const auto at = s.find(from);
      REQUIRE(at != std::string::npos);
      s.replace(at, from.size(), to);
    };
  };
  // Wrong header, other version.
  CHECK_THAT(error_of(edited(cs, replace("plumage-cross-section 1", "plumage-cross-sectio 1"))),
             Catch::StartsWith("line 1: not a plumage cross section"));
  CHECK_THAT(error_of(edited(cs, replace("plumage-cross-section 1", "plumage-cross-section 2"))),
             Catch::StartsWith("line 1: cross-section format version '2'"));
  // Truncated: in the middle of the top's vertices, and in the middle of a line.
  const std::string whole = edited(cs, [](std::string&) {});
  CHECK_THAT(error_of(whole.substr(0, whole.size() / 2)), Catch::StartsWith("line ") && Catch::Contains("truncated"));
  CHECK_THAT(error_of(whole.substr(0, 300)), Catch::Contains("truncated"));
  CHECK_THAT(error_of(whole.substr(0, whole.size() - 4)), Catch::Contains("truncated") || Catch::Contains("expected 'end'"));
  // A number that is not one (line 9: the top's second vertex).
  CHECK(error_of(edited(cs, [](std::string& s) {
          std::size_t at = 0;
          for (int k = 0; k < 8; ++k) at = s.find('\n', at) + 1;
          s.insert(at, "x");
        })).rfind("line 9: x: 'x", 0) == 0);
  CHECK_THAT(error_of(edited(cs, replace("\n-10000 ", "\nnan "))), Catch::StartsWith("line 8: x: nan is not finite"));
  CHECK_THAT(error_of(edited(cs, replace("\ntop_roughness", " 7\ntop_roughness"))),
             Catch::StartsWith("line 690: unexpected text"));
  // Open outline: a region of two vertices; one that repeats its first vertex.
  {
    CrossSection open = cs;
    open.regions.back().outline.resize(2);
    CHECK_THAT(error_of(edited(open, [](std::string&) {})), Catch::Contains("open outline"));
    CrossSection repeated = cs;
    repeated.regions.back().outline.push_back(repeated.regions.back().outline.front());
    CHECK_THAT(error_of(edited(repeated, [](std::string&) {})), Catch::Contains("repeats its first vertex"));
  }
  // Huge counts: over the limit, and over what the file can hold (refused before allocating).
  CHECK_THAT(error_of(edited(cs, replace("\ntop 683\n", "\ntop 4294967296\n"))), Catch::Contains("over the limit"));
  CHECK_THAT(error_of(edited(cs, replace("\nmelanosomes 0", "\nmelanosomes 100000000"))),
             Catch::Contains("cannot fit in the"));
  // Indices the solvers would follow out of the lists.
  CHECK_THAT(error_of(edited(cs, replace("region 1 air_gap parent 0", "region 1 air_gap parent 5"))),
             Catch::Contains("parent 5 of region 1"));
  CHECK_THAT(error_of(edited(cs, replace(" material keratin\n", " material unobtainium\n"))),
             Catch::Contains("unknown material 'unobtainium'"));
  CHECK_THAT(error_of(edited(cs, replace("end\n", "end\nmore\n"))), Catch::Contains("text after 'end'"));
}

TEST_CASE("xsec import: self-intersections are validate()'s, as for generated sections", "[xsec-import]") {
  CrossSection cs = testing::species("rockdove").structure->generate(0);
  std::swap(cs.regions.back().outline[1], cs.regions.back().outline[2]);  // a bow tie
  const CrossSection back = round_trip(cs);  // reads: the file is well formed
  CHECK_FALSE(validate(back).empty());
}
