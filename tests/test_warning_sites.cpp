// Issue 23, "a warning that always fires says nothing": warnings say where and how much. The
// solver tells a caller's WarningSites which azimuth or instance raised a code and by how much;
// a work group keeps, per unit, how many instances raised a per-direction code; the material's
// warnings text says in what share of the units, at which directions, with what share of the
// energy, and lists the cells a render checks its paths against.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "pipeline/records.hpp"
#include "pipeline/warning_attribution.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/material_warnings.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;

namespace {

SpeciesConfig validation_config(const std::string& name) {
  return load_species_config(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs" / "validation" / (name + ".yaml"),
                             testing::registry());
}

GroupRecord group(std::uint32_t w, std::uint32_t a, int grid, double energy) {
  GroupRecord r;
  r.w = w, r.a = a;
  r.units.resize(static_cast<std::size_t>(grid));
  for (UnitRecord& u : r.units) u.energy = energy;
  return r;
}

}  // namespace

TEST_CASE("warning sites: the solver names the azimuth and the instance, with the measure", "[warnings]") {
  CapturedWarnings captured;
  const auto config = validation_config("rough-film");
  const std::vector<double> phis{0.0, deg_to_rad(-88.0)};
  WarningSites prepare_scope;
  const auto prepared = config.solver->prepare(config.structure->generate(0), config.reflection);
  REQUIRE(prepare_scope.sites().size() == 1);
  const WarningSite rough = prepare_scope.sites().front();
  CHECK(rough.code == "approx.rough_surface");
  CHECK(rough.kind == WarningSite::Item::instance);
  CHECK(rough.item == 0);
  CHECK(rough.value > 0.12);  // the rms slope, above the flat-top limit
  // The echoed message names the instance and its seed.
  CHECK_THAT(captured.echoed(), Catch::Contains("instance 0 (seed 0x"));
  CHECK_THAT(captured.message("approx.rough_surface"), Catch::Contains("instance 0 (seed 0x"));
  {
    WarningSites solve_scope;  // nested: the solve's sites land here, not in prepare_scope
    config.solver->solve(*prepared, 550.0, 0.0, phis, pattern_directions(100).phi_o_rad);
    REQUIRE(solve_scope.sites().size() == 1);
    const WarningSite& g = solve_scope.sites().front();
    CHECK(g.code == "approx.grazing");
    CHECK(g.kind == WarningSite::Item::azimuth);
    CHECK(g.item == 1);       // the −88° azimuth, not the normal one
    CHECK(g.value > 0.5);     // the horizon spill ratio beyond its limit
  }
  CHECK(prepare_scope.sites().size() == 1);
  // Without a scope warn_at is warn: counted, not collected.
  config.solver->solve(*prepared, 550.0, 0.0, phis, pattern_directions(100).phi_o_rad);
  CHECK(captured.count("approx.grazing") == 2);
}

TEST_CASE("warning sites: records keep per-unit sites, older records still parse", "[warnings]") {
  GroupRecord r = group(1, 2, 3, 0.5);
  r.warnings = {"approx.grazing"};
  const std::string old_bytes = serialize(r);  // no unit warnings: the pre-issue-23 layout
  std::size_t pos = 0;
  auto back = parse_record(old_bytes, pos);
  REQUIRE(back);
  CHECK(back->unit_warnings.empty());
  CHECK(pos == old_bytes.size());

  r.unit_warnings = {{"approx.grazing", 1, 3, std::numeric_limits<double>::infinity()}, {"approx.grazing", 2, 1, 0.7}};
  const std::string bytes = serialize(r);
  CHECK(bytes.size() > old_bytes.size());
  pos = 0;
  back = parse_record(bytes, pos);
  REQUIRE(back);
  REQUIRE(back->unit_warnings.size() == 2);
  CHECK(back->unit_warnings[0].code == "approx.grazing");
  CHECK(back->unit_warnings[0].b == 1);
  CHECK(back->unit_warnings[0].instances == 3);
  CHECK(std::isinf(back->unit_warnings[0].worst));
  CHECK(back->unit_warnings[1].worst == 0.7);
  CHECK(serialize(*back) == bytes);
}

TEST_CASE("warning sites: the material says where and how much", "[warnings]") {
  CharacterizeSettings s;
  s.grid = 4;
  s.instances = 2;
  s.lambda_nm = {400.0, 500.0};
  // 8 groups of 4 units; approx.grazing in the grazing row a = 1 at b = 1 … 4 (λ bin 0) and at
  // b = 1 of row a = 2 (λ bin 1): 5 of 32 units. Energies: 1 per unit, 4 in the flagged row.
  std::vector<GroupRecord> records;
  for (std::uint32_t w = 0; w < 2; ++w)
    for (std::uint32_t a = 1; a <= 4; ++a) records.push_back(group(w, a, 4, 1.0));
  for (std::uint32_t b = 1; b <= 4; ++b) records[0].unit_warnings.push_back({"approx.grazing", b, 2, 0.9});
  records[0].warnings = {"approx.grazing"};
  for (UnitRecord& u : records[0].units) u.energy = 4.0;
  records[5].unit_warnings.push_back({"approx.grazing", 1, 1, 3.0});
  records[5].warnings = {"approx.grazing", "fit.two_lobes"};
  std::vector<const GroupRecord*> groups;
  for (const GroupRecord& r : records) groups.push_back(&r);
  const std::string text = material_warnings(s, groups);
  INFO(text);
  // Units (5 of 32 = 15.6 %), groups (2 of 8), directions, energy (16 + 1 of 44 = 38.6 %), worst
  // measure and the instances' share (4·2 + 1 of 5·2 = 90 %).
  CHECK_THAT(text, Catch::Contains("approx.grazing: raised in 5 of 32 work units (15.6 %), in 2 of 8 work groups"));
  CHECK_THAT(text, Catch::Contains("directions theta_i >= 75.5 deg at every phi_i; |phi_i| >= 75.5 deg at theta_i "
                                   "60.0-60.0 deg"));
  CHECK_THAT(text, Catch::Contains("38.6 % of the characterised reflected energy"));
  CHECK_THAT(text, Catch::Contains("worst horizon spill ratio (lobe half-width over its distance to the horizon) 3"));
  CHECK_THAT(text, Catch::Contains("raised by 90.0 % of those units' instance solves"));
  CHECK_THAT(text, Catch::Contains("approx.grazing cells: 1:1-4 2:1-1\n"));
  // A code without sites keeps the group count.
  CHECK_THAT(text, Catch::Contains("fit.two_lobes: raised while computing 1 of 8 work groups"));

  const auto parsed = parse_material_warnings(text, s.grid);
  REQUIRE(parsed.size() == 2);
  CHECK(parsed[0].code == "approx.grazing");
  REQUIRE(parsed[0].directional());
  CHECK(parsed[0].contains(0.1, 1.0));        // cos θ_i = 0.1 → row 1 (grazing), every azimuth
  CHECK(parsed[0].contains(0.5, 0.2));        // row 2, column 1
  CHECK_FALSE(parsed[0].contains(0.5, 0.9));  // row 2, column 4
  CHECK_FALSE(parsed[0].contains(1.0, 1.0));  // normal incidence
  CHECK_FALSE(parsed[1].directional());
  CHECK(material_warning_summaries(text).find(" cells: ") == std::string::npos);
  // Rows that reach further from the horizon toward grazing incidence: said at both ends.
  std::vector<std::uint8_t> widening(16, 0);
  widening[3 * 4 + 0] = 1;                      // row 4 (theta_i 0): b = 1
  widening[1 * 4 + 0] = widening[1 * 4 + 1] = 1;  // row 2 (theta_i 60): b = 1, 2
  CHECK(describe_cells(4, widening) ==
        "|phi_i| >= 75.5 deg at theta_i 0.0 deg, widening to |phi_i| >= 60.0 deg at theta_i 60.0 deg");
  CHECK(format_cells(4, widening) == "2:1-2 4:1-1");
  // A material written before issue 23: entries, none directional.
  const auto old = parse_material_warnings(
      "approx.grazing: raised while computing 100 of 100 work groups, first at lambda = 400 nm, cos theta_i = 1/10\n", 10);
  REQUIRE(old.size() == 1);
  CHECK_FALSE(old[0].directional());
}
