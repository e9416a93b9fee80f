#include "embree_scene.hpp"

#include <string>

#include "plumage/error.hpp"

namespace plumage::pathtracer {

namespace {

void check_device(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw Error(std::string("pathtracer: Embree error ") + std::to_string(int(e)) + " in " + what);
}

void add_triangles(RTCDevice device, RTCScene scene, unsigned id, const float* xyz, std::size_t nverts,
                   const std::uint32_t* tri, std::size_t ntri) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nverts));
  auto* ix = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), ntri));
  if (v == nullptr || ix == nullptr) throw Error("pathtracer: Embree could not allocate geometry buffers");
  for (std::size_t i = 0; i < 3 * nverts; ++i) v[i] = xyz[i];
  for (std::size_t i = 0; i < 3 * ntri; ++i) ix[i] = tri[i];
  rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(scene, g, id);
  rtcReleaseGeometry(g);
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene) {
  device_ = rtcNewDevice(nullptr);
  if (device_ == nullptr) throw Error("pathtracer: cannot create an Embree device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  meshes_ = static_cast<unsigned>(scene.meshes.size());
  for (unsigned m = 0; m < meshes_; ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (std::uint32_t i : mesh.triangles[t]) {
        if (i >= mesh.positions.size()) {
          throw Error("pathtracer: mesh '" + mesh.name + "' triangle " + std::to_string(t) + " refers to vertex " +
                      std::to_string(i) + " of " + std::to_string(mesh.positions.size()));
        }
      }
    }
    for (const Vec3f& p : mesh.positions) extent_ = std::max(extent_, max_abs(to_v3(p)));
    if (mesh.triangles.empty()) continue;  // an empty geometry ID stays unused
    add_triangles(device_, scene_, m, &mesh.positions[0].x, mesh.positions.size(), mesh.triangles[0].data(),
                  mesh.triangles.size());
  }
  for (std::size_t l = 0; l < scene.area_lights.size(); ++l) {
    const AreaLight& a = scene.area_lights[l];
    const V3 c = to_v3(a.corner_mm), u = to_v3(a.edge_u_mm), v = to_v3(a.edge_v_mm);
    const V3 p[4] = {c, c + u, c + u + v, c + v};
    float xyz[12];
    for (int i = 0; i < 4; ++i) {
      xyz[3 * i] = static_cast<float>(p[i].x);
      xyz[3 * i + 1] = static_cast<float>(p[i].y);
      xyz[3 * i + 2] = static_cast<float>(p[i].z);
      extent_ = std::max(extent_, max_abs(p[i]));
    }
    const std::uint32_t tri[6] = {0, 1, 2, 0, 2, 3};  // winding normal u × v
    add_triangles(device_, scene_, meshes_ + static_cast<unsigned>(l), xyz, 4, tri, 2);
  }
  rtcCommitScene(scene_);
  check_device(device_, "scene build");
}

EmbreeScene::~EmbreeScene() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

Hit EmbreeScene::intersect(V3 o, V3 d, double tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(d.x);
  rh.ray.dir_y = static_cast<float>(d.y);
  rh.ray.dir_z = static_cast<float>(d.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = static_cast<float>(std::min(tmax, 3.0e38));
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.found = true;
  h.t = rh.ray.tfar;
  h.geom = rh.hit.geomID;
  h.prim = rh.hit.primID;
  h.u = rh.hit.u;
  h.v = rh.hit.v;
  h.ng = normalize(V3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
  return h;
}

bool EmbreeScene::occluded(V3 o, V3 d, double tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r{};
  r.org_x = static_cast<float>(o.x);
  r.org_y = static_cast<float>(o.y);
  r.org_z = static_cast<float>(o.z);
  r.dir_x = static_cast<float>(d.x);
  r.dir_y = static_cast<float>(d.y);
  r.dir_z = static_cast<float>(d.z);
  r.tnear = 0.0f;
  r.tfar = static_cast<float>(std::min(tmax, 3.0e38));
  r.mask = 0xffffffffu;
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar = −inf on a hit
}

}  // namespace plumage::pathtracer
