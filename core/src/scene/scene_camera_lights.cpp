// A scene's camera and lights (scene_sections.hpp): one parameter table each.
#include "scene_sections.hpp"
#include "vec3d.hpp"

namespace plumage::scene_detail {

Vec3f read_vec3(const ParamView& node, std::string_view key, Limits limits) {
  const std::vector<double> v = node.numbers(key, limits);
  if (v.size() != 3) node.fail(key, "expected 3 numbers [x, y, z], got " + std::to_string(v.size()));
  return to_f({v[0], v[1], v[2]});
}
Vec3f read_vec3_or(const ParamView& node, std::string_view key, Vec3f fallback, Limits limits) {
  return node.has(key) ? read_vec3(node, key, limits) : (node.accept(key), fallback);
}
Vec3f read_unit3(const ParamView& node, std::string_view key) {
  const V3 v = from_f(read_vec3(node, key));
  if (!(norm(v) > 0)) node.fail(key, "must not be the zero vector");
  return to_f(normalized(v));
}

namespace {

// ---- camera ----------------------------------------------------------------------------------

struct CameraKeys {
  const Camera* base = nullptr;  // a view's camera inherits every key it leaves out
  Vec3f position_mm, look_at_mm, up = {0, 0, 1};
  double fov_deg = 30.0;
};

// A point the camera needs: required without a base camera, else inherited.
template <Vec3f CameraKeys::*Field, Vec3f Camera::*Inherited>
void read_point(const ParamView& p, CameraKeys& k, std::string_view key) {
  k.*Field = k.base ? read_vec3_or(p, key, k.base->*Inherited) : read_vec3(p, key);
}

const ParamTable<CameraKeys>& camera_table() {
  static const auto table =
      ParamTable<CameraKeys>{}
          .custom("position_mm", "vector", "mm", "required", "pinhole position [x, y, z] (a view: the scene's camera's)",
                  [](const ParamView& p, CameraKeys& k) {
                    read_point<&CameraKeys::position_mm, &Camera::position_mm>(p, k, "position_mm");
                  })
          .custom("look_at_mm", "vector", "mm", "required", "point at the image centre (a view: the scene's camera's)",
                  [](const ParamView& p, CameraKeys& k) {
                    read_point<&CameraKeys::look_at_mm, &Camera::look_at_mm>(p, k, "look_at_mm");
                  })
          .custom("up", "vector", "1", "[0, 0, 1]", "up direction of the image (normalised; not along the view)",
                  [](const ParamView& p, CameraKeys& k) {
                    if (p.has("up")) k.up = read_unit3(p, "up");
                  })
          .number("fov_deg", &CameraKeys::fov_deg, "deg", 30.0, Limits{0.0, 179.0, true, true},
                  "vertical field of view");
  return table;
}

// ---- lights ----------------------------------------------------------------------------------

enum class LightType { distant, point, area, environment };

struct LightKeys {
  LightType type = LightType::distant;
  Vec3f toward_light, position_mm, corner_mm, edge_u_mm, edge_v_mm;
  double irradiance = 1.0, intensity = 1.0, area_radiance = 1.0, environment_radiance = 0.05;
  bool two_sided = false;
};

template <LightType T>
bool is(const LightKeys& k) {
  return k.type == T;
}

template <Vec3f LightKeys::*Field>
ParamTable<LightKeys>::Reader vector_reader(std::string key, bool unit) {
  return [key, unit](const ParamView& p, LightKeys& k) { k.*Field = unit ? read_unit3(p, key) : read_vec3(p, key); };
}

const ParamTable<LightKeys>& light_table() {
  using T = LightType;
  static const auto table =
      ParamTable<LightKeys>{}
          .choice("type", &LightKeys::type,
                  std::vector<std::pair<std::string_view, T>>{
                      {"distant", T::distant}, {"point", T::point}, {"area", T::area}, {"environment", T::environment}},
                  required, "kind of light; every emission has the shape of D65 times its scale")
          .custom("toward_light", "vector", "1", "required", "direction to the light, world frame (normalised)",
                  vector_reader<&LightKeys::toward_light>("toward_light", true))
          .only_if(is<T::distant>, "type: distant")
          .number("irradiance", &LightKeys::irradiance, "1", 1.0, Limits::non_negative(),
                  "irradiance on a surface facing the light (x D65)")
          .only_if(is<T::distant>, "type: distant")
          .custom("position_mm", "vector", "mm", "required", "position of the point light",
                  vector_reader<&LightKeys::position_mm>("position_mm", false))
          .only_if(is<T::point>, "type: point")
          .number("intensity", &LightKeys::intensity, "1", 1.0, Limits::non_negative(),
                  "radiant intensity per steradian (x D65)")
          .only_if(is<T::point>, "type: point")
          .custom("corner_mm", "vector", "mm", "required", "corner of the emitting parallelogram",
                  vector_reader<&LightKeys::corner_mm>("corner_mm", false))
          .only_if(is<T::area>, "type: area")
          .custom("edge_u_mm", "vector", "mm", "required", "first edge from the corner",
                  vector_reader<&LightKeys::edge_u_mm>("edge_u_mm", false))
          .only_if(is<T::area>, "type: area")
          .custom("edge_v_mm", "vector", "mm", "required", "second edge; it emits on the side of edge_u x edge_v",
                  vector_reader<&LightKeys::edge_v_mm>("edge_v_mm", false))
          .only_if(is<T::area>, "type: area")
          .number("radiance", &LightKeys::area_radiance, "1", 1.0, Limits::non_negative(), "radiance (x D65)")
          .only_if(is<T::area>, "type: area")
          .boolean("two_sided", &LightKeys::two_sided, false, "emit on both sides")
          .only_if(is<T::area>, "type: area")
          .number("radiance", &LightKeys::environment_radiance, "1", 0.05, Limits::non_negative(),
                  "constant radiance from every direction (x D65); one environment per view")
          .only_if(is<T::environment>, "type: environment");
  return table;
}

}  // namespace

Camera read_camera(const ParamView& c, const Camera* base) {
  CameraKeys k;
  k.base = base;
  if (base) k.up = base->up, k.fov_deg = base->vertical_fov_rad * 180.0 / kPiD;
  camera_table().read_into(c, k);
  Camera cam = base ? *base : Camera{};
  cam.position_mm = k.position_mm;
  cam.look_at_mm = k.look_at_mm;
  cam.up = k.up;
  cam.vertical_fov_rad = rad(k.fov_deg);
  const V3 forward = from_f(cam.look_at_mm) - from_f(cam.position_mm);
  if (!(norm(forward) > 0)) c.fail("look_at_mm", "equals position_mm (no viewing direction)");
  if (norm(cross(normalized(forward), from_f(cam.up))) < 1e-6) c.fail("up", "is parallel to the viewing direction");
  return cam;
}

void read_lights(const ParamView& parent, SceneView& view) {
  view.point_lights.clear(), view.distant_lights.clear(), view.area_lights.clear();
  view.environment = {};
  for (const ParamView& l : parent.items("lights")) {
    const LightKeys k = light_table().read(l);
    switch (k.type) {
      case LightType::distant:
        view.distant_lights.push_back({k.toward_light, k.irradiance});
        break;
      case LightType::point:
        view.point_lights.push_back({k.position_mm, k.intensity});
        break;
      case LightType::area:
        if (!(norm(cross(from_f(k.edge_u_mm), from_f(k.edge_v_mm))) > 0)) l.fail("edge_v_mm", "the edges span no area");
        view.area_lights.push_back({k.corner_mm, k.edge_u_mm, k.edge_v_mm, k.area_radiance, k.two_sided});
        break;
      case LightType::environment:
        if (view.environment.radiance > 0) l.fail("type", "only one environment light per scene");
        view.environment.radiance = k.environment_radiance;
        break;
    }
  }
}

std::vector<ParamSpec> camera_specs() { return camera_table().specs(); }
std::vector<ParamSpec> light_specs() { return light_table().specs(); }

}  // namespace plumage::scene_detail
