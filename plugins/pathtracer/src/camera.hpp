// Pinhole camera of Camera (scene.hpp): pixel (0, 0) top-left, film coordinates in pixels.
#pragma once

#include <cmath>

#include "plumage/scene.hpp"
#include "vec3.hpp"

namespace plumage::pathtracer {

struct CameraRay {
  V3 origin, dir;
};

class PinholeCamera {
 public:
  explicit PinholeCamera(const Camera& c) : width_(c.width), height_(c.height) {
    origin_ = to_v3(c.position_mm);
    forward_ = normalize(to_v3(c.look_at_mm) - origin_);
    right_ = normalize(cross(forward_, to_v3(c.up)));
    up_ = cross(right_, forward_);
    tan_half_ = std::tan(0.5 * c.vertical_fov_rad);
    aspect_ = static_cast<double>(c.width) / c.height;
  }
  // Film position (px, py) in pixels, continuous.
  CameraRay generate(double px, double py) const {
    const double sx = (2.0 * px / width_ - 1.0) * tan_half_ * aspect_;
    const double sy = (1.0 - 2.0 * py / height_) * tan_half_;
    return {origin_, normalize(forward_ + sx * right_ + sy * up_)};
  }
  // Angle one pixel subtends at the image centre: the ray cone's spread (LOD).
  double spread_rad() const { return 2.0 * tan_half_ / height_; }

 private:
  int width_, height_;
  V3 origin_, forward_, right_, up_;
  double tan_half_ = 0.0, aspect_ = 1.0;
};

}  // namespace plumage::pathtracer
