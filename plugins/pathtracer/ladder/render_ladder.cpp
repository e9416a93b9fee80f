// Accuracy ladder "pathtracer" (issue 9): the renderer at growing samples per pixel against a
// converged render of the same scene (many more samples, an independent seed, so that its
// residual noise is uncorrelated with the rungs'): relative RMS of the linear sRGB image. The
// scene is the reference library's noisy feather scene (reference/reference_scene.hpp, shared
// with the tests: a synthetic feather patch over a diffuse floor, area + point light +
// environment), so every estimator contributes.
#include <cmath>
#include <cstdio>

#include "pathtracer.hpp"
#include "plumage/accuracy_ladder.hpp"
#include "reference_scene.hpp"

namespace plumage::pathtracer {

namespace {

// RMS over pixels and channels of (a − ref), relative to the RMS of ref.
double relative_rms(const LinearImage& a, const LinearImage& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) {
    const RgbF p = a.pixels()[i], q = ref.pixels()[i];
    num += (p.r - q.r) * (p.r - q.r) + (p.g - q.g) * (p.g - q.g) + (p.b - q.b) * (p.b - q.b);
    den += q.r * q.r + q.g * q.g + q.b * q.b;
  }
  return std::sqrt(num / den);
}

}  // namespace

std::vector<LadderPoint> run_render_ladder(const AccuracyLadder::Options& options) {
  const int size = options.quick ? 32 : 64;
  const int reference_spp = options.quick ? 4096 : 16384;
  const std::vector<int> ladder = options.quick ? std::vector<int>{1, 4, 16, 64, 256} : std::vector<int>{1, 4, 16, 64, 256, 1024};
  const Scene scene = reference::noisy_feather_scene(size);
  Settings settings;
  settings.samples_per_pixel = reference_spp;
  settings.seed = 0x5eed0001;
  if (options.progress) options.progress("reference: " + std::to_string(reference_spp) + " spp");
  const LinearImage converged = PathTracer(settings).render(scene, {}).rgb;
  char case_name[96];
  std::snprintf(case_name, sizeof case_name, "feather patch over a floor, %dx%d px", size, size);
  std::vector<LadderPoint> points;
  for (int spp : ladder) {
    settings.samples_per_pixel = spp;
    settings.seed = 0x5eed1000u + static_cast<unsigned>(spp);
    LinearImage image;
    const PathTracer tracer(settings);
    const RungCost cost = measure_rung([&] { image = tracer.render(scene, {}).rgb; });
    LadderPoint pt;
    pt.backend = "pathtracer";
    pt.case_name = case_name;
    pt.setting = "spp=" + std::to_string(spp);
    pt.fidelity = spp;
    pt.reference = "converged render (" + std::to_string(reference_spp) + " spp, independent seed)";
    pt.metric = "relative RMS of the linear sRGB image";
    pt.error = relative_rms(image, converged);
    pt.wall_s = cost.wall_s;
    pt.cpu_s = cost.cpu_s;
    if (options.progress) {
      char line[160];
      std::snprintf(line, sizeof line, "%s: error %.3g, %.3g s", pt.setting.c_str(), pt.error, pt.wall_s);
      options.progress(line);
    }
    points.push_back(pt);
  }
  return points;
}

}  // namespace plumage::pathtracer
