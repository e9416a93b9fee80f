// Convergence of the approximate solver in top-surface node spacing, on real barbules: the same
// instance's top polyline resampled from the default 30 nm to 10 nm (the surface itself is the
// same piecewise-linear curve), far fields compared. Hidden tag: run by `make validate`.
#include <catch2/catch.hpp>

#include <filesystem>

#include "plumage/geometry.hpp"
#include "plumage/pattern_metrics.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;

namespace {
using plumage::testing::registry;
}  // namespace

TEST_CASE("node spacing 30 nm against 10 nm on layered barbules", "[.][convergence]") {
  const auto dirs = pattern_directions(400).phi_o_rad;
  // Types 1–3 have layer profiles that vary continuously along the barbule: 1 %. The
  // hummingbird's stack changes discontinuously where a normal line starts or stops crossing a
  // platelet, so the node sampling of platelet ends matters: measured 8.7–10.6 % at 550 nm
  // (docs/validation.md); the bound records that state, a smoother treatment should lower it.
  const std::pair<const char*, double> cases[] = {
      {"rockdove", 0.01}, {"starling", 0.01}, {"bronzewing", 0.01}, {"hummingbird", 0.03}};
  for (const auto& [name, bound] : cases) {
    const auto config = load_species_config(
        std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / (std::string(name) + ".yaml"),
        registry());
    double worst = 0;
    for (std::uint64_t instance : {0u, 1u}) {
      const CrossSection coarse = config.structure->generate(instance);
      CrossSection fine = coarse;
      fine.top = resample_uniform(coarse.top, 10.0);
      auto pc = config.solver->prepare(coarse, config.reflection);
      auto pf = config.solver->prepare(fine, config.reflection);
      for (double lambda : {400.0, 550.0, 694.0}) {
        for (double phi_deg : {0.0, 40.0}) {
          const double phi[1] = {deg_to_rad(phi_deg)};
          const auto a = config.solver->solve(*pc, lambda, deg_to_rad(20.0), phi, dirs).front();
          const auto b = config.solver->solve(*pf, lambda, deg_to_rad(20.0), phi, dirs).front();
          const double e = unpolarised_relative_l2(a, b);
          worst = std::max(worst, e);
          if (e > 0.02) WARN(name << " instance " << instance << " lambda " << lambda << " phi " << phi_deg << ": " << e);
        }
      }
    }
    WARN(name << ": worst relative L2 of the mean pattern, 30 nm vs 10 nm nodes: " << worst);
    CHECK(worst < bound);
  }
}
