// From a parsed scene file to renderable meshes and a Scene (scene_config.hpp).
#include <string>

#include "plumage/error.hpp"
#include "plumage/scene_config.hpp"
#include "vec3d.hpp"

namespace plumage {

using namespace scene_detail;

namespace {

SceneMesh plane_mesh(const SceneObjectSpec& o) {
  const V3 n = normalized(from_f(o.normal));
  const V3 helper = std::abs(n.z) < 0.9 ? V3{0, 0, 1} : V3{1, 0, 0};
  const V3 u = normalized(cross(helper, n)), v = cross(n, u);
  const V3 c = from_f(o.center_mm);
  const double h = 0.5 * o.size_mm;
  SceneMesh m;
  m.name = o.name;
  m.material = o.material;
  for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) m.positions.push_back(to_f(c + (a * h) * u + (b * h) * v));
  m.triangles = {{0, 1, 2}, {0, 2, 3}};  // counter-clockwise about n (u × v = n)
  return m;
}

}  // namespace

std::vector<SceneMesh> build_scene_meshes(const SceneConfig& config, SceneGeometryStats* stats) {
  std::vector<SceneMesh> meshes;
  SceneGeometryStats st;
  for (std::size_t k = 0; k < config.objects.size(); ++k) {
    const SceneObjectSpec& o = config.objects[k];
    const std::uint64_t seed = object_item_seed(o.seed, o.name, k);
    try {
      if (o.kind == SceneObjectSpec::Kind::plane) {
        meshes.push_back(plane_mesh(o));
      } else if (o.kind == SceneObjectSpec::Kind::feather) {
        FeatherGeometry g = build_feather(o.shape, o.detail, seed, o.placement, config.max_triangles);
        g.shaft.name = o.name + " shaft", g.vane.name = o.name + " vane";
        g.shaft.material = o.shaft_material, g.vane.material = o.material;
        st.feathers += 1, st.barbs += g.barb_count, st.barbule_ids += g.barbule_count;
        meshes.push_back(std::move(g.shaft));
        meshes.push_back(std::move(g.vane));
      } else {
        AssemblyGeometry g = build_feather_assembly(o.assembly, seed, config.max_triangles);
        g.shaft.name = o.name + " shafts", g.vane.name = o.name + " vanes";
        g.shaft.material = o.shaft_material, g.vane.material = o.material;
        st.feathers += g.feather_count, st.barbs += g.barb_count, st.barbule_ids += g.barbule_count;
        meshes.push_back(std::move(g.shaft));
        meshes.push_back(std::move(g.vane));
      }
    } catch (const ConfigError&) {
      throw;
    } catch (const Error& e) {
      throw Error(config.file.string() + ": object '" + o.name + "': " + e.what());
    }
  }
  for (const auto& m : meshes) st.triangles += m.triangles.size();
  if (st.triangles > config.max_triangles) {
    throw Error(config.file.string() + ": the scene has " + std::to_string(st.triangles) + " triangles, more than render.max_triangles = " +
                std::to_string(config.max_triangles));
  }
  if (stats) *stats = st;
  return meshes;
}

Scene make_scene(const SceneConfig& config, const SceneView& view, std::vector<SceneMesh> meshes) {
  Scene s;
  s.name = view.name.empty() ? config.name : config.name + "-" + view.name;
  s.materials = config.materials;
  for (const auto& m : s.materials) {
    if (m.kind == SceneMaterial::Kind::feather && !m.feather)
      throw Error(config.file.string() + ": feather material '" + m.name + "' was not resolved to a FeatherBsdf");
  }
  s.meshes = std::move(meshes);
  s.point_lights = view.point_lights;
  s.distant_lights = view.distant_lights;
  s.area_lights = view.area_lights;
  s.environment = view.environment;
  s.camera = view.camera;
  return s;
}

}  // namespace plumage
