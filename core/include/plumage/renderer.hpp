// Extension point: renderers of a Scene (issue 8). Implementation: "pathtracer"
// (plugins/pathtracer: Embree 3, hero-wavelength spectral path tracing).
//
// A renderer owns its settings (samples, seeds, level of detail, wavelength range...): its
// factory reads them from the scene's `renderer:` section through its own parameter table, so
// the Scene carries only what every renderer sees (geometry, materials, lights, camera).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "plumage/exr.hpp"
#include "plumage/image.hpp"
#include "plumage/material_warnings.hpp"
#include "plumage/plugin.hpp"
#include "plumage/scene.hpp"

namespace plumage {

struct RenderStats {
  double seconds = 0.0;              // wall time of render()
  std::uint64_t camera_paths = 0;    // width × height × spp
  std::uint64_t rays = 0;            // every ray traced (camera, bounce, shadow)
  double mean_lod_fraction = 0.0;    // share of feather shading points that used the mean BRDF
};

struct RenderResult {
  // Linear sRGB radiance; a white Lambertian surface under a unit-irradiance D65 distant light
  // at normal incidence gives (1/π)·(1, 1, 1) up to the sRGB white point rounding.
  LinearImage rgb;
  // Radiance per equal wavelength bin, [y][x][bin], as the EXR writer takes it; bins == 0 when
  // the renderer was not asked for spectral channels.
  SpectralChannels spectral;
  RenderStats stats;
  // Per feather material and warning code that says where it was raised (the material's cells,
  // plumage/material_warnings.hpp): the throughput-weighted share of its BSDF evaluations that
  // reach those directions; render_job warns when a share is above render.warning_share. Only
  // observed: the image does not depend on it. Deterministic like the image.
  std::vector<WarningShare> warning_shares;
};

class Renderer : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "renderer";

  // (work done, total work, message); may be empty. Called from one thread at a time.
  using Progress = std::function<void(std::size_t done, std::size_t total, std::string_view what)>;

  // Deterministic: the same scene and settings (seed included) give the same image for any
  // thread count.
  virtual RenderResult render(const Scene& scene, Progress progress) const = 0;

  // The settings a log line names, e.g. "16 spp, lod auto, seed 1"; may be empty.
  virtual std::string describe() const { return {}; }
};

}  // namespace plumage
