#include "reference_scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "plumage/feather_material.hpp"
#include "plumage/fitter.hpp"

namespace plumage::pathtracer::reference {

SceneMesh square(double size, std::uint32_t material, int barbules) {
  SceneMesh m;
  m.name = "square";
  const double h = 0.5 * size;
  m.positions = {v3f(-h, -h, 0), v3f(h, -h, 0), v3f(h, h, 0), v3f(-h, h, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.frame_axis = {v3f(0, 1, 0), v3f(0, 1, 0)};
  m.frame_normal = {v3f(0, 0, 1), v3f(0, 0, 1)};
  m.material = material;
  if (barbules > 0) m.barbule_spacing_mm = size / barbules;
  return m;
}

SceneMaterial diffuse(double albedo) {
  SceneMaterial m;
  m.name = "white";
  m.kind = SceneMaterial::Kind::diffuse;
  m.albedo.value = {albedo};
  return m;
}

SceneMaterial feather(std::shared_ptr<const FeatherBsdf> bsdf) {
  SceneMaterial m;
  m.name = "feather";
  m.kind = SceneMaterial::Kind::feather;
  m.feather = std::move(bsdf);
  return m;
}

FeatherMaterial synthetic_feather_material(double peak_albedo, int grid) {
  constexpr int kBins = 50;
  FeatherMaterial m;
  m.label = "synthetic/test";
  m.sigma = 0.04;
  m.l0 = 0.3;
  m.grid = grid;
  for (int w = 0; w < kBins; ++w) m.lambda_nm.push_back(400.0 + 6.0 * w);
  m.nodes.resize(static_cast<std::size_t>(kBins) * (grid + 1) * (grid + 1));
  for (int w = 0; w < kBins; ++w) {
    for (int i = 0; i <= grid; ++i) {
      for (int j = 0; j <= grid; ++j) {
        const double ct = static_cast<double>(i) / grid, cp = static_cast<double>(j) / grid;
        MaterialNode& n = m.node(static_cast<std::size_t>(w), i, j);
        const double phi_i = std::acos(cp);
        n.m_eff = 0.15 + 0.15 * (1.0 - ct) + 0.001 * w;
        n.phi_eff = std::clamp(phi_i + deg_to_rad(6.0) * (1.0 - ct), -0.5 * kPi, 0.5 * kPi);
        n.m_sta = 0.1;
        n.phi_sta = n.phi_eff;
        n.pol_share = 0.6;
        n.correlation = 1.0;
        n.f_eff = n.f_sta = 0.0;
        if (i == 0 || j == 0) continue;  // grazing rows: F = 0 (spec §4.7)
        const double theta_i = std::acos(ct);
        const double I = hemisphere_lobe_integral(Lobe{n.m_eff, n.phi_eff, m.sigma, 1.0}, theta_i);
        const double z = (w - 24.0) / 8.0;
        const double albedo = 0.1 + (peak_albedo - 0.1) * std::exp(-z * z);
        const double F = I > 0.0 ? albedo / I : 0.0;
        n.f_eff = F * ct * cp;  // premultiplied (spec §4.3)
        n.f_sta = 0.3 * n.f_eff;
      }
    }
  }
  m.noise = ar1_pool(64, 64, 0.8, 0xfea7);
  return m;
}

std::shared_ptr<const FeatherBsdf> synthetic_feather(double peak_albedo, int grid) {
  return std::make_shared<FeatherBsdf>(std::make_shared<FeatherMaterial>(synthetic_feather_material(peak_albedo, grid)));
}

NoisePool ar1_pool(std::size_t count, int samples, double rho, std::uint64_t seed) {
  NoisePool p;
  p.samples = samples;
  p.lag1 = rho;
  p.functions.resize(count * static_cast<std::size_t>(samples));
  std::mt19937_64 rng(seed);
  bool has_spare = false;
  double spare = 0.0;
  auto gauss = [&] {
    if (has_spare) {
      has_spare = false;
      return spare;
    }
    const double u1 = (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare = r * std::sin(2.0 * kPi * u2);
    has_spare = true;
    return r * std::cos(2.0 * kPi * u2);
  };
  const double c = std::sqrt(1.0 - rho * rho);
  for (std::size_t k = 0; k < count; ++k) {
    double v = gauss();
    for (int t = 0; t < samples; ++t) {
      if (t > 0) v = rho * v + c * gauss();
      p.functions[k * samples + t] = static_cast<float>(v);
    }
  }
  return p;
}

Camera far_camera(Direction toward_camera, double distance_mm, double fov_rad, int size) {
  Camera c;
  c.position_mm = v3f(distance_mm * toward_camera.x, distance_mm * toward_camera.y, distance_mm * toward_camera.z);
  c.look_at_mm = v3f(0, 0, 0);
  c.up = std::abs(toward_camera.y) < 0.9 ? v3f(0, 1, 0) : v3f(1, 0, 0);
  c.vertical_fov_rad = fov_rad;
  c.width = c.height = size;
  return c;
}

Scene noisy_feather_scene(int size) {
  Scene s;
  s.name = "noisy";
  s.materials = {diffuse(0.6), feather(synthetic_feather(0.8, 6))};
  SceneMesh floor = square(60.0, 0);
  for (auto& p : floor.positions) p.z = -1.0f;
  s.meshes.push_back(floor);
  s.meshes.push_back(square(12.0, 1, 200));
  s.area_lights.push_back({v3f(-10, -10, 25), v3f(20, 0, 0), v3f(0, 20, 0), 0.4, false});
  // The emitting side is edge_u × edge_v = +z: swapped, it faces down onto the scene.
  std::swap(s.area_lights[0].edge_u_mm, s.area_lights[0].edge_v_mm);
  s.point_lights.push_back({v3f(8, 4, 10), 40.0});
  s.environment.radiance = 0.1;
  s.camera = far_camera({0.2, -0.4, 0.89}, 40.0, 0.9, size);
  return s;
}

}  // namespace plumage::pathtracer::reference
