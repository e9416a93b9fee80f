// The Embree 3 scene of a plumage Scene: one triangle geometry per SceneMesh (geomID = mesh
// index, primID = triangle index) and two triangles per area light (geomID = meshes + light
// index), RTC_SCENE_FLAG_ROBUST, build quality high. Owns the device; thread-safe queries.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <limits>

#include "plumage/scene.hpp"
#include "vec3.hpp"

namespace plumage::pathtracer {

struct Hit {
  bool found = false;
  double t = 0.0;
  unsigned geom = 0, prim = 0;
  double u = 0.0, v = 0.0;  // barycentrics: hit = (1 − u − v)·p0 + u·p1 + v·p2
  V3 ng;  // geometric normal, unit, orientation of the triangle's winding
};

class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  Hit intersect(V3 origin, V3 dir, double tmax = std::numeric_limits<double>::infinity()) const;
  bool occluded(V3 origin, V3 dir, double tmax) const;

  unsigned mesh_count() const { return meshes_; }
  // Largest |coordinate| of the scene (mm): sets the ray-origin offset against self-hits.
  double extent() const { return extent_; }
  RTCScene handle() const { return scene_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  unsigned meshes_ = 0;
  double extent_ = 1.0;
};

}  // namespace plumage::pathtracer
