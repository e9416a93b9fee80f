// MaterialLookupTable (feather_material.hpp): the renderer's precomputed form of
// FeatherMaterial::lookup must give the same parameters. Checked on rough random node tables
// (no smoothness to hide a wrong slope or a swapped corner), several grids and bins, inside the
// cells, on the nodes and cell edges, at grazing and outside [0, 1] (clamped).
#include <catch2/catch.hpp>

#include <cmath>

#include "plumage/feather_material.hpp"
#include "plumage/random.hpp"

using namespace plumage;

namespace {

FeatherMaterial random_material(int grid, std::size_t bins, std::uint64_t seed) {
  RandomStream rng(seed);
  FeatherMaterial m;
  m.grid = grid;
  for (std::size_t w = 0; w < bins; ++w) m.lambda_nm.push_back(400.0 + 6.0 * static_cast<double>(w));
  m.nodes.resize(bins * static_cast<std::size_t>(grid + 1) * static_cast<std::size_t>(grid + 1));
  for (MaterialNode& n : m.nodes) {
    // Ranges a little wider than the clamps, so the clamps are exercised too.
    n.m_eff = -0.1 + 1.2 * rng.uniform();
    n.m_sta = -0.1 + 1.2 * rng.uniform();
    n.phi_eff = -1.7 + 3.4 * rng.uniform();
    n.phi_sta = -1.7 + 3.4 * rng.uniform();
    n.f_eff = -0.2 + 1.5 * rng.uniform();
    n.f_sta = -0.2 + 1.5 * rng.uniform();
    n.pol_share = -0.1 + 1.2 * rng.uniform();
    n.correlation = -0.1 + 3.0 * rng.uniform();
  }
  return m;
}

// Largest |table − reference| / max(1, |reference|) over the eight fields.
double field_error(const MaterialNode& a, const MaterialNode& b) {
  double worst = 0.0;
  for (const auto field : kMaterialFields) {
    worst = std::max(worst, std::abs(a.*field - b.*field) / std::max(1.0, std::abs(b.*field)));
  }
  return worst;
}

}  // namespace

TEST_CASE("material lookup table equals FeatherMaterial::lookup", "[material]") {
  for (const int grid : {1, 7, 20}) {
    const std::size_t bins = 3;
    const FeatherMaterial m = random_material(grid, bins, 17 + static_cast<std::uint64_t>(grid));
    const MaterialLookupTable table(m);
    RandomStream rng(99);
    double worst = 0.0;
    std::size_t exact = 0, total = 0;
    auto check = [&](std::size_t w, double ct, double cp) {
      const MaterialNode ref = m.lookup(w, ct, cp), got = table.lookup(w, ct, cp);
      worst = std::max(worst, field_error(got, ref));
      exact += field_error(got, ref) == 0.0;
      ++total;
    };
    for (int k = 0; k < 20000; ++k) {
      check(static_cast<std::size_t>(k) % bins, -0.05 + 1.1 * rng.uniform(), -0.05 + 1.1 * rng.uniform());
    }
    for (std::size_t w = 0; w < bins; ++w) {
      for (int i = 0; i <= 2 * grid; ++i) {
        for (int j = 0; j <= 2 * grid; ++j) check(w, 0.5 * i / grid, 0.5 * j / grid);  // nodes, edges, centres
      }
      check(w, 1e-9, 0.3);
      check(w, 0.3, 1e-9);
    }
    INFO("grid " << grid << ": worst relative difference " << worst << ", " << exact << " of " << total
                 << " bit-identical");
    CHECK(worst <= 1e-12);
  }
}

TEST_CASE("material lookup table rejects inconsistent tables", "[material]") {
  FeatherMaterial m = random_material(4, 2, 3);
  m.nodes.pop_back();
  CHECK_THROWS(MaterialLookupTable(m));
}
