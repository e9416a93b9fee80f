// The sections of a scene file (scene_config.hpp), one reader and one parameter table each
// (param_table.hpp): camera and lights (scene_camera_lights.cpp), materials
// (scene_materials.cpp), objects and feather shapes (scene_objects.cpp); the file's top level,
// `render:` and `views:` in scene_config.cpp. Every table is registered as a config section
// (config_sections.hpp), so docs/parameters.md lists the scene's keys.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "plumage/param_table.hpp"
#include "plumage/scene_config.hpp"

namespace plumage::scene_detail {

// [x, y, z] (exactly 3 numbers, each within `limits`: by default a scene coordinate, params.hpp);
// absent: the fallback. unit3: normalised, not the zero vector.
Vec3f read_vec3(const ParamView& node, std::string_view key, Limits limits = Limits::scene_coordinate_mm());
Vec3f read_vec3_or(const ParamView& node, std::string_view key, Vec3f fallback,
                   Limits limits = Limits::scene_coordinate_mm());
Vec3f read_unit3(const ParamView& node, std::string_view key);

// A view's camera: `base` (the scene's camera) supplies every key the section leaves out; without
// a base, position_mm and look_at_mm are required.
Camera read_camera(const ParamView& section, const Camera* base);
// The `lights:` list of `parent` replaces the view's lights.
void read_lights(const ParamView& parent, SceneView& view);
// The `materials:` map, in file order, appended to config.materials / feather_requests.
void read_materials(const ParamView& materials, const std::filesystem::path& directory, SceneConfig& config);
// The `objects:` list (at least one); may append the implicit `default_shaft` material.
void read_objects(const ParamView& root, SceneConfig& config);

std::vector<ParamSpec> camera_specs();
std::vector<ParamSpec> light_specs();
std::vector<ParamSpec> material_specs();
std::vector<ParamSpec> object_specs();

}  // namespace plumage::scene_detail
