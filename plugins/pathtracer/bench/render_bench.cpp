// Benchmark "render" (`plumage bench render`, issue 8; a benchmark of the plug-in since issue 22):
// the path tracer on a single procedural feather (feather_geometry.hpp, explicit barbules) at
// 1024², 64 spp by default: wall and process CPU time, rays/s, the mean-LOD share, and Embree's
// raw traversal rate on the same geometry and the same camera (embree_traversal.hpp).
#include "render_bench.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "embree_traversal.hpp"
#include "pathtracer.hpp"
#include "plumage/accuracy_ladder.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/error.hpp"
#include "plumage/exr.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/feather_geometry.hpp"

namespace plumage::pathtracer {

namespace {

struct Geometry {
  std::size_t triangles = 0, barbules = 0;
};

// One feather (default FeatherShape, explicit barbules, seed 1) lit by a distant light and a dim
// sky, seen from above (the whole vane in view).
Scene feather_scene(const RenderBenchParams& b, Geometry& geometry) {
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
  vane.feather = std::make_shared<FeatherBsdf>(std::make_shared<FeatherMaterial>(read_feather_material(b.material)));
  s.materials = {shaft, vane};
  g.shaft.material = 0;
  g.vane.material = 1;
  geometry.triangles = g.shaft.triangles.size() + g.vane.triangles.size();
  geometry.barbules = g.barbule_count;
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

std::string lod_word(LevelOfDetail lod) {
  return lod == LevelOfDetail::mean ? "mean" : lod == LevelOfDetail::instance ? "instance" : "auto";
}

std::string report_markdown(const RenderBenchParams& b, const Geometry& g, const RenderStats& r, double cpu_s,
                            const TraversalRate& t, const std::string& command) {
  const double rays_per_s = double(r.rays) / r.seconds;
  std::ostringstream md;
  md << std::setprecision(4);
  md << "## render\n\n"
     << "The `pathtracer` Renderer (plugins/pathtracer, issue 8) on one procedural feather "
        "(feather_geometry.hpp, default FeatherShape, explicit barbules, seed 1: "
     << g.triangles << " triangles, " << g.barbules << " barbules; vane = `" << b.material
     << "`, shaft diffuse 0.12), distant light + dim sky, camera above the whole vane; " << b.size << "², " << b.spp
     << " spp, max depth 8, "
     << (b.lod == LevelOfDetail::automatic ? std::string("automatic") : lod_word(b.lod) + "-forced")
     << " LOD. Rays = camera + bounce + shadow rays. Embree's raw rate: the same "
        "triangles, the same pinhole camera, "
     << b.traversal_rays
     << " jittered rays per pixel, closest hit only (no shading), oneTBB over all cores. CPU = process CPU time of "
        "the render. Goal (issue 8): <= 120 s on 2 cores.\n\n"
     << "| machine | command | date | wall s | CPU s | rays | rays/s | Embree rtcIntersect1 rays/s | rtcIntersect16 rays/s | mean-LOD share | goal |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n"
     << "| " << machine_description() << " | `" << command << "` | " << today_iso() << " | " << r.seconds << " | "
     << cpu_s << " | " << r.rays << " | " << rays_per_s << " | " << t.rays_per_s_1 << " | " << t.rays_per_s_16
     << " | " << r.mean_lod_fraction << " | <= 120 s |\n";
  return md.str();
}

}  // namespace

const ParamTable<RenderBenchParams>& render_bench_table() {
  using L = LevelOfDetail;
  static const auto table =
      ParamTable<RenderBenchParams>{}
          .integer("size", &RenderBenchParams::size, "px", 1024, Limits::closed(1, 16384), "image width = height")
          .integer("spp", &RenderBenchParams::spp, "1", 64, Limits::closed(1, 1 << 20), "samples per pixel")
          .text("material", &RenderBenchParams::material, "build/materials/mallard-green.plm",
                "feather material (.plm) of the vane")
          .integer("traversal_rays", &RenderBenchParams::traversal_rays, "1", 4, Limits::closed(1, 1024),
                   "rays per pixel of the raw Embree measurement")
          .choice("lod", &RenderBenchParams::lod, {{"auto", L::automatic}, {"mean", L::mean}, {"instance", L::instance}},
                  L::automatic, "level of detail of the render (the renderer's `lod`)")
          .text("out", &RenderBenchParams::out, "", "also write <out>.exr and <out>.png of the render");
  return table;
}

std::unique_ptr<RenderBenchmark> make_render_benchmark(const ParamView& params) {
  RenderBenchParams b = render_bench_table().read(params);
  if (!std::filesystem::exists(b.material)) {
    params.fail("material", "no feather material " + b.material + " (characterise one first, or pass --material <file.plm>)");
  }
  return std::make_unique<RenderBenchmark>(std::move(b));
}

Benchmark::Report RenderBenchmark::run(const Options& options) const {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const RenderBenchParams& b = params_;
  Geometry geometry;
  Scene scene;
  std::ostringstream line;
  const RungCost build = measure_rung([&] { scene = feather_scene(b, geometry); });
  line << "scene: " << geometry.triangles << " triangles, " << geometry.barbules
       << " barbules, built (with the FeatherBsdf) in " << build.wall_s << " s";
  say(line.str());
  const TraversalRate t = embree_traversal_rate(scene, b.traversal_rays);
  line.str("");
  line << "Embree raw traversal: " << t.rays_per_s_1 / 1e6 << " Mrays/s (rtcIntersect1), " << t.rays_per_s_16 / 1e6
       << " Mrays/s (rtcIntersect16), " << double(t.hits) / double(t.rays) << " of the camera rays hit";
  say(line.str());

  Settings settings;
  settings.samples_per_pixel = b.spp;
  settings.lod = b.lod;
  const PathTracer tracer(settings);
  RenderResult r;
  const RungCost cost = measure_rung([&] { r = tracer.render(scene, {}); });
  line.str("");
  line << std::setprecision(4) << "render " << b.size << "x" << b.size << " " << b.spp << " spp: " << r.stats.seconds
       << " s wall, " << cost.cpu_s << " s CPU, " << r.stats.rays << " rays ("
       << double(r.stats.rays) / r.stats.seconds / 1e6 << " Mrays/s), mean-LOD share " << r.stats.mean_lod_fraction;
  say(line.str());
  if (!b.out.empty()) {
    write_exr(r.rgb, b.out + ".exr");
    write_png(to_display(r.rgb), b.out + ".png");
    say("wrote " + b.out + ".exr and " + b.out + ".png");
  }
  return {"render", report_markdown(b, geometry, r.stats, cost.cpu_s, t, options.command)};
}

}  // namespace plumage::pathtracer
