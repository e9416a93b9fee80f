// Procedural feathers (feather_geometry.hpp): shading frames, barbule ids, triangle counts, the
// barbule tilt against the vane, the ≥ 1000-feather assembly, determinism of the seeded jitter.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "plumage/feather_geometry.hpp"

using namespace plumage;

namespace {

double dot3(Vec3f a, Vec3f b) { return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z; }
Vec3f sub(Vec3f a, Vec3f b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3f cross3(Vec3f a, Vec3f b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double len(Vec3f a) { return std::sqrt(dot3(a, a)); }

// Unit, orthogonal frames; returns the worst deviation.
double frame_error(const SceneMesh& m) {
  double worst = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    worst = std::max({worst, std::abs(len(m.frame_axis[t]) - 1), std::abs(len(m.frame_normal[t]) - 1),
                      std::abs(dot3(m.frame_axis[t], m.frame_normal[t]))});
  }
  return worst;
}

// Ids form 0 … N−1 with none missing.
bool dense_ids(const SceneMesh& m, std::size_t n) {
  std::set<std::uint32_t> ids(m.barbule_id.begin(), m.barbule_id.end());
  return ids.size() == n && (n == 0 || (*ids.begin() == 0 && *ids.rbegin() == n - 1));
}

Vec3f geometric_normal(const SceneMesh& m, std::size_t t) {
  const auto& tri = m.triangles[t];
  const Vec3f n = cross3(sub(m.positions[tri[1]], m.positions[tri[0]]), sub(m.positions[tri[2]], m.positions[tri[0]]));
  const double l = len(n);
  return {float(n.x / l), float(n.y / l), float(n.z / l)};
}

FeatherShape small_feather() {
  FeatherShape f;
  f.length_mm = 8, f.vane_width_mm = 4, f.barb_spacing_mm = 0.3, f.barbule_spacing_mm = 0.05;
  f.rachis_width_mm = 0.3;
  return f;
}

}  // namespace

TEST_CASE("explicit barbules: frames, ids, triangle count, geometric normal = mean normal", "[scene][geometry]") {
  FeatherShape f = small_feather();
  const FeatherGeometry g = build_feather(f, FeatherDetail::barbules, 7);
  const SceneMesh& v = g.vane;
  REQUIRE(g.barbule_count > 1000);
  REQUIRE(v.frame_axis.size() == v.triangles.size());
  REQUIRE(v.frame_normal.size() == v.triangles.size());
  REQUIRE(v.barbule_id.size() == v.triangles.size());
  // Every barbule is one strip of barbule_segments quads.
  CHECK(v.triangles.size() == g.barbule_count * 2 * static_cast<std::size_t>(f.barbule_segments));
  CHECK(frame_error(v) < 1e-6);
  CHECK(dense_ids(v, g.barbule_count));
  // All triangles of one barbule share its frame (n is the barbule's mean normal).
  std::map<std::uint32_t, std::size_t> first;
  double spread = 0, facing = 1;
  for (std::size_t t = 0; t < v.triangles.size(); ++t) {
    auto [it, fresh] = first.emplace(v.barbule_id[t], t);
    if (!fresh) spread = std::max(spread, 1 - dot3(v.frame_normal[t], v.frame_normal[it->second]));
    // A straight strip is planar: its geometric normal is the barbule normal (same orientation).
    facing = std::min(facing, dot3(geometric_normal(v, t), v.frame_normal[t]));
  }
  CHECK(spread < 1e-6);
  CHECK(facing > 0.9999);
  CHECK(v.barbule_spacing_mm == Approx(f.barbule_spacing_mm));
  CHECK(g.shaft.barbule_id.empty());
}

TEST_CASE("barbule tilt: angle between barbule normal and vane normal equals the tilt on a flat vane", "[scene][geometry]") {
  FeatherShape f = small_feather();
  f.camber_mm = 0, f.barbule_elevation_deg = 0, f.barbule_tilt_deg = 20;
  const FeatherGeometry g = build_feather(f, FeatherDetail::barbules, 3);
  double worst_tilt = 0, worst_plane = 0;
  for (std::size_t t = 0; t < g.vane.triangles.size(); ++t) {
    const double angle = std::acos(std::clamp(double(g.vane.frame_normal[t].z), -1.0, 1.0)) * 180 / M_PI;
    worst_tilt = std::max(worst_tilt, std::abs(angle - 20.0));
    worst_plane = std::max(worst_plane, std::abs(double(g.vane.frame_axis[t].z)));  // axis stays in the vane
  }
  CHECK(worst_tilt < 1e-3);
  CHECK(worst_plane < 1e-6);
  // Mirror symmetry: the normal leans toward the rachis on both sides (x·n_x < 0).
  std::size_t inward = 0;
  for (std::size_t t = 0; t < g.vane.triangles.size(); ++t) {
    const Vec3f p = g.vane.positions[g.vane.triangles[t][0]];
    inward += p.x * g.vane.frame_normal[t].x < 0;
  }
  CHECK(inward == g.vane.triangles.size());
}

TEST_CASE("a single feather with explicit barbules stays at a few 10^5 triangles", "[scene][geometry]") {
  FeatherShape f;  // the defaults: a 30 mm contour feather
  const FeatherGeometry g = build_feather(f, FeatherDetail::barbules, 1);
  const std::size_t triangles = g.vane.triangles.size() + g.shaft.triangles.size();
  CHECK(triangles > 100'000);
  CHECK(triangles < 1'000'000);
  // Limit: refused before building.
  CHECK_THROWS_WITH(build_feather(f, FeatherDetail::barbules, 1, {}, 10'000), Catch::Contains("exceed the limit"));
}

TEST_CASE("barb-level feather: one id per barb segment, frames from the barbules", "[scene][geometry]") {
  FeatherShape f = small_feather();
  f.barbule_tilt_deg = 20;
  const FeatherGeometry g = build_feather(f, FeatherDetail::barb_level, 5);
  const SceneMesh& v = g.vane;
  CHECK(v.triangles.size() == 2 * g.barbule_count);
  CHECK(frame_error(v) < 1e-6);
  CHECK(dense_ids(v, g.barbule_count));
  CHECK(v.barbule_spacing_mm == Approx(f.barbule_spacing_mm));
  // The shading normal leans from the strip by about the tilt (plus elevation and camber).
  double max_angle = 0;
  for (std::size_t t = 0; t < v.triangles.size(); ++t)
    max_angle = std::max(max_angle, std::acos(std::clamp(dot3(geometric_normal(v, t), v.frame_normal[t]), -1.0, 1.0)) * 180 / M_PI);
  CHECK(max_angle > 15);
  CHECK(max_angle < 35);
}

TEST_CASE("placement rotates frames and scales positions", "[scene][geometry]") {
  const FeatherShape f = small_feather();
  const FeatherGeometry a = build_feather(f, FeatherDetail::barb_level, 9);
  const Placement p = placement_from_euler({10, 20, 30}, {90, 0, 0}, 2.0);  // +y → +z, +z → −y
  const FeatherGeometry b = build_feather(f, FeatherDetail::barb_level, 9, p);
  REQUIRE(a.vane.positions.size() == b.vane.positions.size());
  for (std::size_t k = 0; k < a.vane.positions.size(); k += 97) {
    const Vec3f q = a.vane.positions[k], r = b.vane.positions[k];
    CHECK(r.x == Approx(10 + 2 * q.x).margin(1e-4));
    CHECK(r.y == Approx(20 - 2 * q.z).margin(1e-4));
    CHECK(r.z == Approx(30 + 2 * q.y).margin(1e-4));
  }
  CHECK(b.vane.frame_normal[0].y == Approx(-a.vane.frame_normal[0].z).margin(1e-6));
  CHECK(b.vane.barbule_spacing_mm == Approx(2 * f.barbule_spacing_mm));
}

TEST_CASE("assembly: >= 1000 barb-level feathers on an ellipsoid, seeded and deterministic", "[scene][geometry]") {
  AssemblyShape a;
  a.count = 1200;
  a.body.radii_mm = {20, 40, 20};
  a.feather.length_mm = 10, a.feather.vane_width_mm = 7, a.feather.barb_spacing_mm = 0.6, a.feather.barb_segment_mm = 1.0;
  a.feather.rachis_width_mm = 0.3, a.feather.calamus_mm = 0.5;
  const AssemblyGeometry g = build_feather_assembly(a, 11);
  CHECK(g.feather_count == 1200);
  CHECK(g.vane.triangles.size() == 2 * g.barbule_count);
  CHECK(dense_ids(g.vane, g.barbule_count));
  CHECK(frame_error(g.vane) < 1e-5);
  // Feather bases lie on the ellipsoid: every shaft's lowest ring starts there, so the nearest
  // shaft vertices to the surface are within a rachis radius (check the calamus ends).
  std::size_t near_surface = 0;
  for (const Vec3f& q : g.shaft.positions) {
    const double e = std::sqrt(q.x * q.x / 400.0 + q.y * q.y / 1600.0 + q.z * q.z / 400.0);
    near_surface += std::abs(e - 1) < 0.05;
  }
  CHECK(near_surface > 1200);
  // Same seed: bit-identical; another seed: different jitter.
  const AssemblyGeometry again = build_feather_assembly(a, 11);
  REQUIRE(again.vane.positions.size() == g.vane.positions.size());
  bool same = true;
  for (std::size_t k = 0; k < g.vane.positions.size(); ++k)
    same = same && std::memcmp(&g.vane.positions[k], &again.vane.positions[k], sizeof(Vec3f)) == 0;
  CHECK(same);
  const AssemblyGeometry other = build_feather_assembly(a, 12);
  CHECK(std::memcmp(&other.vane.positions[0], &g.vane.positions[0], sizeof(Vec3f)) != 0);
}

TEST_CASE("item seeds differ by object name and index", "[scene][geometry]") {
  CHECK(object_item_seed(1, "a", 0) != object_item_seed(1, "a", 1));
  CHECK(object_item_seed(1, "a", 0) != object_item_seed(1, "b", 0));
  CHECK(object_item_seed(1, "a", 0) != object_item_seed(2, "a", 0));
  CHECK(object_item_seed(1, "a", 0) == object_item_seed(1, "a", 0));
}
