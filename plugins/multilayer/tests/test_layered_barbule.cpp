// The layered_barbule generator reproduces spec geometry-and-brdf §1.3(1–4) statistically, over
// ≥ 200 instances per species: exact roughness ranges, Gaussian correlation lengths, per-variant
// cortex thickness, melanosome diameter distributions, hummingbird platelet and bubble counts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>

#include "plumage/config_document.hpp"
#include "plumage/geometry.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::distance_to;
using plumage::testing::registry;
using plumage::testing::species;

struct Moments {
  double n = 0, sum = 0, sum2 = 0, lo = 1e300, hi = -1e300;
  void add(double x) {
    n += 1;
    sum += x;
    sum2 += x * x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  double mean() const { return sum / n; }
  double sd() const { return std::sqrt(std::max(0.0, sum2 / n - mean() * mean())); }
};

// Exact roughness range in every instance, and τ of the mean circular autocovariance.
double check_roughness(const std::string& name, double lo, double hi, int instances = 200) {
  auto cfg = species(name);
  std::vector<double> acc;
  double step = 0.0;
  for (int k = 0; k < instances; ++k) {
    const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
    const auto [mn, mx] = std::minmax_element(cs.top_roughness_nm.begin(), cs.top_roughness_nm.end());
    REQUIRE(*mn == lo);
    REQUIRE(*mx == hi);
    std::vector<double> xs(cs.top.size());
    for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = cs.top[i].x;
    const auto c = circular_autocovariance(xs, cs.top_roughness_nm, 2048, 1024, step);
    if (acc.empty()) acc.assign(c.size(), 0.0);
    for (std::size_t j = 0; j < c.size(); ++j) acc[j] += c[j];
  }
  return gaussian_correlation_length(acc, step);
}

}  // namespace

TEST_CASE("top roughness: exact range and Gaussian correlation length", "[layered_barbule][statistics]") {
  const std::map<std::string, std::array<double, 3>> expected{
      {"rockdove", {-80.0, 80.0, 1000.0}},
      {"starling", {-300.0, 300.0, 1500.0}},
      {"bronzewing", {-200.0, 200.0, 1500.0}},
      {"hummingbird", {-250.0, 250.0, 1500.0}}};
  for (const auto& [name, e] : expected) {
    const double tau = check_roughness(name, e[0], e[1]);
    WARN(name << ": correlation length " << tau << " nm configured " << e[2] << " nm, error "
              << 100.0 * (tau / e[2] - 1.0) << " %");
    CHECK(tau == Approx(e[2]).epsilon(0.10));
  }
}

TEST_CASE("rock dove: cortex per variant, air gap and melanin fraction ranges", "[layered_barbule][statistics]") {
  const std::map<std::string, double> cortex{{"forest", 595}, {"jade", 582}, {"sea", 569},
                                             {"teal", 556},   {"violet", 543}, {"purple", 530}};
  for (const auto& [variant, c] : cortex) {
    auto cfg = species("rockdove", variant);
    Moments first, gap;
    const int n = variant == "forest" ? 200 : 30;
    for (int k = 0; k < n; ++k) {
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
      for (std::size_t i = 1; i + 1 < cs.top.size(); i += 7) {
        if (std::abs(cs.top[i].x) > 5000.0) continue;
        const LayerProfile p = layer_profile_at(cs, i);
        REQUIRE(p.layers.size() == 4);
        first.add(p.layers[0].thickness_nm);
        gap.add(p.layers[1].thickness_nm);
      }
      const auto& f = cs.layered->boundaries[1].fraction;  // melanin fraction of the granule layer
      REQUIRE(*std::min_element(f.begin(), f.end()) == 0.8);
      REQUIRE(*std::max_element(f.begin(), f.end()) == 1.0);
    }
    INFO(variant);
    // The inner cortex is the top offset along its vertex normals: exact along those normals.
    CHECK(first.lo == Approx(c).margin(1e-6));
    CHECK(first.hi == Approx(c).margin(1e-6));
    // The gap is offset along the inner cortex's normals: within the configured range, nearly.
    CHECK(gap.lo >= 250.0 - 5.0);
    CHECK(gap.hi <= 750.0 + 5.0);
    if (variant == "forest") {
      CHECK(gap.lo < 270.0);
      CHECK(gap.hi > 730.0);
      WARN("rock dove gap thickness " << gap.lo << " .. " << gap.hi << " nm, mean " << gap.mean());
    }
  }
}

TEST_CASE("melanosome rows: cortex per variant and diameter distributions", "[layered_barbule][statistics]") {
  struct Case {
    std::string species, variant;
    double cortex, d, spacing, jitter;
    int rows, instances;
  };
  const std::vector<Case> cases{
      {"starling", "aqua", 300, 250, 0, 0.2, 1, 30},     {"starling", "green", 320, 250, 0, 0.2, 1, 200},
      {"starling", "teal", 440, 250, 0, 0.2, 1, 30},     {"starling", "lavender", 420, 250, 0, 0.2, 1, 30},
      {"bronzewing", "pink", 12, 99, 100, 0.1, 6, 20},   {"bronzewing", "green", 12, 82, 77, 0.1, 6, 200},
      {"bronzewing", "blue", 12, 75, 63, 0.1, 6, 20}};
  for (const auto& c : cases) {
    INFO(c.species << "-" << c.variant);
    auto cfg = species(c.species, c.variant);
    Moments diam, depth_error;
    for (int k = 0; k < c.instances; ++k) {
      const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
      for (const Disc& d : cs.melanosomes) {
        diam.add(d.diameter_nm);
        if (d.row < c.rows && std::abs(d.center.x) < 0.3 * cs.width_nm()) {
          // Row i's centres lie at cortex + D/2 + i (D + s) under the top.
          const double expected = c.cortex + 0.5 * c.d + d.row * (c.d + c.spacing);
          depth_error.add(distance_to(cs.top, d.center) - expected);
        }
      }
    }
    CHECK(diam.lo >= (1.0 - c.jitter) * c.d);
    CHECK(diam.hi <= (1.0 + c.jitter) * c.d);
    // Uniform on [(1-j)D, (1+j)D]: mean D, standard deviation 2jD/sqrt(12).
    CHECK(diam.mean() == Approx(c.d).epsilon(0.01));
    CHECK(diam.sd() == Approx(2.0 * c.jitter * c.d / std::sqrt(12.0)).epsilon(0.05));
    CHECK(std::abs(depth_error.mean()) < 1.0);
    CHECK(depth_error.hi < 3.0);
    CHECK(depth_error.lo > -3.0);
    if (c.instances >= 200) {
      WARN(c.species << "-" << c.variant << ": " << diam.n << " melanosomes, diameter mean " << diam.mean()
                     << " nm sd " << diam.sd() << " nm; row depth error " << depth_error.lo << " .. "
                     << depth_error.hi << " nm");
    }
  }
}

TEST_CASE("hummingbird: platelet and bubble counts", "[layered_barbule][statistics]") {
  auto cfg = species("hummingbird");
  Moments platelets_per_instance, bubbles_l1, bubbles_l3, thickness;
  for (int k = 0; k < 200; ++k) {
    const CrossSection cs = cfg.structure->generate(static_cast<std::uint64_t>(k));
    std::map<int, int> per_layer, bubbles_in;  // bubbles per platelet region
    int platelets = 0;
    for (std::size_t r = 0; r < cs.regions.size(); ++r) {
      const Region& g = cs.regions[r];
      if (g.role == RegionRole::platelet) {
        ++platelets;
        ++per_layer[g.layer];
      }
      if (g.role == RegionRole::air_bubble) {
        // The exact model (issue 28): one region per bubble, inside its platelet.
        REQUIRE(g.members == 1);
        REQUIRE(cs.regions[static_cast<std::size_t>(g.parent)].role == RegionRole::platelet);
        ++bubbles_in[g.parent];
      }
    }
    for (const auto& [plate, count] : bubbles_in) {
      const Region& box = cs.regions[static_cast<std::size_t>(plate)];
      const Region& bubble = cs.regions[static_cast<std::size_t>(plate) + 1];
      REQUIRE(bubble.parent == plate);
      // n = round((L − 2 t_w + t_m)/(air + t_m)) with t_w = 30, t_m = 20 nm.
      REQUIRE(count == std::lround((box.size_nm - 60.0 + 20.0) / (bubble.size_nm + 20.0)));
      if (box.layer == 0) {
        REQUIRE(bubble.size_nm == 30.0);
        bubbles_l1.add(count);
      }
      if (box.layer >= 2) {
        REQUIRE(bubble.size_nm >= 95.0);
        REQUIRE(bubble.size_nm <= 105.0);
        bubbles_l3.add(count);
      }
    }
    // 38 µm between the corners: 85 % / 90 % covered by platelets of mean length 2 µm.
    REQUIRE(per_layer.size() == 12);
    CHECK(per_layer[0] == 16);
    for (int l = 1; l < 12; ++l) CHECK(per_layer[l] == 17);
    platelets_per_instance.add(platelets);
    thickness.add(z_at(cs.top, 0.0) - z_at(cs.bottom, 0.0));
  }
  CHECK(platelets_per_instance.lo == 203);
  CHECK(platelets_per_instance.hi == 203);
  // Layer 1: platelets ~1.9 µm with 30 nm bubbles: ~37 per platelet; later layers ~(L − 40)/120.
  CHECK(bubbles_l1.mean() == Approx((0.85 * 38000.0 / 16.0 - 40.0) / 50.0).epsilon(0.03));
  CHECK(bubbles_l3.mean() == Approx((0.9 * 38000.0 / 17.0 - 40.0) / 120.0).epsilon(0.04));
  // T = 2·10 + 12·60 + Σ air + Σ spacers ≈ 2.5 µm.
  CHECK(thickness.mean() == Approx(2500.0).epsilon(0.03));
  WARN("hummingbird: 203 platelets per instance, bubbles per platelet: layer 1 mean " << bubbles_l1.mean()
       << ", layers 3-12 mean " << bubbles_l3.mean() << " (" << bubbles_l3.lo << " .. " << bubbles_l3.hi
       << "); thickness " << thickness.mean() << " nm");
}

TEST_CASE("layered_barbule refuses inconsistent parameters at their line", "[layered_barbule][config]") {
  ParamView none;
  CHECK_THROWS_WITH(registry().create_named<StructureGenerator>("layered_barbule", none, registry().context()),
                    Catch::Contains("model"));
}

// One declaration per parameter: the documented rows are the table that reads, with the shared
// outline rows nested under `outline` and the model-specific rows conditional on the model.
TEST_CASE("layered_barbule documents the parameters it reads", "[layered_barbule][config]") {
  const auto* entry = registry().find("structure_generator", "layered_barbule");
  REQUIRE(entry != nullptr);
  std::map<std::string, ParamSpec> rows;
  for (const ParamSpec& p : entry->info.params) rows[p.name] = p;
  REQUIRE(rows.count("outline.width_um"));
  CHECK(rows.at("outline.width_um").unit == "um");
  CHECK(rows.at("outline.width_um").range == "in (0, 10000]");
  REQUIRE(rows.count("outline.bottom.roughness.correlation_um"));
  CHECK(rows.at("outline.cap_ratio").condition == "shape: pillow");
  CHECK(rows.at("layers").condition == "model: platelets");
  CHECK(rows.at("layers").default_value == "required");
  CHECK(rows.at("neck_fraction").default_value == "1/3");
  CHECK(rows.at("end_gap_um").default_value == "[0.08, 0.12]");
  REQUIRE(rows.count("films.thickness_nm"));
  CHECK(rows.at("films.thickness_nm").condition == "model: films");
  CHECK(rows.at("granules.fraction.range").range == "in [0, 1]");

  const std::string films =
      "generator: layered_barbule\nmodel: films\ncortex_nm: 200\nfilms: [{material: melanin, thickness_nm: 100}]\n"
      "outline: {shape: pillow, width_um: 20, thickness_um: 3, roughness: {correlation_um: 1, range_um: [-0.1, 0.1]}}\n";
  auto create = [](const std::string& yaml) {
    const auto doc = ConfigDocument::parse(yaml, "films.yaml");
    return registry().create<StructureGenerator>(doc.root(), "generator", registry().context());
  };
  REQUIRE_NOTHROW(create(films));
  // A platelets parameter does not apply to films: an unknown key.
  CHECK_THROWS_WITH(create(films + "wall_nm: 20\n"), Catch::Contains("films.yaml:6:") && Catch::Contains("wall_nm"));
  // The outline's thickness is required except where the model computes it.
  std::string thin = films;
  thin.replace(thin.find(" thickness_um: 3,"), 17, "");
  CHECK_THROWS_WITH(create(thin), Catch::Contains("missing required key 'thickness_um'"));
  // Outline parameters of another shape are unknown keys too.
  std::string arc = films;
  arc.replace(arc.find("shape: pillow,"), 14, "shape: pillow, edge_slope_deg: [18, 30],");
  CHECK_THROWS_WITH(create(arc), Catch::Contains("edge_slope_deg"));
}
