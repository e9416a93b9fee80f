// The scene of the path tracer's accuracy ladder (ladder/render_ladder.cpp) and of its tests,
// built in memory (a clean clone has no characterised .plm): flat squares, a diffuse floor, a
// synthetic coloured FeatherMaterial over 400–700 nm with an AR(1) instance-noise pool, a far
// pinhole camera. A small library beside the renderer (issue 22: production code does not include
// tests/); the tests add their own closed forms (tests/render_fixtures.hpp).
#pragma once

#include <cstdint>
#include <memory>

#include "plumage/conventions.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/scene.hpp"

namespace plumage::pathtracer::reference {

inline Vec3f v3f(double x, double y, double z) {
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

// Square of side `size` mm in the plane z = 0, centred at the origin, normal +z; frame t = +y.
// barbules > 0: a feather patch of that many barbules across (barbule_spacing_mm = size/barbules).
SceneMesh square(double size, std::uint32_t material, int barbules = 0);

SceneMaterial diffuse(double albedo);
SceneMaterial feather(std::shared_ptr<const FeatherBsdf> bsdf);

// A coloured synthetic feather: 50 bins of 6 nm from 400 nm, reflected albedo E peaking at
// 544 nm (0.1 + (peak − 0.1)·exp(−((w − 24)/8)²)), roughness m_eff = 0.15–0.3, the lobe's
// effective azimuth offset by up to 6° (a non-trivial φ_eff), σ = 0.04, l0 = 0.3, statistics
// lobe m = 0.1 at 0.3 of F_eff, pol_share 0.6; F_eff from the fitter's hemisphere integral
// (fitter.hpp), so that A_r = E at the nodes; 64 AR(1) noise functions of 64 samples, ρ = 0.8.
FeatherMaterial synthetic_feather_material(double peak_albedo = 0.8, int grid = 10);
std::shared_ptr<const FeatherBsdf> synthetic_feather(double peak_albedo = 0.8, int grid = 10);

// Independent stationary Gaussian AR(1) functions: zero mean, unit variance, lag-1 ρ; Box–Muller
// on std::mt19937_64 (not std::normal_distribution, whose output is implementation-defined).
NoisePool ar1_pool(std::size_t count, int samples, double rho, std::uint64_t seed);

// Far pinhole camera looking at the origin from direction `toward_camera` (unit), narrow field.
Camera far_camera(Direction toward_camera, double distance_mm, double fov_rad, int size);

// Feather patch over a diffuse floor, an area light, a point light and an environment: every
// estimator (NEE + MIS, BSDF sampling, spectral MIS, roulette) contributes noise.
Scene noisy_feather_scene(int size);

}  // namespace plumage::pathtracer::reference
