// Procedural feathers for rendering (paper §7.3–7.4): a rachis, barbs along both sides of it
// inside a vane outline, and either explicit barbules (polygon strips, one BRDF instance each) or
// barb-level strips that carry the barbules' orientation in their shading frame.
//
// Feather frame (before placement): the rachis runs along +y from the base (y = 0) to the tip
// (y = length_mm), the vane lies near the xy-plane and its top (the side whose barbules
// reflect) faces +z. Lengths in mm, angles in degrees in the parameters.
//
// Barbule orientation (paper §7.3, Fig. 12): a barbule leaves its barb at `barbule_angle_deg` in
// the vane plane, pointing toward the feather tip (distal barbules; proximal ones mirror the angle
// toward the base). Its shading frame: t along its axis (BRDF y), n its mean normal (BRDF z),
// obtained from the vane normal by rotating about t by `barbule_tilt_deg` (positive: the
// barbule's outer edge lifts away from the vane plane; hummingbird ≈ 20°, Giraldo et al. 2018)
// after raising the axis by `barbule_elevation_deg` out of the vane plane.
//
// Barb-level feathers (paper §7.4, as Huang et al. 2022): no barbule triangles; each barb is a
// strip as wide as the barb spacing (the vane stays closed), cut into segments, and every
// segment's frame is the distal barbule frame at that point; each segment gets its own BRDF
// instance (barbule_id) and the mesh's barbule_spacing_mm is the real barbule spacing, so the
// renderer's level of detail knows how many barbules a pixel covers.
//
// Randomness (random.hpp): every draw comes from RandomStream(seed, purpose) with seeds derived
// from the caller's seed and the barb / feather index, so geometry is identical on every machine.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "plumage/scene.hpp"

namespace plumage {

struct FeatherShape {
  double length_mm = 30.0;        // rachis length covered by the vane (base → tip)
  double calamus_mm = 3.0;        // bare quill below the vane (rachis only)
  double vane_width_mm = 14.0;    // full width of the vane at its widest
  double vane_asymmetry = 0.0;    // in [-0.8, 0.8]: left half-width ×(1 − a), right ×(1 + a)
  double camber_mm = 1.0;         // the vane bends down (−z) by this much at its edges
  double rachis_width_mm = 0.6;   // diameter at the base, tapering to 20 % at the tip
  double barb_spacing_mm = 0.3;   // along the rachis, on each side
  double barb_angle_deg = 40.0;   // barb direction vs the rachis at the base of the barb
  double barb_curl_deg = 25.0;    // the barb turns this much toward the tip over its length
  double barb_width_mm = 0.04;    // barb (ramus) strip width, explicit-barbule feathers
  double barb_segment_mm = 0.5;   // target segment length along a barb
  double barbule_length_mm = 0.25;
  double barbule_width_mm = 0.03;
  double barbule_spacing_mm = 0.04;  // along the barb, per side
  double barbule_angle_deg = 35.0;   // barbule axis vs barb axis, in the vane plane
  double barbule_tilt_deg = 0.0;     // rotation of the barbule about its axis (paper §7.3)
  double barbule_elevation_deg = 5.0;  // axis raised out of the vane plane
  int barbule_segments = 2;          // quads per barbule strip
  bool proximal_barbules = true;     // also the barbules on the base side of each barb
  double jitter = 0.05;              // relative random variation of barb angle, spacing, length
};

// One feather: shaft (rachis + explicit barbs, not iridescent) and the iridescent part
// (explicit barbules, or barb-level strips). Materials are left 0: the caller assigns them.
struct FeatherGeometry {
  SceneMesh shaft;
  SceneMesh vane;  // frames, barbule_id and barbule_spacing_mm set
  std::size_t barb_count = 0;
  std::size_t barbule_count = 0;  // explicit barbules, or barb-level segments (distinct ids)
};

enum class FeatherDetail { barbules, barb_level };

// A rigid placement: p ↦ origin + R·(scale·p), R's columns = (x_axis, y_axis, z_axis), unit and
// orthonormal (the constructor functions make them so).
struct Placement {
  Vec3f origin_mm;
  Vec3f x_axis = {1, 0, 0}, y_axis = {0, 1, 0}, z_axis = {0, 0, 1};
  double scale = 1.0;
};
// From Euler angles in degrees (rotation about x, then y, then z, of the feather frame).
Placement placement_from_euler(const Vec3f& origin_mm, const Vec3f& rotate_deg, double scale = 1.0);

// Throws Error naming the field if a parameter is out of range.
void validate_feather_shape(const FeatherShape& shape);

// Builds one feather, placed. `seed` keys every random draw. Throws Error before building the
// barbules if the feather would exceed `max_triangles` (a 2-core machine renders a few 10^5).
FeatherGeometry build_feather(const FeatherShape& shape, FeatherDetail detail, std::uint64_t seed,
                              const Placement& placement = {}, std::size_t max_triangles = 4'000'000);

// Appends `part` to `into` (offsets indices; barbule ids continue after into's largest + 1).
void append_mesh(SceneMesh& into, const SceneMesh& part);

// Barb-level feathers on an ellipsoidal body (paper §7.4, Fig. 14): feather bases on a
// Fibonacci lattice over the part of the ellipsoid with latitude in [lat_min, lat_max]
// (body frame: the axis of radius ry is the body's long axis, feathers point toward −y, "tail"),
// lying at `lie_deg` from the surface, with seeded jitter of position, heading, lie and size.
struct BodyShape {
  Vec3f center_mm;
  Vec3f radii_mm = {20, 40, 20};  // x, y, z semi-axes
  double lat_min_deg = -90.0, lat_max_deg = 90.0;  // latitude about the y axis's equator: y/ry = sin(lat)
};
struct AssemblyShape {
  BodyShape body;
  FeatherShape feather;  // the mean feather
  int count = 1200;
  double lie_deg = 12.0;          // feather plane vs the local tangent plane
  double heading_jitter_deg = 6.0;
  double lie_jitter_deg = 3.0;
  double size_jitter = 0.1;       // relative
  double position_jitter = 0.3;   // of the lattice spacing
};
struct AssemblyGeometry {
  SceneMesh shaft, vane;
  std::size_t feather_count = 0, barb_count = 0, barbule_count = 0;
};
AssemblyGeometry build_feather_assembly(const AssemblyShape& shape, std::uint64_t seed,
                                        std::size_t max_triangles = 4'000'000);

// Seeds: the seed of item `index` of a scene object (config seed, object name).
std::uint64_t object_item_seed(std::uint64_t seed, const std::string& object_name, std::uint64_t index);

}  // namespace plumage
