// Small double-precision vector maths of the path tracer (shading and sampling in double; Embree
// rays in float).
#pragma once

#include <algorithm>
#include <cmath>

#include "plumage/scene.hpp"

namespace plumage::pathtracer {

struct V3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 normalize(V3 a) {
  const double l = length(a);
  return l > 0.0 ? (1.0 / l) * a : a;
}
inline V3 to_v3(Vec3f v) { return {v.x, v.y, v.z}; }
inline double max_abs(V3 a) { return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}); }

// An orthonormal frame (x, y, z): world → local and back.
struct Frame {
  V3 x, y, z;
  V3 to_local(V3 w) const { return {dot(w, x), dot(w, y), dot(w, z)}; }
  V3 to_world(V3 l) const { return l.x * x + l.y * y + l.z * z; }
  // Any frame around a unit normal (Duff et al. 2017, branchless).
  static Frame around(V3 n) {
    const double s = std::copysign(1.0, n.z);
    const double a = -1.0 / (s + n.z), b = n.x * n.y * a;
    return {{1.0 + s * n.x * n.x * a, s * b, -s * n.x}, {b, s + n.y * n.y * a, -n.y}, n};
  }
};

}  // namespace plumage::pathtracer
