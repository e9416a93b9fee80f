// The crystal_barbule generator against spec geometry-and-brdf §1.3(5–7) and
// photonic-crystals.md, over ≥ 200 instances: exact roughness and regularity ranges, Gaussian
// correlation length, the crystal's rows under the rough top, hollow cores and channels.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "plumage/crystal_cell.hpp"
#include "plumage/geometry.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::distance_to;
using plumage::testing::registry;
using plumage::testing::species;

}  // namespace

TEST_CASE("crystal barbules: exact roughness range and correlation length", "[crystal_barbule][statistics]") {
  for (const std::string name : {"mallard", "magpie", "peacock"}) {
    auto cfg = species(name);
    std::vector<double> acc;
    double step = 0.0;
    for (int k = 0; k < 200; ++k) {
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
      const auto [mn, mx] = std::minmax_element(cs.top_roughness_nm.begin(), cs.top_roughness_nm.end());
      REQUIRE(*mn == -300.0);
      REQUIRE(*mx == 300.0);
      std::vector<double> xs(cs.top.size());
      for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = cs.top[i].x;
      const auto c = circular_autocovariance(xs, cs.top_roughness_nm, 2048, 1024, step);
      if (acc.empty()) acc.assign(c.size(), 0.0);
      for (std::size_t j = 0; j < c.size(); ++j) acc[j] += c[j];
      CHECK(cs.width_nm() == Approx(40000.0));
    }
    const double tau = gaussian_correlation_length(acc, step);
    WARN(name << ": correlation length " << tau << " nm configured 1200 nm, error "
              << 100.0 * (tau / 1200.0 - 1.0) << " %");
    CHECK(tau == Approx(1200.0).epsilon(0.10));
  }
}

TEST_CASE("regularity: exactly [rho - 0.1, rho + 0.1] per magpie variant, 1 elsewhere", "[crystal_barbule][statistics]") {
  const std::map<std::string, double> rho{{"forest", 1.0}, {"lime", 1.0}, {"yellow", 1.0}, {"rose", 0.9},
                                          {"purple", 0.8}, {"violet", 0.7}, {"blue", 0.6}, {"teal", 0.5}};
  for (const auto& [variant, r] : rho) {
    INFO(variant);
    auto cfg = species("magpie", variant);
    const int n = variant == "teal" ? 200 : 20;
    for (int k = 0; k < n; ++k) {
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
      REQUIRE(cs.crystal);
      const auto& q = cs.crystal->regularity;
      REQUIRE(q.size() == cs.top.size());
      const auto [mn, mx] = std::minmax_element(q.begin(), q.end());
      if (r >= 1.0) {
        REQUIRE(*mn == 1.0);
        REQUIRE(*mx == 1.0);
      } else {
        REQUIRE(*mn == Approx(r - 0.1).margin(1e-12));
        REQUIRE(*mx == Approx(r + 0.1).margin(1e-12));
      }
      CHECK(cs.crystal->crystal_name == "magpie-" + variant);
    }
  }
  for (const std::string name : {"mallard", "peacock"}) {
    auto cfg = species(name);
    const CrossSection cs = cfg.structure->generate(0);
    CHECK(std::all_of(cs.crystal->regularity.begin(), cs.crystal->regularity.end(), [](double q) { return q == 1.0; }));
  }
}

TEST_CASE("the exact model places the crystal under the rough top", "[crystal_barbule][lattice]") {
  struct Case {
    std::string species, variant;
  };
  const std::vector<Case> cases{{"mallard", "lime"},   {"mallard", "blue"},   {"magpie", "violet"},
                                {"magpie", "rose"},    {"magpie", "teal"},    {"peacock", "cyan"},
                                {"peacock", "yellow"}};
  for (const auto& c : cases) {
    INFO(c.species << "-" << c.variant);
    auto cfg = species(c.species, c.variant);
    const CrystalCell cell = load_crystal_cell(fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "crystals" /
                                               (c.species + "-" + c.variant + ".yaml"));
    double worst = 0.0;
    int rods = 0, cores = 0, channels = 0;
    std::map<int, int> per_row;
    const int n = 20;
    for (int k = 0; k < n; ++k) {
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
      for (const Region& r : cs.regions) {
        if (r.role == RegionRole::rod) {
          ++rods;
          ++per_row[r.layer];
          REQUIRE(r.size_nm == cell.rod_diameter_nm);
          Vec2 c0{0, 0};
          for (const Vec2& v : r.outline) c0 = c0 + v;
          c0 = (1.0 / static_cast<double>(r.outline.size())) * c0;
          if (r.layer == 0) worst = std::max(worst, std::abs(distance_to(cs.top, c0) - cell.rod_depth_nm(0)));
        }
        if (r.role == RegionRole::core) ++cores;
        if (r.role == RegionRole::channel) ++channels;
      }
    }
    // Row 0 sits cortex + D/2 under the top (to the top's polyline, within a few nm of curvature).
    CHECK(worst < 3.0);
    if (cell.core_diameter_nm > 0) CHECK(cores == rods);
    if (cell.channel_diameter_nm > 0) CHECK(channels > rods / 2);
    CHECK(static_cast<int>(per_row.size()) == cell.rows);
    // Sites lost where the curvature squeezes the lattice: a few per cent at most.
    const double full = static_cast<double>(per_row[0]);
    double lost = 0.0;
    for (const auto& [row, count] : per_row) lost += std::max(0.0, full - count);
    const double defect = lost / (full * cell.rows);
    WARN(c.species << "-" << c.variant << ": " << rods / n << " rods per instance, " << 100.0 * defect
                   << " % lattice sites left out; row 0 depth error " << worst << " nm");
    CHECK(defect < 0.15);
  }
}
