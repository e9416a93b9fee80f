// A scene file (configs/scenes/<scene>.yaml) read into plain data: camera(s), lights, materials,
// objects (procedural feathers, barb-level assemblies, planes) and the image's size. Every error
// is a ConfigError naming file:line:column and the field; unknown keys are rejected with the
// nearest valid name (params.hpp). Each section is read by one parameter table (param_table.hpp,
// listed in docs/parameters.md under "scene"). Geometry is built separately
// (build_scene_meshes), feather materials are resolved by the caller, and the renderer reads its
// own section (render_job.hpp does all three for `plumage render`). User guide: docs/scenes.md.
//
//   scene: starling                      # name of the outputs (default: the file's stem)
//   renderer: pathtracer                 # or {type: pathtracer, spp: 16, seed: 1, lod: auto, ...}:
//                                        # a kind "renderer" plug-in and its own settings
//   render: {resolution: [512, 512], max_triangles: 4000000, exposure: 1, warning_share: 0.01}
//   camera: {position_mm: [x, y, z], look_at_mm: [x, y, z], up: [0, 0, 1], fov_deg: 30}
//   lights:
//     - {type: distant, toward_light: [x, y, z], irradiance: 1}
//     - {type: point, position_mm: [x, y, z], intensity: 1}
//     - {type: area, corner_mm: [..], edge_u_mm: [..], edge_v_mm: [..], radiance: 1, two_sided: false}
//     - {type: environment, radiance: 0.05}
//   materials:
//     starling: {type: feather, species: ../species/starling.yaml, variant: green, fidelity: preview}
//     custom:   {type: feather, file: my.plm}          # a characterised material file
//     shaft:    {type: diffuse, albedo: 0.05}          # or {lambda_nm: [...], value: [...]}
//     glass:    {type: dielectric, ior: 1.5}
//   objects:
//     - {type: feather, material: starling, shaft_material: shaft, detail: barbules | barb_level,
//        shape: {length_mm: 30, ...FeatherShape}, position_mm: [..], rotate_deg: [..], scale: 1, seed: 1}
//     - {type: assembly, material: ..., count: 1200, body: {center_mm, radii_mm, lat_min_deg,
//        lat_max_deg}, lie_deg: 12, feather: {...FeatherShape}, seed: 1, ...}
//     - {type: plane, material: ground, center_mm: [..], normal: [0, 0, 1], size_mm: 200}
//   views:                               # optional: named variants of camera and lights
//     - {name: a, camera: {...keys override the top-level camera}, lights: [...replace]}
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "plumage/config_document.hpp"
#include "plumage/feather_geometry.hpp"
#include "plumage/scene.hpp"

namespace plumage {

// A `type: feather` material before it is resolved to a FeatherBsdf.
struct FeatherMaterialRequest {
  std::filesystem::path species_config;  // resolved against the scene file's folder
  std::string variant;                   // empty: the species file's default variant
  std::string fidelity = "preview";      // preview | production
  std::filesystem::path file;            // explicit .plm (species_config then empty)
  double transmission_albedo = 0.02;
  SourceMark where;                      // the material's entry, for messages
};

struct SceneObjectSpec {
  enum class Kind { feather, assembly, plane };
  std::string name;
  Kind kind = Kind::feather;
  std::uint32_t material = 0;
  std::uint32_t shaft_material = 0;
  std::uint64_t seed = 1;
  // feather
  FeatherShape shape;
  FeatherDetail detail = FeatherDetail::barbules;
  Placement placement;
  // assembly (its feather shape is assembly.feather)
  AssemblyShape assembly;
  // plane: a square of side size_mm centred at center_mm, facing `normal`
  Vec3f center_mm, normal = {0, 0, 1};
  double size_mm = 100.0;
};

struct SceneView {
  std::string name;  // empty: the scene has no `views:`
  Camera camera;
  std::vector<PointLight> point_lights;
  std::vector<DistantLight> distant_lights;
  std::vector<AreaLight> area_lights;
  EnvironmentLight environment;
};

struct SceneConfig {
  std::filesystem::path file;
  std::string name;
  std::string content_hash;
  ParamView root;  // kept for the `renderer:` section, which the renderer reads (render_job.hpp)
  bool has_renderer_section = false;
  std::vector<SceneMaterial> materials;  // feather entries have feather == nullptr until resolved
  std::vector<std::optional<FeatherMaterialRequest>> feather_requests;  // per material
  std::vector<SceneObjectSpec> objects;
  std::vector<SceneView> views;  // ≥ 1: the top-level camera and lights when no `views:`
  std::size_t max_triangles = 4'000'000;
  double exposure = 1.0;  // render.exposure: scale of the PNG preview only (the EXR is radiance)
  // render.warning_share: the share of a feather material's throughput-weighted BSDF evaluations
  // in the directions where a warning code was raised above which the render raises it
  // (material_warnings.hpp, render_job.cpp).
  double warning_share = 0.01;
};

// Reads and validates a scene file (ConfigError on any problem).
SceneConfig load_scene_config(const std::filesystem::path& file);
SceneConfig parse_scene_config(const ConfigDocument& doc);

struct SceneGeometryStats {
  std::size_t triangles = 0, barbule_ids = 0, feathers = 0, barbs = 0;
};
// Builds every object's meshes (deterministic: seeds from the config and object/item index).
// Throws Error naming the object if a limit is exceeded.
std::vector<SceneMesh> build_scene_meshes(const SceneConfig& config, SceneGeometryStats* stats = nullptr);

// The renderable scene of one view (materials must be resolved by then).
Scene make_scene(const SceneConfig& config, const SceneView& view, std::vector<SceneMesh> meshes);

// The view named `name`; an unknown name is a ConfigError (field "views") naming the nearest
// view and listing them all.
const SceneView& find_view(const SceneConfig& config, const std::string& name);

}  // namespace plumage
