// Pictures and checks of a feather BSDF as a library (brdf_report.hpp): a hemisphere panel
// integrates to the directional albedo; the white furnace covers every entry and sees a material
// brighter than 1 before the BSDF's clamp.
#include <catch2/catch.hpp>

#include <cmath>

#include "bsdf_fixtures.hpp"
#include "plumage/brdf_report.hpp"
#include "plumage/fitter.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

// Grey (spectrally flat) albedo E at every node, 10 bins of 30 nm over 400–700 nm, grid 4.
std::shared_ptr<const FeatherMaterial> grey_material(double albedo) {
  MaterialRecipe r;
  r.bins = 10;
  r.grid = 4;
  r.m_eff = [](int, double, double) { return 0.25; };
  r.albedo = [albedo](int, double, double) { return albedo; };
  FeatherMaterial m = make_material(r, [](const Lobe& l, double t) { return hemisphere_lobe_integral(l, t); });
  m.bin_width_nm = 30.0;
  for (int w = 0; w < r.bins; ++w) m.lambda_nm[static_cast<std::size_t>(w)] = 400.0 + 30.0 * w;
  m.noise = ar1_pool(16, 128, 0.9, 42);
  return std::make_shared<const FeatherMaterial>(std::move(m));
}

}  // namespace

TEST_CASE("brdf report: the mean panel's disk integral is the directional albedo", "[brdf][report]") {
  HemispherePlotOptions o;
  o.incidents = {{0.0, 0.0}, {0.0, -45.0}};
  o.instances = 1;
  o.size = 96;
  const HemispherePanels p = hemisphere_panels(grey_material(0.5), o);
  REQUIRE(p.rows == 2);
  REQUIRE(p.columns == 2);
  REQUIRE(p.xyz.size() == 4);
  CHECK(p.automatic_exposure);
  CHECK(p.exposure > 0.0);
  // Y of a flat reflectance spectrum is its value (white reflector Y = 1, up to the observer's
  // tails outside 400–700 nm). A pixel shows the cosine-weighted lobe L = f cos θ_o and covers
  // (2/size)² of projected solid angle dA = cos θ_o dω, so Σ (Y / cos θ_o) dA = ∫ L dω = A_r,
  // 0.5 at the nodes (normal incidence and φ_i = −45° are nodes of the grid-4 table).
  const double dA = (2.0 / o.size) * (2.0 / o.size);
  for (int row = 0; row < p.rows; ++row) {
    double mean = 0.0, instance = 0.0;
    std::size_t outside = 0;
    for (int py = 0; py < o.size; ++py) {
      for (int px = 0; px < o.size; ++px) {
        const std::size_t k = static_cast<std::size_t>(py) * o.size + px;
        if (!std::isfinite(p.xyz[row * 2][k].y)) {
          ++outside;
          continue;
        }
        const double x = 2.0 * (px + 0.5) / o.size - 1.0, y = 1.0 - 2.0 * (py + 0.5) / o.size;
        const double cos_o = std::sqrt(1.0 - x * x - y * y);
        mean += p.xyz[row * 2][k].y / cos_o * dA;
        instance += p.xyz[row * 2 + 1][k].y / cos_o * dA;
      }
    }
    INFO("row " << row << ": mean panel " << mean << ", instance " << instance);
    CHECK(mean == Approx(0.5).epsilon(0.005));
    CHECK(instance > 0.0);
    CHECK(instance != mean);  // an instance is not the mean BRDF
    // The disk covers π/4 of the square.
    CHECK(static_cast<double>(outside) / (o.size * o.size) == Approx(1.0 - M_PI / 4.0).margin(0.01));
  }
  o.exposure = 3.0;
  const HemispherePanels fixed = hemisphere_panels(grey_material(0.5), o);
  CHECK_FALSE(fixed.automatic_exposure);
  CHECK(fixed.exposure == 3.0);
}

TEST_CASE("brdf report: the white furnace at every table entry", "[brdf][report]") {
  const FurnaceReport ok = white_furnace(grey_material(0.5), 0.05);
  REQUIRE(ok.bins.size() == 10);
  CHECK(ok.nodes_per_bin == 16);
  CHECK(ok.entries == 10u * 2u * 16u);
  CHECK(ok.passes());
  CHECK(ok.worst_total >= 0.55);  // A_r = 0.5 at the nodes, more between them
  CHECK(ok.raw_over_one == 0);
  for (const FurnaceBin& b : ok.bins) {
    CHECK(b.transmission == Approx(0.05));
    CHECK(b.material_raw == Approx(0.5).epsilon(0.01));  // the material's own albedo at its nodes
  }
  // A material brighter than 1 at its nodes: seen before the clamp, which keeps A_r + T <= 1.
  const FurnaceReport bright = white_furnace(grey_material(1.1), 0.0);
  CHECK(bright.raw_over_one == 10 * 16);
  CHECK(bright.worst_raw == Approx(1.1).epsilon(0.01));
  CHECK(bright.clamped_nodes > 0);
  CHECK(bright.passes());
}
