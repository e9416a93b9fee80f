// `plumage bench render` (issue 8): the "pathtracer" Renderer on a single procedural feather
// (feather_geometry.hpp, explicit barbules) at 1024², 64 spp by default: wall and process CPU time,
// rays/s, the mean-LOD share, and Embree's raw traversal rate on the same geometry and the same
// camera (rtcIntersect1 and rtcIntersect16 over oneTBB, no shading). Reaches the renderer only
// through the registry.
#include <embree3/rtcore.h>
#include <sys/resource.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "commands.hpp"
#include "plumage/error.hpp"
#include "plumage/exr.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/feather_geometry.hpp"
#include "plumage/random.hpp"
#include "plumage/renderer.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct RenderBench {
  int size = 1024;
  int spp = 64;
  std::string material = "build/materials/mallard-green.plm";
  int traversal_rays_per_pixel = 4;
  std::string lod = "auto";  // auto | mean | instance (RenderSettings::lod)
  std::string out;  // optional EXR + PNG of the render
  std::string record;
};

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// One feather (default FeatherShape, explicit barbules) lit by a distant light and a dim sky, seen
// from above (the whole vane in view).
Scene feather_scene(const RenderBench& b, std::size_t* triangles, std::size_t* barbules) {
  Scene s;
  s.name = "bench single feather";
  const FeatherShape shape;
  FeatherGeometry g = build_feather(shape, FeatherDetail::barbules, 1);
  SceneMaterial shaft;
  shaft.name = "shaft";
  shaft.kind = SceneMaterial::Kind::diffuse;
  shaft.albedo.value = {0.12};
  SceneMaterial vane;
  vane.name = "vane";
  vane.kind = SceneMaterial::Kind::feather;
  if (!std::filesystem::exists(b.material)) {
    throw UsageError("bench render: feather material " + b.material +
                     " not found (characterise one first, or pass --material <file.plm>)");
  }
  vane.feather = std::make_shared<FeatherBsdf>(std::make_shared<FeatherMaterial>(read_feather_material(b.material)));
  s.materials = {shaft, vane};
  g.shaft.material = 0;
  g.vane.material = 1;
  *triangles = g.shaft.triangles.size() + g.vane.triangles.size();
  *barbules = g.barbule_count;
  s.meshes = {std::move(g.shaft), std::move(g.vane)};
  s.distant_lights.push_back({{0.35f, -0.3f, 0.89f}, 3.0});
  s.environment.radiance = 0.05;
  const double mid = 0.5 * shape.length_mm, reach = 0.5 * (shape.length_mm + shape.calamus_mm) + 1.0;
  s.camera.position_mm = {0.0f, static_cast<float>(mid), 80.0f};
  s.camera.look_at_mm = {0.0f, static_cast<float>(mid), 0.0f};
  s.camera.up = {0.0f, 1.0f, 0.0f};
  s.camera.vertical_fov_rad = 2.0 * std::atan(reach / 80.0);
  s.camera.width = s.camera.height = b.size;
  return s;
}

// Embree's own rate on the same triangles and the same pinhole camera (jittered rays, no shading).
struct Traversal {
  double rays_per_s_1 = 0, rays_per_s_16 = 0;
  std::uint64_t rays = 0, hits = 0;
};

Traversal raw_traversal(const Scene& s, int rays_per_pixel) {
  RTCDevice device = rtcNewDevice(nullptr);
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

  const Camera& c = s.camera;
  const double px = c.position_mm.x, py = c.position_mm.y, pz = c.position_mm.z;
  double f[3] = {c.look_at_mm.x - px, c.look_at_mm.y - py, c.look_at_mm.z - pz};
  auto norm = [](double* a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k) a[k] /= l;
  };
  norm(f);
  double r[3] = {f[1] * c.up.z - f[2] * c.up.y, f[2] * c.up.x - f[0] * c.up.z, f[0] * c.up.y - f[1] * c.up.x};
  norm(r);
  const double u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
  const double th = std::tan(0.5 * c.vertical_fov_rad), aspect = double(c.width) / c.height;
  auto ray_dir = [&](std::uint64_t pixel, int k, float* d) {
    RandomStream rs(pixel * 64 + static_cast<std::uint64_t>(k));
    const double x = (pixel % c.width) + rs.uniform(), y = (pixel / c.width) + rs.uniform();
    const double sx = (2.0 * x / c.width - 1.0) * th * aspect, sy = (1.0 - 2.0 * y / c.height) * th;
    double dd[3] = {f[0] + sx * r[0] + sy * u[0], f[1] + sx * r[1] + sy * u[1], f[2] + sx * r[2] + sy * u[2]};
    norm(dd);
    for (int q = 0; q < 3; ++q) d[q] = static_cast<float>(dd[q]);
  };
  const std::uint64_t pixels = static_cast<std::uint64_t>(c.width) * c.height;
  Traversal t;
  t.rays = pixels * rays_per_pixel;
  std::atomic<std::uint64_t> hits{0};
  // rtcIntersect1
  auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, pixels, 4096), [&](const tbb::blocked_range<std::uint64_t>& br) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    std::uint64_t h = 0;
    for (std::uint64_t p = br.begin(); p != br.end(); ++p) {
      for (int k = 0; k < rays_per_pixel; ++k) {
        RTCRayHit rh{};
        float d[3];
        ray_dir(p, k, d);
        rh.ray.org_x = float(px); rh.ray.org_y = float(py); rh.ray.org_z = float(pz);
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
  t.rays_per_s_1 = double(t.rays) / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t.hits = hits.load();
  // rtcIntersect16: 16 consecutive rays (4 pixels × 4 jitters) per packet.
  t0 = std::chrono::steady_clock::now();
  const std::uint64_t total = t.rays;
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
        if (ray < total) ray_dir(ray / rays_per_pixel, static_cast<int>(ray % rays_per_pixel), d);
        rh.ray.org_x[l] = float(px); rh.ray.org_y[l] = float(py); rh.ray.org_z[l] = float(pz);
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
  t.rays_per_s_16 = double(t.rays) / std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return t;
}

void bench_render(AppContext& context, const RenderBench& b) {
  if (b.size < 1 || b.spp < 1) throw UsageError("bench render: --size and --spp must be positive");
  std::size_t triangles = 0, barbules = 0;
  const auto tb = std::chrono::steady_clock::now();
  const Scene scene = feather_scene(b, &triangles, &barbules);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tb).count();
  std::cerr << "scene: " << triangles << " triangles, " << barbules << " barbules, built (with the FeatherBsdf) in "
            << build_s << " s\n";
  const Traversal t = raw_traversal(scene, b.traversal_rays_per_pixel);
  std::cerr << "Embree raw traversal: " << t.rays_per_s_1 / 1e6 << " Mrays/s (rtcIntersect1), "
            << t.rays_per_s_16 / 1e6 << " Mrays/s (rtcIntersect16), " << double(t.hits) / double(t.rays)
            << " of the camera rays hit\n";

  auto renderer = context.registry().create_named<Renderer>("pathtracer", ParamView{}, context.registry().context());
  RenderSettings settings;
  settings.samples_per_pixel = b.spp;
  if (b.lod == "mean") {
    settings.lod = LevelOfDetail::mean;
  } else if (b.lod == "instance") {
    settings.lod = LevelOfDetail::instance;
  } else if (b.lod != "auto") {
    throw UsageError("bench render: --lod must be auto, mean or instance (got '" + b.lod + "')");
  }
  std::unique_ptr<Progress> progress;
  const double cpu0 = cpu_seconds();
  const RenderResult r = renderer->render(scene, settings, [&](std::size_t done, std::size_t total, std::string_view what) {
    if (!progress) progress = std::make_unique<Progress>(std::string(what), total, context.quiet);
    progress->advance(done);
  });
  const double cpu = cpu_seconds() - cpu0;
  const double rays_per_s = double(r.stats.rays) / r.stats.seconds;
  std::cout << std::setprecision(4) << "render " << b.size << "x" << b.size << " " << b.spp << " spp: " << r.stats.seconds
            << " s wall, " << cpu << " s CPU, " << r.stats.rays << " rays (" << rays_per_s / 1e6
            << " Mrays/s), mean-LOD share " << r.stats.mean_lod_fraction << "\n";
  if (!b.out.empty()) {
    write_exr(r.rgb, b.out + ".exr");
    write_png(to_display(r.rgb), b.out + ".png");
    std::cout << "wrote " << b.out << ".exr and " << b.out << ".png\n";
  }

  std::ostringstream md;
  md << std::setprecision(4);
  md << "## render\n\n"
     << "The `pathtracer` Renderer (plugins/pathtracer, issue 8) on one procedural feather "
        "(feather_geometry.hpp, default FeatherShape, explicit barbules, seed 1: "
     << triangles << " triangles, " << barbules << " barbules; vane = `" << b.material
     << "`, shaft diffuse 0.12), distant light + dim sky, camera above the whole vane; " << b.size << "², " << b.spp
     << " spp, max depth 8, "
     << (b.lod == "auto" ? std::string("automatic") : b.lod + "-forced") << " LOD. Rays = camera + bounce + shadow rays. Embree's raw rate: the same "
        "triangles, the same pinhole camera, "
     << b.traversal_rays_per_pixel
     << " jittered rays per pixel, closest hit only (no shading), oneTBB over all cores. CPU = process CPU time of "
        "the render. Goal (issue 8): <= 120 s on 2 cores.\n\n"
     << "| machine | command | date | wall s | CPU s | rays | rays/s | Embree rtcIntersect1 rays/s | rtcIntersect16 rays/s | mean-LOD share | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n"
     << "| " << machine_description() << " | `plumage bench render --size " << b.size << " --spp " << b.spp
     << (b.lod == "auto" ? std::string() : " --lod " + b.lod) << "` | "
     << today_iso() << " | " << r.stats.seconds << " | " << cpu << " | " << r.stats.rays << " | " << rays_per_s << " | "
     << t.rays_per_s_1 << " | " << t.rays_per_s_16 << " | " << r.stats.mean_lod_fraction << " | <= 120 s |\n";
  if (!b.record.empty()) {
    record_benchmark(b.record, "render", md.str());
    std::cerr << "recorded in " << b.record << "\n";
  }
}

}  // namespace

void add_bench_render_command(CLI::App& bench, AppContext& context) {
  auto b = std::make_shared<RenderBench>();
  auto* cmd = bench.add_subcommand("render", "Path tracer on a single feather: time, rays/s vs Embree's raw traversal");
  cmd->add_option("--size", b->size, "Image width = height (pixels)")->capture_default_str();
  cmd->add_option("--spp", b->spp, "Samples per pixel")->capture_default_str();
  cmd->add_option("--material", b->material, "Feather material (.plm) of the vane")->capture_default_str();
  cmd->add_option("--traversal-rays", b->traversal_rays_per_pixel, "Rays per pixel of the raw Embree measurement")
      ->capture_default_str();
  cmd->add_option("--lod", b->lod, "Level of detail: auto, mean or instance")->capture_default_str();
  cmd->add_option("--out", b->out, "Also write <out>.exr and <out>.png");
  cmd->add_option("--record", b->record, "Markdown file to record the result in (e.g. docs/benchmarks.md)");
  cmd->callback([&context, b] { bench_render(context, *b); });
}

}  // namespace plumage::cli
