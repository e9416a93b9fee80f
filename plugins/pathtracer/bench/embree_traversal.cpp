#include "embree_traversal.hpp"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>

#include "plumage/random.hpp"

namespace plumage::pathtracer {

namespace {

// The meshes' triangles only (no area-light quads, no per-triangle data): robust, high quality,
// as the path tracer's own Embree scene.
RTCScene triangle_scene(RTCDevice device, const Scene& s) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  for (const SceneMesh& m : s.meshes) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), m.positions.size()));
    auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), m.triangles.size()));
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      v[3 * i] = m.positions[i].x;
      v[3 * i + 1] = m.positions[i].y;
      v[3 * i + 2] = m.positions[i].z;
    }
    for (std::size_t i = 0; i < m.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) ix[3 * i + k] = m.triangles[i][k];
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene);
  return scene;
}

void normalise(double* a) {
  const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  for (int k = 0; k < 3; ++k) a[k] /= l;
}

// The scene's pinhole camera with jitter k of a pixel drawn from RandomStream(pixel·64 + k).
class JitteredCamera {
 public:
  explicit JitteredCamera(const Camera& c) : c_(c) {
    origin_[0] = float(c.position_mm.x), origin_[1] = float(c.position_mm.y), origin_[2] = float(c.position_mm.z);
    const double px = c.position_mm.x, py = c.position_mm.y, pz = c.position_mm.z;
    f_[0] = c.look_at_mm.x - px, f_[1] = c.look_at_mm.y - py, f_[2] = c.look_at_mm.z - pz;
    normalise(f_);
    r_[0] = f_[1] * c.up.z - f_[2] * c.up.y, r_[1] = f_[2] * c.up.x - f_[0] * c.up.z;
    r_[2] = f_[0] * c.up.y - f_[1] * c.up.x;
    normalise(r_);
    u_[0] = r_[1] * f_[2] - r_[2] * f_[1], u_[1] = r_[2] * f_[0] - r_[0] * f_[2], u_[2] = r_[0] * f_[1] - r_[1] * f_[0];
    th_ = std::tan(0.5 * c.vertical_fov_rad), aspect_ = double(c.width) / c.height;
  }
  const float* origin() const { return origin_; }
  void direction(std::uint64_t pixel, int k, float* d) const {
    RandomStream rs(pixel * 64 + static_cast<std::uint64_t>(k));
    const double x = (pixel % c_.width) + rs.uniform(), y = (pixel / c_.width) + rs.uniform();
    const double sx = (2.0 * x / c_.width - 1.0) * th_ * aspect_, sy = (1.0 - 2.0 * y / c_.height) * th_;
    double dd[3] = {f_[0] + sx * r_[0] + sy * u_[0], f_[1] + sx * r_[1] + sy * u_[1], f_[2] + sx * r_[2] + sy * u_[2]};
    normalise(dd);
    for (int q = 0; q < 3; ++q) d[q] = static_cast<float>(dd[q]);
  }

 private:
  const Camera& c_;
  float origin_[3];
  double f_[3], r_[3], u_[3], th_, aspect_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// rtcIntersect1 over every (pixel, jitter); returns the number of hits.
std::uint64_t single_rays(RTCScene scene, const JitteredCamera& cam, std::uint64_t pixels, int rays_per_pixel) {
  const float* o = cam.origin();
  std::atomic<std::uint64_t> hits{0};
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, pixels, 4096), [&](const tbb::blocked_range<std::uint64_t>& br) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    std::uint64_t h = 0;
    for (std::uint64_t p = br.begin(); p != br.end(); ++p) {
      for (int k = 0; k < rays_per_pixel; ++k) {
        RTCRayHit rh{};
        float d[3];
        cam.direction(p, k, d);
        rh.ray.org_x = o[0]; rh.ray.org_y = o[1]; rh.ray.org_z = o[2];
        rh.ray.dir_x = d[0]; rh.ray.dir_y = d[1]; rh.ray.dir_z = d[2];
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = 1e30f;
        rh.ray.mask = 0xffffffffu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        h += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
    }
    hits += h;
  });
  return hits.load();
}

// rtcIntersect16: 16 consecutive rays (4 pixels × 4 jitters) per packet.
void packet_rays(RTCScene scene, const JitteredCamera& cam, std::uint64_t total, int rays_per_pixel) {
  const float* o = cam.origin();
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, (total + 15) / 16, 256), [&](const tbb::blocked_range<std::uint64_t>& br) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    for (std::uint64_t b = br.begin(); b != br.end(); ++b) {
      for (int l = 0; l < 16; ++l) {
        const std::uint64_t ray = b * 16 + static_cast<std::uint64_t>(l);
        valid[l] = ray < total ? -1 : 0;
        float d[3] = {0, 0, 1};
        if (ray < total) cam.direction(ray / rays_per_pixel, static_cast<int>(ray % rays_per_pixel), d);
        rh.ray.org_x[l] = o[0]; rh.ray.org_y[l] = o[1]; rh.ray.org_z[l] = o[2];
        rh.ray.dir_x[l] = d[0]; rh.ray.dir_y[l] = d[1]; rh.ray.dir_z[l] = d[2];
        rh.ray.tnear[l] = 0.0f;
        rh.ray.tfar[l] = 1e30f;
        rh.ray.mask[l] = 0xffffffffu;
        rh.ray.time[l] = 0.0f;
        rh.ray.flags[l] = 0;
        rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, scene, &ctx, &rh);
    }
  });
}

}  // namespace

TraversalRate embree_traversal_rate(const Scene& s, int rays_per_pixel) {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = triangle_scene(device, s);
  const JitteredCamera cam(s.camera);
  const std::uint64_t pixels = static_cast<std::uint64_t>(s.camera.width) * s.camera.height;
  TraversalRate t;
  t.rays = pixels * rays_per_pixel;
  auto t0 = std::chrono::steady_clock::now();
  t.hits = single_rays(scene, cam, pixels, rays_per_pixel);
  t.rays_per_s_1 = double(t.rays) / seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  packet_rays(scene, cam, t.rays, rays_per_pixel);
  t.rays_per_s_16 = double(t.rays) / seconds_since(t0);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return t;
}

}  // namespace plumage::pathtracer
