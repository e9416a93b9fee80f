// Embree's own traversal rate on a Scene's triangles and pinhole camera (`plumage bench render`):
// jittered camera rays, closest hit only, no shading, oneTBB over all cores; once with
// rtcIntersect1 and once with rtcIntersect16 packets. The yardstick the path tracer's rays/s is
// read against.
#pragma once

#include <cstdint>

#include "plumage/scene.hpp"

namespace plumage::pathtracer {

struct TraversalRate {
  double rays_per_s_1 = 0, rays_per_s_16 = 0;
  std::uint64_t rays = 0, hits = 0;  // per pass; hits of the rtcIntersect1 pass
};

TraversalRate embree_traversal_rate(const Scene& scene, int rays_per_pixel);

}  // namespace plumage::pathtracer
