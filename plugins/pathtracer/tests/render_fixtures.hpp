// Scenes and materials of the path tracer tests, built in memory (a clean clone has no
// characterised .plm files): the ladder's reference scene and its pieces (square, diffuse,
// synthetic feather, far camera, noisy feather scene: plugins/pathtracer/reference), plus an
// icosphere and colour helpers independent of the renderer (trapezoid rule on the CIE tables).
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "bsdf_fixtures.hpp"
#include "plumage/colour.hpp"
#include "plumage/conventions.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/fitter.hpp"
#include "plumage/scene.hpp"
#include "reference_scene.hpp"

namespace plumage::testing {

using pathtracer::reference::diffuse;
using pathtracer::reference::far_camera;
using pathtracer::reference::feather;
using pathtracer::reference::noisy_feather_scene;
using pathtracer::reference::square;
using pathtracer::reference::synthetic_feather;
using pathtracer::reference::v3f;

// Icosphere of radius r (subdivided `levels` times, vertices on the sphere): a convex closed mesh,
// outward winding.
inline SceneMesh icosphere(double r, int levels, std::uint32_t material) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  auto norm = [](std::array<double, 3> a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return std::array<double, 3>{a[0] / l, a[1] / l, a[2] / l};
  };
  for (auto& q : p) q = norm(q);
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<std::uint32_t, 3>> g;
    for (auto tri : f) {
      std::uint32_t mid[3];
      for (int e = 0; e < 3; ++e) {
        const auto a = p[tri[e]], b = p[tri[(e + 1) % 3]];
        p.push_back(norm({a[0] + b[0], a[1] + b[1], a[2] + b[2]}));
        mid[e] = static_cast<std::uint32_t>(p.size() - 1);
      }
      g.push_back({tri[0], mid[0], mid[2]});
      g.push_back({tri[1], mid[1], mid[0]});
      g.push_back({tri[2], mid[2], mid[1]});
      g.push_back({mid[0], mid[1], mid[2]});
    }
    f = std::move(g);
  }
  SceneMesh m;
  m.name = "icosphere";
  for (const auto& q : p) m.positions.push_back(v3f(r * q[0], r * q[1], r * q[2]));
  m.triangles = f;
  m.material = material;
  // A shading frame per triangle (used only with feather materials): n = face normal.
  for (const auto& tri : f) {
    double c[3] = {0, 0, 0};
    for (auto i : tri) for (int k = 0; k < 3; ++k) c[k] += p[i][k] / 3.0;
    const auto n = norm({c[0], c[1], c[2]});
    const auto a = norm(std::abs(n[2]) < 0.9 ? std::array<double, 3>{-n[1], n[0], 0.0}
                                              : std::array<double, 3>{0.0, -n[2], n[1]});
    m.frame_normal.push_back(v3f(n[0], n[1], n[2]));
    m.frame_axis.push_back(v3f(a[0], a[1], a[2]));
  }
  return m;
}

// Linear sRGB of a radiance spectrum L(λ) (in D65 table units) over [lmin, lmax], by the
// trapezoid rule on a 0.1 nm grid with the CIE tables interpolated linearly, normalised per XYZ
// channel so that D65 × 1 gives the white point (the renderer's stated convention, written
// out here independently).
template <class F>
Rgb reference_rgb(F radiance, double lmin = 400.0, double lmax = 700.0) {
  const CieTables& t = cie_tables();
  auto lerp = [&](const std::vector<double>& v, double l) {
    std::size_t i = 0;
    while (i + 2 < t.lambda_nm.size() && t.lambda_nm[i + 1] <= l) ++i;
    const double a = (l - t.lambda_nm[i]) / (t.lambda_nm[i + 1] - t.lambda_nm[i]);
    return v[i] + a * (v[i + 1] - v[i]);
  };
  const int n = static_cast<int>(std::round((lmax - lmin) / 0.1));
  Xyz s, w;
  for (int i = 0; i <= n; ++i) {
    const double l = lmin + (lmax - lmin) * i / n, h = (i == 0 || i == n ? 0.5 : 1.0);
    const double d = lerp(t.d65, l), L = radiance(l);
    const double x = lerp(t.xbar, l), y = lerp(t.ybar, l), z = lerp(t.zbar, l);
    s.x += h * L * x; s.y += h * L * y; s.z += h * L * z;
    w.x += h * d * x; w.y += h * d * y; w.z += h * d * z;
  }
  const Xyz white = d65_white_point();
  return xyz_to_linear_srgb({s.x * white.x / w.x, s.y * white.y / w.y, s.z * white.z / w.z});
}

inline double d65_at(double l) {
  const CieTables& t = cie_tables();
  std::size_t i = 0;
  while (i + 2 < t.lambda_nm.size() && t.lambda_nm[i + 1] <= l) ++i;
  const double a = (l - t.lambda_nm[i]) / (t.lambda_nm[i + 1] - t.lambda_nm[i]);
  return t.d65[i] + a * (t.d65[i + 1] - t.d65[i]);
}

}  // namespace plumage::testing
