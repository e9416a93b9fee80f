// Scene files (scene_config.hpp): the top level, `render:` and `views:`; the other sections in
// scene_camera_lights.cpp, scene_materials.cpp and scene_objects.cpp (scene_sections.hpp). Every
// read goes through ParamView, so every error names file:line:column and the field, and unknown
// keys get the nearest valid name.
#include "plumage/scene_config.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/config_sections.hpp"
#include "scene_sections.hpp"

namespace plumage {

using namespace scene_detail;

namespace {

// ---- render: the image, not the renderer -------------------------------------------------------

struct RenderKeys {
  int width = 0, height = 0;  // 0: the camera's default (512)
  std::size_t max_triangles = 4'000'000;
  double exposure = 1.0;
  double warning_share = 0.01;
};

const ParamTable<RenderKeys>& render_table() {
  static const auto table =
      ParamTable<RenderKeys>{}
          .custom("resolution", "list", "px", "[512, 512]", "[width, height] of every view's image, whole pixels in [1, 16384]",
                  [](const ParamView& r, RenderKeys& k) {
                    if (!r.has("resolution")) return;
                    const std::vector<double> res = r.numbers("resolution", Limits::closed(1, 16384));
                    if (res.size() != 2 || res[0] != std::floor(res[0]) || res[1] != std::floor(res[1]))
                      r.fail("resolution", "expected [width, height] in whole pixels");
                    k.width = static_cast<int>(res[0]), k.height = static_cast<int>(res[1]);
                  })
          .integer("max_triangles", &RenderKeys::max_triangles, "1", 4'000'000, Limits::closed(1, 1e8),
                   "budget of the scene's geometry, checked before barbules are built")
          .number("exposure", &RenderKeys::exposure, "1", 1.0, Limits::positive(),
                  "scale of the PNG preview only (the EXR holds radiance)")
          .number("warning_share", &RenderKeys::warning_share, "1", 0.01, Limits::closed(0, 1),
                  "a feather material's warning raised per direction in its characterisation (e.g. approx.grazing) "
                  "is passed on by the render only when at least this share of the material's feather BSDF "
                  "evaluations, weighted by path throughput times f*cos, has its incident direction where the code "
                  "was raised (1 %: a lobe that small is below the preview's noise); 0: always, 1: only if all");
  return table;
}

// The renderer's settings lived in `render:` before they became the renderer's own: say where
// they went rather than only "unknown key".
void refuse_renderer_keys(const ParamView& r) {
  const std::vector<std::string> names = render_table().names();
  for (const std::string& key : r.keys()) {
    if (std::find(names.begin(), names.end(), key) != names.end() || nearest_name(key, names)) continue;
    r.fail(key, "not a key of render: (resolution, max_triangles, exposure, warning_share); the renderer's own settings (spp, seed, "
                "lod, ...) go in its section, e.g. renderer: {type: pathtracer, " + key + ": ...}");
  }
}

// ---- views ---------------------------------------------------------------------------------------

std::vector<ParamSpec> view_specs() {
  return {{"name", "text", "-", "required", "the view's name (output <scene>-<name>.exr)", "", ""},
          {"camera", "map", "-", "the scene's camera", "keys override the scene's camera one by one", "", ""},
          {"lights", "list", "-", "the scene's lights", "replace the scene's lights", "", ""}};
}

void read_views(const ParamView& root, const SceneView& base, bool have_camera, SceneConfig& c) {
  c.views.clear();
  std::vector<std::string> seen;
  for (const ParamView& v : root.items("views")) {
    SceneView view = base;
    view.name = v.text("name");
    if (std::find(seen.begin(), seen.end(), view.name) != seen.end()) v.fail("name", "duplicate view name '" + view.name + "'");
    seen.push_back(view.name);
    if (v.has("camera")) view.camera = read_camera(v.child("camera"), have_camera ? &base.camera : nullptr);
    else if (!have_camera) v.fail("camera", "missing: no top-level camera to inherit");
    else v.accept("camera");
    view.camera.width = base.camera.width, view.camera.height = base.camera.height;
    if (v.has("lights")) read_lights(v, view);
    else v.accept("lights");
    c.views.push_back(view);
  }
  if (c.views.empty()) root.fail("views", "an empty list (leave the key out instead)");
}

// ---- the file ------------------------------------------------------------------------------------

std::vector<ParamSpec> top_level_specs() {
  return {{"scene", "text", "-", "the file's stem", "name of the outputs", "", ""},
          {"description", "text", "-", "\"\"", "free text", "", ""},
          {"renderer", "text or map", "-", "pathtracer",
           "a kind `renderer` plug-in: its type, or {type: ..., its own settings} (plug-in types below)", "", ""},
          {"render", "map", "-", "{}", "the images: resolution, geometry budget, PNG exposure (scene: render)", "", ""},
          {"camera", "map", "-", "required unless every view has one", "pinhole camera (scene: camera)", "", ""},
          {"lights", "list", "-", "[]", "lights of every view (scene: lights[])", "", ""},
          {"materials", "map", "-", "{}", "name -> material (scene: materials.<name>)", "", ""},
          {"objects", "list", "-", "required", "at least one object (scene: objects[])", "", ""},
          {"views", "list", "-", "one unnamed view", "named variants of camera and lights (scene: views[])", "", ""}};
}

const ConfigSectionRegistration kSceneSections[] = {
    ConfigSectionRegistration{{"scene", "(top level)", "a scene file (configs/scenes/*.yaml, `plumage render`)", top_level_specs}},
    ConfigSectionRegistration{{"scene", "render", "the images of every view", [] { return render_table().specs(); }}},
    ConfigSectionRegistration{{"scene", "camera", "pinhole camera; in a view, keys override the scene's", camera_specs}},
    ConfigSectionRegistration{{"scene", "lights[]", "one light; `type` selects the rows that apply", light_specs}},
    ConfigSectionRegistration{{"scene", "materials.<name>", "one material; `type` selects the rows that apply", material_specs}},
    ConfigSectionRegistration{{"scene", "objects[]", "one object; `type` selects the rows that apply", object_specs}},
    ConfigSectionRegistration{{"scene", "views[]", "a named variant of the camera and lights", view_specs}},
};

}  // namespace

SceneConfig parse_scene_config(const ConfigDocument& doc) {
  SceneConfig c;
  const ParamView root = doc.root();
  if (!root.is_map()) root.fail_here("a scene file is a map (scene, camera, lights, materials, objects, render)");
  c.file = doc.path();
  c.content_hash = doc.content_hash();
  c.root = root;
  c.name = root.text_or("scene", doc.path().stem().string());
  root.accept("description");
  // The renderer reads its own section when it is created (render_job.hpp); not read here.
  root.accept("renderer");
  c.has_renderer_section = root.has("renderer");

  RenderKeys render = render_table().defaults();
  if (auto r = root.child_if("render")) {
    render = render_table().read(*r);
    refuse_renderer_keys(*r);
  }
  c.max_triangles = render.max_triangles;
  c.exposure = render.exposure;
  c.warning_share = render.warning_share;

  // Top-level camera and lights: the defaults of every view.
  SceneView base;
  const bool have_camera = root.has("camera");
  if (have_camera) base.camera = read_camera(root.child("camera"), nullptr);
  if (render.width > 0) base.camera.width = render.width, base.camera.height = render.height;
  if (root.has("lights")) read_lights(root, base);
  else root.accept("lights");

  if (root.has("materials")) read_materials(root.child("materials"), doc.directory(), c);
  else root.accept("materials");
  read_objects(root, c);

  if (root.has("views")) {
    read_views(root, base, have_camera, c);
  } else {
    root.accept("views");
    if (!have_camera) root.fail("camera", "missing required key 'camera'");
    c.views.assign(1, base);
  }
  for (const auto& v : c.views) {
    const bool lit = !v.point_lights.empty() || !v.distant_lights.empty() || !v.area_lights.empty() || v.environment.radiance > 0;
    if (!lit) root.fail(root.has("views") ? "views" : "lights", "view '" + v.name + "' has no light");
  }
  root.finish();
  return c;
}

SceneConfig load_scene_config(const std::filesystem::path& file) { return parse_scene_config(ConfigDocument::load(file)); }

const SceneView& find_view(const SceneConfig& config, const std::string& name) {
  std::vector<std::string> names;
  for (const auto& v : config.views) {
    if (v.name == name) return v;
    names.push_back(v.name);
  }
  if (config.views.size() == 1 && config.views[0].name.empty())
    throw ConfigError({config.file.string()}, "views", "no view '" + name + "': the scene has no `views:` (leave out the view)");
  std::string msg = "no view '" + name + "'";
  if (auto near = nearest_name(name, names)) msg += " (did you mean '" + *near + "'?)";
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
  throw ConfigError({config.file.string()}, "views", msg + "; views: " + (all.empty() ? "(none)" : all));
}

}  // namespace plumage
