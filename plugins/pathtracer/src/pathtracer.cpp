#include "pathtracer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <string>

#include "camera.hpp"
#include "embree_scene.hpp"
#include "integrator.hpp"
#include "plumage/error.hpp"
#include "plumage/params.hpp"
#include "spectral_tables.hpp"

namespace plumage::pathtracer {

namespace {

// Embree builds its bounds in single precision and aborts the process (not an error code) on
// non-finite or enormous ones, so every point handed to it is checked first against the scene's
// declared coordinate range (params.hpp, Limits::scene_coordinate_mm): bad input, exit 2, the
// field named. Scene configs are refused there already; this guards scenes built in code.
void check_bounds(const Scene& scene) {
  const Limits limits = Limits::scene_coordinate_mm();
  auto check = [&](const Vec3f& p, const std::string& field) {
    if (limits.admits(p.x) && limits.admits(p.y) && limits.admits(p.z)) return;
    throw ConfigError({"scene '" + scene.name + "'", 0, 0}, field,
                      "point [" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                          "] is not a scene coordinate: each must be finite and " + limits.describe() + " mm");
  };
  check(scene.camera.position_mm, "camera.position_mm");
  check(scene.camera.look_at_mm, "camera.look_at_mm");
  for (const SceneMesh& mesh : scene.meshes) {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      check(mesh.positions[i], "mesh '" + mesh.name + "' vertex " + std::to_string(i));
  }
  for (std::size_t l = 0; l < scene.point_lights.size(); ++l)
    check(scene.point_lights[l].position_mm, "point light " + std::to_string(l) + " position_mm");
  for (std::size_t l = 0; l < scene.area_lights.size(); ++l) {
    const AreaLight& a = scene.area_lights[l];
    const Vec3f far = {a.corner_mm.x + a.edge_u_mm.x + a.edge_v_mm.x, a.corner_mm.y + a.edge_u_mm.y + a.edge_v_mm.y,
                       a.corner_mm.z + a.edge_u_mm.z + a.edge_v_mm.z};
    check(a.corner_mm, "area light " + std::to_string(l) + " corner_mm");
    check(far, "area light " + std::to_string(l) + " corner_mm + edge_u_mm + edge_v_mm");
  }
}

}  // namespace

void validate_scene(const Scene& scene, const Settings& s) {
  auto fail = [&](const std::string& what) { throw Error("pathtracer: scene '" + scene.name + "': " + what); };
  check_bounds(scene);
  if (scene.camera.width <= 0 || scene.camera.height <= 0) fail("camera width/height must be positive");
  if (!(scene.camera.vertical_fov_rad > 0.0 && scene.camera.vertical_fov_rad < kPi)) fail("camera vertical_fov_rad must be in (0, pi)");
  if (s.samples_per_pixel < 1) fail("samples_per_pixel must be >= 1");
  if (s.max_depth < 1) fail("max_depth must be >= 1");
  if (s.tile_size < 1) fail("tile_size must be >= 1");
  if (s.spectral_bins < 0) fail("spectral_bins must be >= 0");
  if (!(s.lambda_max_nm > s.lambda_min_nm)) fail("lambda_max_nm must exceed lambda_min_nm");
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const SceneMaterial& m = scene.materials[i];
    if (m.kind == SceneMaterial::Kind::feather && !m.feather) fail("material '" + m.name + "' is a feather without a FeatherBsdf");
    if (m.kind == SceneMaterial::Kind::dielectric && !(m.ior > 0.0)) fail("material '" + m.name + "': ior must be > 0");
  }
  for (const SceneMesh& mesh : scene.meshes) {
    if (mesh.material >= scene.materials.size()) {
      fail("mesh '" + mesh.name + "': material index " + std::to_string(mesh.material) + " of " +
           std::to_string(scene.materials.size()));
    }
    const std::size_t n = mesh.triangles.size();
    if (scene.materials[mesh.material].kind == SceneMaterial::Kind::feather &&
        (mesh.frame_axis.size() != n || mesh.frame_normal.size() != n)) {
      fail("mesh '" + mesh.name + "': a feather material needs frame_axis and frame_normal per triangle (" +
           std::to_string(mesh.frame_axis.size()) + ", " + std::to_string(mesh.frame_normal.size()) + " for " +
           std::to_string(n) + " triangles)");
    }
    if (!mesh.barbule_id.empty() && mesh.barbule_id.size() != n) {
      fail("mesh '" + mesh.name + "': barbule_id has " + std::to_string(mesh.barbule_id.size()) + " entries for " +
           std::to_string(n) + " triangles");
    }
  }
}

RenderResult PathTracer::render(const Scene& scene, Progress progress) const {
  const Settings& settings = settings_;
  const auto t0 = std::chrono::steady_clock::now();
  validate_scene(scene, settings);
  const SpectralTables tables(settings.lambda_min_nm, settings.lambda_max_nm);
  const EmbreeScene embree(scene);
  const Integrator integrator(scene, settings, embree, tables);
  const PinholeCamera camera(scene.camera);

  const int W = scene.camera.width, H = scene.camera.height, T = settings.tile_size;
  const int tiles_x = (W + T - 1) / T, tiles_y = (H + T - 1) / T;
  const std::size_t tiles = static_cast<std::size_t>(tiles_x) * tiles_y;
  const int spp = settings.samples_per_pixel, bins = settings.spectral_bins;
  const double bin_width = (settings.lambda_max_nm - settings.lambda_min_nm) / std::max(1, bins);

  RenderResult result;
  result.rgb = LinearImage(W, H);
  if (bins > 0) {
    result.spectral.bins = bins;
    result.spectral.lambda_min_nm = settings.lambda_min_nm;
    result.spectral.lambda_max_nm = settings.lambda_max_nm;
    result.spectral.values.assign(static_cast<std::size_t>(W) * H * bins, 0.0f);
  }
  std::atomic<std::uint64_t> rays{0}, feather_points{0}, feather_mean{0};
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;

  // Each tile's warning tallies (Integrator::observe), summed in tile order after the render.
  std::vector<std::vector<WarningTally>> tile_warnings(integrator.watched().empty() ? 0 : tiles);

  auto render_tile = [&](std::size_t tile) {
    const int tx = static_cast<int>(tile % tiles_x), ty = static_cast<int>(tile / tiles_x);
    PathCounters counters;
    counters.warnings.resize(integrator.watched().size());
    std::vector<double> spectral_acc(static_cast<std::size_t>(std::max(bins, 0)));
    for (int y = ty * T; y < std::min(H, (ty + 1) * T); ++y) {
      for (int x = tx * T; x < std::min(W, (tx + 1) * T); ++x) {
        const std::uint64_t pixel = static_cast<std::uint64_t>(y) * W + x;
        Xyz sum;
        std::fill(spectral_acc.begin(), spectral_acc.end(), 0.0);
        for (int s = 0; s < spp; ++s) {
          PathSampler rng(settings.seed, pixel, static_cast<std::uint64_t>(s));
          const double u = rng.next(), v = rng.next();
          const Spectrum4 lambda = tables.wavelengths(rng.next());
          const CameraRay ray = camera.generate(x + u, y + v);
          const Spectrum4 L = integrator.trace(ray.origin, ray.dir, camera.spread_rad(), lambda, rng, counters);
          const Xyz c = tables.to_xyz(lambda, L);
          sum.x += c.x;
          sum.y += c.y;
          sum.z += c.z;
          for (int j = 0; j < kWavelengths && bins > 0; ++j) {
            // E[(range/binw)·1{λ_j ∈ bin}·L_j] = bin average of L; averaged over the 4 λ.
            const int b = std::min(bins - 1, static_cast<int>((lambda[j] - settings.lambda_min_nm) / bin_width));
            spectral_acc[static_cast<std::size_t>(b)] += 0.25 * tables.range() / bin_width * L[j];
          }
        }
        const double inv = 1.0 / spp;
        const Rgb rgb = xyz_to_linear_srgb({sum.x * inv, sum.y * inv, sum.z * inv});
        result.rgb.at(x, y) = {static_cast<float>(rgb.r), static_cast<float>(rgb.g), static_cast<float>(rgb.b)};
        for (int b = 0; b < bins; ++b) {
          result.spectral.values[pixel * bins + b] = static_cast<float>(spectral_acc[static_cast<std::size_t>(b)] * inv);
        }
      }
    }
    rays += counters.rays;
    feather_points += counters.feather_points;
    feather_mean += counters.feather_mean;
    if (!tile_warnings.empty()) tile_warnings[tile] = std::move(counters.warnings);
    const std::size_t finished = ++done;
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(finished, tiles, "tiles");
    }
  };

  auto run = [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t t = r.begin(); t != r.end(); ++t) render_tile(t);
                      },
                      tbb::simple_partitioner());
  };
  if (settings.threads > 0) {
    tbb::task_arena arena(settings.threads);
    arena.execute(run);
  } else {
    run();
  }

  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  result.stats.camera_paths = static_cast<std::uint64_t>(W) * H * spp;
  result.stats.rays = rays.load();
  result.stats.mean_lod_fraction =
      feather_points.load() > 0 ? static_cast<double>(feather_mean.load()) / static_cast<double>(feather_points.load()) : 0.0;
  std::vector<WarningTally> totals(integrator.watched().size());
  for (const std::vector<WarningTally>& tile : tile_warnings) {
    for (std::size_t k = 0; k < tile.size(); ++k) {
      totals[k].weight_in += tile[k].weight_in, totals[k].weight_total += tile[k].weight_total;
      totals[k].evaluations_in += tile[k].evaluations_in, totals[k].evaluations += tile[k].evaluations;
    }
  }
  result.warning_shares = integrator.warning_shares(totals);
  return result;
}

}  // namespace plumage::pathtracer
