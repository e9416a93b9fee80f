// The reflected fraction of the approximate solver on the whole characterisation grid (spec
// geometry-and-brdf §0.3: cos θ_i, cos φ_i ∈ {0.05, …, 1}, φ_i of both signs), for every
// variant of every layered species, two instances and both ends of the spectrum: 0 ≤ R ≤ 1
// everywhere (issue 4 acceptance), with the default (lossless) normalisation. Hidden tag: run
// by `make validate` (~15 s per variant on 2 idle cores).
#include <catch2/catch.hpp>

#include <tbb/parallel_for.h>

#include <array>
#include <filesystem>

#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;

TEST_CASE("0 <= reflected fraction <= 1 on the whole incident grid, every layered variant", "[.][solver-grid]") {
  using plumage::testing::registry;
  const double bin = kPi / 400;
  const auto dirs = pattern_directions(400).phi_o_rad;
  std::vector<double> phis;
  for (int b = 1; b <= 20; ++b) phis.push_back(std::acos(b / 20.0)), phis.push_back(-std::acos(b / 20.0));
  for (const char* name : {"bronzewing", "hummingbird", "rockdove", "starling"}) {
    const auto file = std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / (std::string(name) + ".yaml");
    for (const std::string& variant : species_variants(file)) {
      const auto config = load_species_config(file, registry(), variant);
      // Rows of the grid in parallel; each keeps its own extremes.
      std::array<double, 20> row_lo, row_hi;
      row_lo.fill(1e300), row_hi.fill(-1e300);
      for (std::uint64_t instance : {0u, 1u}) {
        auto prepared = config.solver->prepare(config.structure->generate(instance), config.reflection);
        tbb::parallel_for(1, 21, [&](int a) {
          for (double lambda : {400.0, 694.0}) {
            for (const auto& ff : config.solver->solve(*prepared, lambda, std::acos(a / 20.0), phis, dirs)) {
              for (int pol = 0; pol < 2; ++pol) {
                row_lo[a - 1] = std::min(row_lo[a - 1], ff.reflected_fraction(pol, bin));
                row_hi[a - 1] = std::max(row_hi[a - 1], ff.reflected_fraction(pol, bin));
              }
            }
          }
        });
      }
      const double lo = *std::min_element(row_lo.begin(), row_lo.end());
      const double hi = *std::max_element(row_hi.begin(), row_hi.end());
      WARN(name << "/" << variant << ": R in [" << lo << ", " << hi << "] over 2 instances x 2 lambda x 800 directions x 2 pols");
      CHECK(lo >= 0.0);
      CHECK(hi <= 1.0);
    }
  }
}
