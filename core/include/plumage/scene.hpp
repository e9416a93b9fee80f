// A renderable scene (issue 8): what `plumage render` hands to a Renderer plug-in after reading
// configs/scenes/<scene>.yaml, building the procedural feathers and resolving every material.
// Plain data: no plug-in types, no YAML; a Renderer never opens a file. How to render it (samples,
// seed, level of detail...) is the renderer's own business (renderer.hpp).
//
// Units: scene lengths in millimetres (a feather is tens of mm, a barbule tens of µm), angles in
// radians, wavelengths in nm. Emission spectra have the shape of illuminant D65 (colour.hpp,
// SpectrumKind::radiance) times a scalar, so a white diffuse surface renders white.
//
// Feather shading frame (conventions.hpp, BRDF frame): per triangle, `frame_axis` t is the
// barbule axis (BRDF y) and `frame_normal` n the barbule's mean normal (BRDF z); BRDF x = t × n
// (across the barbule). For barb-level feathers the barbules' orientation is already folded
// into these vectors (paper §7.3).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plumage/feather_bsdf.hpp"

namespace plumage {

struct Vec3f {
  float x = 0.0f, y = 0.0f, z = 0.0f;
};

// Reflectance (or transmittance) sampled at `lambda_nm`, linear in between, ends held. One value:
// constant. Empty: 0.
struct TabulatedSpectrum {
  std::vector<double> lambda_nm;
  std::vector<double> value;
  double at(double lambda) const;
};

struct SceneMaterial {
  enum class Kind { feather, diffuse, dielectric };
  std::string name;
  Kind kind = Kind::diffuse;
  std::shared_ptr<const FeatherBsdf> feather;  // kind feather
  TabulatedSpectrum albedo;                    // kind diffuse: Lambertian reflectance
  double ior = 1.5;                            // kind dielectric: smooth interface, real index
};

struct SceneMesh {
  std::string name;
  std::vector<Vec3f> positions;                         // mm
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions
  // Per triangle, unit and orthogonal; required for feather materials, ignored otherwise
  // (the geometric normal is used).
  std::vector<Vec3f> frame_axis, frame_normal;
  // Per triangle: the barbule a triangle belongs to; BRDF instance k = barbule_id (empty: all 0).
  std::vector<std::uint32_t> barbule_id;
  std::uint32_t material = 0;  // index into Scene::materials
  // Level of detail (DESIGN §7): centre-to-centre distance of neighbouring barbules, mm. Where a
  // pixel's footprint covers many of them the renderer uses the mean BRDF. 0: not a feather.
  double barbule_spacing_mm = 0.0;
};

struct PointLight {
  Vec3f position_mm;
  double intensity = 1.0;  // radiant intensity scale (× D65 shape), per steradian
};
struct DistantLight {
  Vec3f toward_light = {0.0f, 0.0f, 1.0f};  // unit, world frame, pointing to the light
  double irradiance = 1.0;                  // on a surface facing it (× D65 shape)
};
// A one- or two-sided emitting parallelogram: corner + s·edge_u + t·edge_v, s, t ∈ [0, 1],
// emitting on the side of edge_u × edge_v (both sides when two_sided).
struct AreaLight {
  Vec3f corner_mm, edge_u_mm, edge_v_mm;
  double radiance = 1.0;  // × D65 shape
  bool two_sided = false;
};
// Constant radiance from every direction (× D65 shape); 0 switches it off.
struct EnvironmentLight {
  double radiance = 0.0;
};

struct Camera {
  Vec3f position_mm, look_at_mm, up = {0.0f, 1.0f, 0.0f};
  double vertical_fov_rad = 0.5;
  int width = 512, height = 512;
};

struct Scene {
  std::string name;
  std::vector<SceneMaterial> materials;
  std::vector<SceneMesh> meshes;
  std::vector<PointLight> point_lights;
  std::vector<DistantLight> distant_lights;
  std::vector<AreaLight> area_lights;
  EnvironmentLight environment;
  Camera camera;
};

}  // namespace plumage
