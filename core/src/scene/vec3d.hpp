// Small double-precision 3-vector for building scene geometry (stored as Vec3f in SceneMesh).
#pragma once

#include <cmath>

#include "plumage/scene.hpp"

namespace plumage::scene_detail {

struct V3 {
  double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 normalized(V3 a) {
  const double n = norm(a);
  return n > 0 ? (1.0 / n) * a : V3{0, 0, 1};
}
inline V3 from_f(Vec3f v) { return {v.x, v.y, v.z}; }
inline Vec3f to_f(V3 v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
// `a` rotated by `angle` about the unit axis `k` (Rodrigues).
inline V3 rotated(V3 a, V3 k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * a + s * cross(k, a) + ((1 - c) * dot(k, a)) * k;
}

constexpr double kPiD = 3.14159265358979323846;
inline double rad(double deg) { return deg * kPiD / 180.0; }

}  // namespace plumage::scene_detail
