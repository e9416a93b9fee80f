// The "pathtracer" Renderer (renderer.hpp): Embree scene, pinhole camera, oneTBB over tiles,
// per-pixel accumulation in a fixed sample order (bit-identical for any thread count),
// spectral → CIE XYZ → linear sRGB, optional spectral bins.
#pragma once

#include "plumage/renderer.hpp"

namespace plumage::pathtracer {

class PathTracer final : public Renderer {
 public:
  RenderResult render(const Scene& scene, const RenderSettings& settings, Progress progress) const override;
};

// Throws Error naming the mesh/material/field for inconsistent scenes (indices, frames, sizes).
void validate_scene(const Scene& scene, const RenderSettings& settings);

}  // namespace plumage::pathtracer
