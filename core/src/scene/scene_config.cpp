// Scene files (scene_config.hpp): parsing and validation through ParamView, so that every error
// names file:line:column and the field, and unknown keys get the nearest valid name.
#include "plumage/scene_config.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "vec3d.hpp"

namespace plumage {

using namespace scene_detail;

namespace {

Vec3f vec3(const ParamView& node, std::string_view key) {
  const std::vector<double> v = node.numbers(key);
  if (v.size() != 3) node.fail(key, "expected 3 numbers [x, y, z], got " + std::to_string(v.size()));
  return to_f({v[0], v[1], v[2]});
}
Vec3f vec3_or(const ParamView& node, std::string_view key, Vec3f fallback) {
  return node.has(key) ? vec3(node, key) : (node.accept(key), fallback);
}
Vec3f unit3(const ParamView& node, std::string_view key) {
  const V3 v = from_f(vec3(node, key));
  if (!(norm(v) > 0)) node.fail(key, "must not be the zero vector");
  return to_f(normalized(v));
}

Camera parse_camera(const ParamView& c, const Camera* base) {
  Camera cam = base ? *base : Camera{};
  if (base) {
    cam.position_mm = vec3_or(c, "position_mm", cam.position_mm);
    cam.look_at_mm = vec3_or(c, "look_at_mm", cam.look_at_mm);
  } else {
    cam.position_mm = vec3(c, "position_mm");
    cam.look_at_mm = vec3(c, "look_at_mm");
  }
  if (c.has("up")) cam.up = unit3(c, "up");
  else c.accept("up"), cam.up = base ? base->up : Vec3f{0, 0, 1};
  const double fov = c.number_or("fov_deg", base ? cam.vertical_fov_rad * 180.0 / kPiD : 30.0, Limits{0.0, 179.0, true, true});
  cam.vertical_fov_rad = rad(fov);
  const V3 forward = from_f(cam.look_at_mm) - from_f(cam.position_mm);
  if (!(norm(forward) > 0)) c.fail("look_at_mm", "equals position_mm (no viewing direction)");
  if (norm(cross(normalized(forward), from_f(cam.up))) < 1e-6) c.fail("up", "is parallel to the viewing direction");
  return cam;
}

void parse_lights(const ParamView& root, SceneView& view) {
  view.point_lights.clear(), view.distant_lights.clear(), view.area_lights.clear();
  view.environment = {};
  static constexpr std::string_view kTypes[] = {"distant", "point", "area", "environment"};
  for (const ParamView& l : root.items("lights")) {
    const std::string type = l.choice("type", kTypes);
    if (type == "distant") {
      view.distant_lights.push_back({unit3(l, "toward_light"), l.number_or("irradiance", 1.0, Limits::non_negative())});
    } else if (type == "point") {
      view.point_lights.push_back({vec3(l, "position_mm"), l.number_or("intensity", 1.0, Limits::non_negative())});
    } else if (type == "area") {
      AreaLight a;
      a.corner_mm = vec3(l, "corner_mm");
      a.edge_u_mm = vec3(l, "edge_u_mm");
      a.edge_v_mm = vec3(l, "edge_v_mm");
      if (!(norm(cross(from_f(a.edge_u_mm), from_f(a.edge_v_mm))) > 0)) l.fail("edge_v_mm", "the edges span no area");
      a.radiance = l.number_or("radiance", 1.0, Limits::non_negative());
      a.two_sided = l.boolean_or("two_sided", false);
      view.area_lights.push_back(a);
    } else {
      if (view.environment.radiance > 0) l.fail("type", "only one environment light per scene");
      view.environment.radiance = l.number_or("radiance", 0.05, Limits::non_negative());
    }
  }
}

FeatherShape parse_shape(const ParamView& s, FeatherShape f) {
  const auto pos = Limits::positive(), nonneg = Limits::non_negative();
  f.length_mm = s.number_or("length_mm", f.length_mm, pos);
  f.calamus_mm = s.number_or("calamus_mm", f.calamus_mm, nonneg);
  f.vane_width_mm = s.number_or("vane_width_mm", f.vane_width_mm, pos);
  f.vane_asymmetry = s.number_or("vane_asymmetry", f.vane_asymmetry, Limits::closed(-0.8, 0.8));
  f.camber_mm = s.number_or("camber_mm", f.camber_mm);
  f.rachis_width_mm = s.number_or("rachis_width_mm", f.rachis_width_mm, pos);
  f.barb_spacing_mm = s.number_or("barb_spacing_mm", f.barb_spacing_mm, pos);
  f.barb_angle_deg = s.number_or("barb_angle_deg", f.barb_angle_deg, Limits{1.0, 89.0, true, true});
  f.barb_curl_deg = s.number_or("barb_curl_deg", f.barb_curl_deg, Limits{0.0, 80.0, false, true});
  f.barb_width_mm = s.number_or("barb_width_mm", f.barb_width_mm, pos);
  f.barb_segment_mm = s.number_or("barb_segment_mm", f.barb_segment_mm, pos);
  f.barbule_length_mm = s.number_or("barbule_length_mm", f.barbule_length_mm, pos);
  f.barbule_width_mm = s.number_or("barbule_width_mm", f.barbule_width_mm, pos);
  f.barbule_spacing_mm = s.number_or("barbule_spacing_mm", f.barbule_spacing_mm, pos);
  f.barbule_angle_deg = s.number_or("barbule_angle_deg", f.barbule_angle_deg, Limits{0.0, 90.0, false, true});
  f.barbule_tilt_deg = s.number_or("barbule_tilt_deg", f.barbule_tilt_deg, Limits{-90.0, 90.0, true, true});
  f.barbule_elevation_deg = s.number_or("barbule_elevation_deg", f.barbule_elevation_deg, Limits{-90.0, 90.0, true, true});
  f.barbule_segments = static_cast<int>(s.integer_or("barbule_segments", f.barbule_segments, Limits::closed(1, 16)));
  f.proximal_barbules = s.boolean_or("proximal_barbules", f.proximal_barbules);
  f.jitter = s.number_or("jitter", f.jitter, Limits::closed(0.0, 0.5));
  try {
    validate_feather_shape(f);
  } catch (const Error& e) {
    s.fail_here(e.what());
  }
  return f;
}

std::uint32_t material_ref(const ParamView& o, std::string_view key, const std::vector<std::string>& names) {
  const std::string name = o.text(key);
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string msg = "unknown material '" + name + "'";
    if (auto near = nearest_name(name, names)) msg += " (did you mean '" + *near + "'?)";
    std::string all;
    for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
    o.fail(key, msg + "; materials: " + (all.empty() ? "(none)" : all));
  }
  return static_cast<std::uint32_t>(it - names.begin());
}

TabulatedSpectrum parse_spectrum(const ParamView& m, std::string_view key) {
  TabulatedSpectrum s;
  const ParamView v = m.node(key);
  if (v.is_scalar()) {
    s.value = {v.scalar_number(Limits::unit_interval())};
    s.lambda_nm = {550.0};
    return s;
  }
  if (!v.is_map()) m.fail(key, "expected a number or {lambda_nm: [...], value: [...]}");
  s.lambda_nm = v.numbers("lambda_nm", Limits::positive());
  s.value = v.numbers("value", Limits::unit_interval());
  if (s.lambda_nm.size() != s.value.size() || s.value.empty())
    v.fail("value", "needs as many entries as lambda_nm (" + std::to_string(s.lambda_nm.size()) + ")");
  for (std::size_t k = 1; k < s.lambda_nm.size(); ++k)
    if (s.lambda_nm[k] <= s.lambda_nm[k - 1]) v.fail("lambda_nm", "must be strictly ascending");
  return s;
}

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

  // Renderer: created later through the registry (kind "renderer"); only its type is read here.
  root.accept("renderer");
  c.has_renderer_section = root.has("renderer");

  // Render settings.
  if (auto r = root.child_if("render")) {
    RenderSettings& s = c.settings;
    s.samples_per_pixel = static_cast<int>(r->integer_or("spp", s.samples_per_pixel, Limits::closed(1, 1 << 20)));
    s.seed = static_cast<std::uint64_t>(r->integer_or("seed", 1, Limits::non_negative()));
    s.max_depth = static_cast<int>(r->integer_or("max_depth", s.max_depth, Limits::closed(1, 1000)));
    static constexpr std::string_view kLod[] = {"auto", "mean", "instance"};
    const std::string lod = r->choice_or("lod", kLod, "auto");
    s.lod = lod == "mean" ? LevelOfDetail::mean : lod == "instance" ? LevelOfDetail::instance : LevelOfDetail::automatic;
    s.lod_barbules = r->number_or("lod_barbules", s.lod_barbules, Limits::positive());
    s.spectral_bins = static_cast<int>(r->integer_or("spectral_bins", 0, Limits::closed(0, 300)));
    s.tile_size = static_cast<int>(r->integer_or("tile_size", s.tile_size, Limits::closed(1, 1024)));
    if (r->has("lambda_nm")) {
      const auto [lo, hi] = r->interval("lambda_nm", Limits::closed(300, 1000));
      if (!(hi > lo)) r->fail("lambda_nm", "needs lo < hi");
      s.lambda_min_nm = lo, s.lambda_max_nm = hi;
    } else {
      r->accept("lambda_nm");
    }
    if (r->has("resolution")) {
      const std::vector<double> res = r->numbers("resolution", Limits::closed(1, 16384));
      if (res.size() != 2 || res[0] != std::floor(res[0]) || res[1] != std::floor(res[1]))
        r->fail("resolution", "expected [width, height] in whole pixels");
      c.views.resize(1);
      c.views[0].camera.width = static_cast<int>(res[0]);
      c.views[0].camera.height = static_cast<int>(res[1]);
    } else {
      r->accept("resolution");
    }
    c.exposure = r->number_or("exposure", 1.0, Limits::positive());
    c.max_triangles = static_cast<std::size_t>(r->integer_or("max_triangles", 4'000'000, Limits::closed(1, 1e8)));
  }
  const int width = c.views.empty() ? 512 : c.views[0].camera.width;
  const int height = c.views.empty() ? 512 : c.views[0].camera.height;

  // Top-level camera and lights: the defaults of every view.
  SceneView base;
  bool have_camera = false;
  if (root.has("camera")) {
    base.camera = parse_camera(root.child("camera"), nullptr);
    have_camera = true;
  }
  base.camera.width = width, base.camera.height = height;
  if (root.has("lights")) parse_lights(root, base);
  else root.accept("lights");

  // Materials (map name → material, in file order).
  std::vector<std::string> names;
  if (root.has("materials")) {
    const ParamView mats = root.child("materials");
    static constexpr std::string_view kKinds[] = {"feather", "diffuse", "dielectric"};
    static constexpr std::string_view kFidelity[] = {"preview", "production"};
    for (const std::string& name : mats.keys()) {
      const ParamView m = mats.child(name);
      SceneMaterial mat;
      mat.name = name;
      const std::string kind = m.choice("type", kKinds);
      std::optional<FeatherMaterialRequest> request;
      if (kind == "feather") {
        mat.kind = SceneMaterial::Kind::feather;
        FeatherMaterialRequest q;
        q.where = m.mark();
        if (m.has("file") == m.has("species")) m.fail_here("a feather material needs exactly one of 'species' (a species config) or 'file' (a .plm)");
        if (m.has("file")) {
          q.file = doc.directory() / m.text("file");
          if (!std::filesystem::exists(q.file)) m.fail("file", "no such material file: " + q.file.string());
        } else {
          q.species_config = doc.directory() / m.text("species");
          if (!std::filesystem::exists(q.species_config)) m.fail("species", "no such species config: " + q.species_config.string());
        }
        q.variant = m.text_or("variant", "");
        q.fidelity = m.choice_or("fidelity", kFidelity, "preview");
        q.transmission_albedo = m.number_or("transmission_albedo", 0.02, Limits::unit_interval());
        request = q;
      } else if (kind == "diffuse") {
        mat.kind = SceneMaterial::Kind::diffuse;
        if (m.has("albedo")) mat.albedo = parse_spectrum(m, "albedo");
        else m.accept("albedo"), mat.albedo.value = {0.5}, mat.albedo.lambda_nm = {550.0};
      } else {
        mat.kind = SceneMaterial::Kind::dielectric;
        mat.ior = m.number_or("ior", 1.5, Limits{1.0, 4.0, false, false});
      }
      names.push_back(name);
      c.materials.push_back(std::move(mat));
      c.feather_requests.push_back(std::move(request));
    }
  } else {
    root.accept("materials");
  }
  // Implicit material for rachis and barbs when an object names none: dark keratin.
  auto default_shaft = [&]() -> std::uint32_t {
    const auto it = std::find(names.begin(), names.end(), "default_shaft");
    if (it != names.end()) return static_cast<std::uint32_t>(it - names.begin());
    SceneMaterial m;
    m.name = "default_shaft";
    m.kind = SceneMaterial::Kind::diffuse;
    m.albedo.value = {0.04};
    m.albedo.lambda_nm = {550.0};
    names.push_back(m.name);
    c.materials.push_back(m);
    c.feather_requests.emplace_back();
    return static_cast<std::uint32_t>(c.materials.size() - 1);
  };

  // Objects.
  static constexpr std::string_view kObjects[] = {"feather", "assembly", "plane"};
  static constexpr std::string_view kDetail[] = {"barbules", "barb_level"};
  std::size_t index = 0;
  for (const ParamView& o : root.items("objects")) {
    SceneObjectSpec obj;
    const std::string type = o.choice("type", kObjects);
    obj.name = o.text_or("name", type + std::to_string(index++));
    obj.material = material_ref(o, "material", names);
    obj.seed = static_cast<std::uint64_t>(o.integer_or("seed", 1, Limits::non_negative()));
    const bool feather_material = c.materials[obj.material].kind == SceneMaterial::Kind::feather;
    if (type == "feather" || type == "assembly") {
      obj.shaft_material = o.has("shaft_material") ? material_ref(o, "shaft_material", names) : (o.accept("shaft_material"), default_shaft());
    }
    if (type == "feather") {
      obj.kind = SceneObjectSpec::Kind::feather;
      obj.detail = o.choice_or("detail", kDetail, "barbules") == "barb_level" ? FeatherDetail::barb_level : FeatherDetail::barbules;
      obj.shape = o.has("shape") ? parse_shape(o.child("shape"), FeatherShape{}) : (o.accept("shape"), FeatherShape{});
      obj.placement = placement_from_euler(vec3_or(o, "position_mm", {}), vec3_or(o, "rotate_deg", {}),
                                           o.number_or("scale", 1.0, Limits::positive()));
      if (!feather_material) o.fail("material", "a feather object needs a feather material");
    } else if (type == "assembly") {
      obj.kind = SceneObjectSpec::Kind::assembly;
      AssemblyShape& a = obj.assembly;
      a.count = static_cast<int>(o.integer_or("count", a.count, Limits::closed(1, 100000)));
      a.lie_deg = o.number_or("lie_deg", a.lie_deg, Limits::closed(0, 89));
      a.heading_jitter_deg = o.number_or("heading_jitter_deg", a.heading_jitter_deg, Limits::closed(0, 180));
      a.lie_jitter_deg = o.number_or("lie_jitter_deg", a.lie_jitter_deg, Limits::closed(0, 45));
      a.size_jitter = o.number_or("size_jitter", a.size_jitter, Limits::closed(0, 0.9));
      a.position_jitter = o.number_or("position_jitter", a.position_jitter, Limits::closed(0, 1));
      const ParamView body = o.child("body");
      a.body.center_mm = vec3_or(body, "center_mm", {});
      a.body.radii_mm = vec3(body, "radii_mm");
      if (!(a.body.radii_mm.x > 0 && a.body.radii_mm.y > 0 && a.body.radii_mm.z > 0)) body.fail("radii_mm", "must all be > 0");
      a.body.lat_min_deg = body.number_or("lat_min_deg", -90.0, Limits::closed(-90, 90));
      a.body.lat_max_deg = body.number_or("lat_max_deg", 90.0, Limits::closed(-90, 90));
      if (!(a.body.lat_min_deg < a.body.lat_max_deg)) body.fail("lat_max_deg", "must exceed lat_min_deg");
      FeatherShape small;  // a body feather: short, broad, coarser barbs (barb-level)
      small.length_mm = 12, small.vane_width_mm = 9, small.barb_spacing_mm = 0.5, small.barb_segment_mm = 0.8;
      small.rachis_width_mm = 0.3, small.calamus_mm = 1.0, small.camber_mm = 0.5;
      a.feather = o.has("feather") ? parse_shape(o.child("feather"), small) : (o.accept("feather"), small);
      if (!feather_material) o.fail("material", "an assembly needs a feather material");
    } else {
      obj.kind = SceneObjectSpec::Kind::plane;
      obj.center_mm = vec3_or(o, "center_mm", {});
      obj.normal = o.has("normal") ? unit3(o, "normal") : (o.accept("normal"), Vec3f{0, 0, 1});
      obj.size_mm = o.number_or("size_mm", 100.0, Limits::positive());
      if (feather_material) o.fail("material", "a plane takes a diffuse or dielectric material");
    }
    c.objects.push_back(std::move(obj));
  }
  if (c.objects.empty()) root.fail("objects", "a scene needs at least one object");

  // Views.
  if (root.has("views")) {
    c.views.clear();
    std::vector<std::string> seen;
    for (const ParamView& v : root.items("views")) {
      SceneView view = base;
      view.name = v.text("name");
      if (std::find(seen.begin(), seen.end(), view.name) != seen.end()) v.fail("name", "duplicate view name '" + view.name + "'");
      seen.push_back(view.name);
      if (v.has("camera")) view.camera = parse_camera(v.child("camera"), have_camera ? &base.camera : nullptr);
      else if (!have_camera) v.fail("camera", "missing: no top-level camera to inherit");
      else v.accept("camera");
      view.camera.width = width, view.camera.height = height;
      if (v.has("lights")) parse_lights(v, view);
      else v.accept("lights");
      c.views.push_back(view);
    }
    if (c.views.empty()) root.fail("views", "an empty list (leave the key out instead)");
  } else {
    root.accept("views");
    if (!have_camera) root.fail("camera", "missing required key 'camera'");
    c.views.assign(1, base);
  }
  bool any_light = false;
  for (const auto& v : c.views) {
    const bool lit = !v.point_lights.empty() || !v.distant_lights.empty() || !v.area_lights.empty() || v.environment.radiance > 0;
    if (!lit) root.fail(root.has("views") ? "views" : "lights", "view '" + v.name + "' has no light");
    any_light = any_light || lit;
  }
  (void)any_light;
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
  std::string msg = config.file.string() + ": no view '" + name + "'";
  if (auto near = nearest_name(name, names)) msg += " (did you mean '" + *near + "'?)";
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
  throw Error(msg + "; views: " + (all.empty() ? "(none)" : all));
}

}  // namespace plumage
