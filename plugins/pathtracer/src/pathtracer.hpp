// The "pathtracer" Renderer (renderer.hpp): Embree scene, pinhole camera, oneTBB over tiles,
// per-pixel accumulation in a fixed sample order (bit-identical for any thread count),
// spectral → CIE XYZ → linear sRGB, optional spectral bins. Its settings (settings.hpp) are fixed
// at construction.
#pragma once

#include "plumage/renderer.hpp"
#include "settings.hpp"

namespace plumage::pathtracer {

class PathTracer final : public Renderer {
 public:
  explicit PathTracer(Settings settings = {}) : settings_(settings) {}

  RenderResult render(const Scene& scene, Progress progress) const override;
  std::string describe() const override { return pathtracer::describe(settings_); }
  const Settings& settings() const { return settings_; }

 private:
  Settings settings_;
};

// Throws Error naming the mesh/material/field for inconsistent scenes (indices, frames, sizes).
void validate_scene(const Scene& scene, const Settings& settings);

}  // namespace plumage::pathtracer
