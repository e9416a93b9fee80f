// Light transport against closed forms: a white Lambertian plane lit by (a) a square area light
// above it (irradiance from the rectangle form factor), (b) a point light, (c) a constant
// environment (E = π·L over the upper hemisphere, the lower half blocked by nothing: the plane
// is one-sided in view). Exercises NEE + power-heuristic MIS for area and environment lights
// with an independent reference; the camera looks straight down at the plane's centre.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "pathtracer.hpp"
#include "render_fixtures.hpp"

using namespace plumage;
using namespace plumage::testing;

namespace {

// Form factor from a point to a rectangle a × b parallel to it at height h, the point below one
// corner (e.g. Howell's catalogue, configuration B-3).
double corner_form_factor(double a, double b, double h) {
  const double X = a / h, Y = b / h;
  const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
  return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2.0 * kPi);
}

double centre_luminance(const Scene& s, int spp) {
  pathtracer::Settings settings;
  settings.samples_per_pixel = spp;
  settings.max_depth = 1;  // direct light only: the closed forms have no interreflection
  const RenderResult r = pathtracer::PathTracer(settings).render(s, {});
  double sum = 0;
  int n = 0;
  for (int y = 4; y < 12; ++y)
    for (int x = 4; x < 12; ++x) {
      const RgbF p = r.rgb.at(x, y);
      sum += srgb_luminance({p.r, p.g, p.b});
      ++n;
    }
  return sum / n;
}

Scene plane_scene() {
  Scene s;
  s.name = "plane";
  s.materials = {diffuse(0.5)};
  s.meshes.push_back(square(1000.0, 0));
  s.camera = far_camera({0.0, 0.0, 1.0}, 5.0, 0.02, 16);  // sees ±0.05 mm around the centre
  return s;
}

}  // namespace

TEST_CASE("pathtracer lights: Lambertian plane under area, point and environment lights", "[pathtracer]") {
  const double rho = 0.5, Y_white = 1.0;  // D65 × 1 has luminance 1
  SECTION("square area light (NEE + MIS)") {
    Scene s = plane_scene();
    // 4 × 4 mm light 3 mm above the centre, facing down (edge_u × edge_v = −z), radiance 2; the
    // camera below it.
    s.camera = far_camera({0.0, 0.0, 1.0}, 1.0, 0.02, 16);
    s.area_lights.push_back({v3f(-2, -2, 3), v3f(0, 4, 0), v3f(4, 0, 0), 2.0, false});
    const double E = kPi * 2.0 * 4.0 * corner_form_factor(2.0, 2.0, 3.0);
    const double expected = rho / kPi * E * Y_white;
    const double got = centre_luminance(s, 256);
    std::printf("lights: area %.5f expected %.5f (rel %.4f)\n", got, expected, std::abs(got / expected - 1));
    CHECK(std::abs(got / expected - 1.0) <= 0.02);
  }
  SECTION("point light") {
    Scene s = plane_scene();
    s.camera = far_camera({0.0, 0.0, 1.0}, 5.0, 0.02, 16);
    s.point_lights.push_back({v3f(0, 0, 10), 30.0});
    const double expected = rho / kPi * 30.0 / 100.0 * Y_white;
    const double got = centre_luminance(s, 16);
    std::printf("lights: point %.5f expected %.5f (rel %.4f)\n", got, expected, std::abs(got / expected - 1));
    CHECK(std::abs(got / expected - 1.0) <= 0.01);
  }
  SECTION("constant environment (NEE + MIS)") {
    Scene s = plane_scene();
    s.environment.radiance = 0.8;
    // Direct only (max_depth 1): the plane reflects ρ·L from its upper hemisphere; the camera
    // looks at it from above, and the plane (1 m wide) hides little of the sky near the centre.
    const double expected = rho * 0.8 * Y_white;
    const double got = centre_luminance(s, 256);
    std::printf("lights: environment %.5f expected %.5f (rel %.4f)\n", got, expected, std::abs(got / expected - 1));
    CHECK(std::abs(got / expected - 1.0) <= 0.02);
  }
}
