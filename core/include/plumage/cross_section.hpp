// One procedural barbule instance: the cross section in the xz-plane (paper §3–4, Figs. 4–5).
//
// Frame (conventions.hpp): x across the barbule, z the macro-surface normal (up, out of the
// feather), barbule axis y. Lengths in nm.
//
// Three views of the same instance, sharing one outline:
//  * top      the illuminated top surface, a polyline left → right (x strictly increasing). Its
//             outward normal is the tangent rotated by +90° (toward +z). It is the only radiating
//             surface of the approximate solver.
//  * regions  the exact interior as closed polygons with a material and a role, nested through
//             `parent` (a region lies inside its parent; siblings do not overlap; a point's
//             material is that of the innermost region containing it, air outside all). Region 0
//             is the body, whose outline is band_polygon(top, bottom) (geometry.hpp). Parents precede
//             their children. For the full-wave solver.
//  * reduced  types 1–4: layer-boundary polylines top → bottom, each with the material below it
//             (LayeredModel); types 5–7: a crystal reference and a per-top-vertex regularity
//             (CrystalModel). For the approximate solver.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/layer_profile.hpp"
#include "plumage/materials.hpp"

namespace plumage {

struct Vec2 {
  double x = 0.0;
  double z = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.z + b.z}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.z - b.z}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.z}; }
inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.z == b.z; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.z * b.z; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.z - a.z * b.x; }
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.z * a.z); }

using Polyline = std::vector<Vec2>;  // open curve
using Polygon = std::vector<Vec2>;   // closed curve, counter-clockwise, last vertex ≠ first

enum class RegionRole {
  body,            // the barbule (keratin)
  cortex,          // a separate keratin shell
  melanosome,      // a melanosome or a row of touching melanosomes (necklace)
  air_bubble,      // air inside a platelet (a chain of bubbles)
  platelet,        // a melanin platelet (hummingbird "pancake")
  air_gap,         // an air layer (rock dove)
  granular_layer,  // melanin granules in a host, as an effective medium
  mixed_core,      // the melanin-keratin mixture at the centre of a barbule
  rod,             // a melanin rod of a photonic crystal
  core,            // the air core of a hollow rod (or of a coated circle)
  channel,         // an air channel of a photonic crystal
  film             // a continuous film (layered slabs, film models)
};

std::string_view role_name(RegionRole role);

struct Region {
  Polygon outline;
  Material material;
  RegionRole role = RegionRole::body;
  int parent = -1;     // index of the enclosing region, -1 for the body (in air)
  int layer = -1;      // row or layer index for structures organised in rows, else -1
  int members = 1;     // bodies united in this region (discs of a necklace, bubbles of a chain)
  double size_nm = 0;  // characteristic size: diameter of a disc, length of a platelet
};

// One boundary of the reduced layered model. `below` is the medium between this boundary and
// the next one that counts. A mixture carries its guest (melanin) fraction per vertex in
// `fraction` (same length as `points`), interpolated where a normal line crosses.
//
// Brackets (hummingbird platelets): a boundary with `closes` ≥ 0 opens a bracket that the
// boundary at index `closes` ends. A normal line uses a bracket only if it crosses both of its
// boundaries; otherwise the bracket and everything inside it are skipped (the medium above
// continues). Boundaries outside brackets always count; where a normal line misses one it is
// extended along its end segment (reference behaviour near the barbule edges).
struct LayerBoundary {
  Polyline points;  // left → right
  Material below;
  std::vector<double> fraction;  // empty unless `below` is a mixture
  int closes = -1;
};

struct LayeredModel {
  Material below_top = Material::keratin();  // medium under the top surface (the cortex)
  std::vector<LayerBoundary> boundaries;      // top → bottom; the last is the bottom surface
};

struct CrystalModel {
  std::string crystal;              // crystal config file (as resolved by the generator)
  std::string crystal_name;         // its `name:`
  std::vector<double> regularity;   // per top vertex, in (0, 1]
};

// A melanosome of a row (informational: the exact model unites a row into one region).
struct Disc {
  Vec2 center;
  double diameter_nm = 0.0;
  int row = -1;
};

struct CrossSection {
  std::string generator;      // plug-in type that made it
  std::string label;          // "species/variant" or a validation shape name
  std::uint64_t instance = 0;
  std::uint64_t seed = 0;

  Polyline top;
  Polyline bottom;  // the bottom surface, left → right; body outline = band_polygon(top, bottom)
  // The random height added to the smooth base shape at each top vertex (for statistics;
  // empty when the top is not rough).
  std::vector<double> top_roughness_nm;
  std::vector<Region> regions;
  std::optional<LayeredModel> layered;
  std::optional<CrystalModel> crystal;
  std::vector<Disc> melanosomes;

  double width_nm() const { return top.empty() ? 0.0 : top.back().x - top.front().x; }
};

// Outward unit normals of a polyline (tangent by central differences, one-sided at the ends,
// rotated by +90°).
std::vector<Vec2> vertex_normals(const Polyline& line);

// The local planar stack under top vertex `node` (wave-simulation spec §2.1): the line through
// the node along its normal is intersected with every boundary of the layered model; the
// distances between successive crossings are the layer thicknesses. Throws Error if the cross
// section has no layered model.
LayerProfile layer_profile_at(const CrossSection& section, std::size_t node);
// All top vertices (compute once per instance).
std::vector<LayerProfile> layer_profiles(const CrossSection& section);

// Geometric validity: top strictly monotone in x; every region simple (no self-intersection)
// and counter-clockwise; no boundary crosses another (shared edges and vertices allowed);
// regions properly nested (inside their parent, disjoint from their siblings); the body outline
// is made of the top and the bottom; layered boundaries and regularity well formed. Empty when valid.
std::vector<std::string> validate(const CrossSection& section);

// Polygon helpers.
double signed_area(const Polygon& polygon);
bool point_in_polygon(Vec2 p, const Polygon& polygon);

}  // namespace plumage
