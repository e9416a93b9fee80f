// FeatherMaterial::lookup: bicubic Hermite over the incident grid (spec geometry-and-brdf §4.7).
#include <catch2/catch.hpp>

#include <cmath>

#include "plumage/feather_material.hpp"

using namespace plumage;

namespace {

FeatherMaterial grid_material(double (*f)(double, double)) {
  FeatherMaterial m;
  m.grid = 20;
  m.lambda_nm = {400.0, 406.0};
  m.nodes.resize(2 * 21 * 21);
  for (std::size_t w = 0; w < 2; ++w) {
    for (int i = 0; i <= 20; ++i) {
      for (int j = 0; j <= 20; ++j) {
        MaterialNode& n = m.node(w, i, j);
        const double v = f(i / 20.0, j / 20.0) + static_cast<double>(w);
        n.m_eff = n.m_sta = 0.5 * v;
        n.phi_eff = n.phi_sta = 0.1 * v;
        n.f_eff = n.f_sta = v;
        n.pol_share = 0.25 * v;
        n.correlation = v;
      }
    }
  }
  return m;
}

}  // namespace

TEST_CASE("material lookup: nodes exact, linear fields exact everywhere", "[material]") {
  const FeatherMaterial m = grid_material([](double a, double b) { return 0.3 + 0.4 * a + 0.5 * b; });
  for (double ct : {0.05, 0.1, 0.37, 0.5, 0.999, 1.0}) {
    for (double cp : {0.05, 0.2, 0.61, 1.0}) {
      const double v = 0.3 + 0.4 * ct + 0.5 * cp;
      const MaterialNode n = m.lookup(0, ct, cp);
      CHECK(n.m_eff == Approx(0.5 * v).margin(1e-14));
      // φ fields are interpolated through their offsets from acos(cos φ_i): see the next test.
      CHECK(n.f_eff == Approx(v / (ct * cp)).epsilon(1e-13));  // stored premultiplied
      CHECK(n.correlation == Approx(v).margin(1e-14));
      CHECK(m.lookup(1, ct, cp).correlation == Approx(v + 1).margin(1e-14));
    }
  }
  CHECK(m.lookup(0, 0.0, 0.5).f_eff == 0.0);  // exact grazing
}

TEST_CASE("material lookup: smooth fields converge at third order", "[material]") {
  const FeatherMaterial m = grid_material([](double a, double b) { return 2.0 + std::sin(3 * a) * std::cos(2 * b); });
  double worst = 0;
  for (int k = 0; k < 200; ++k) {
    const double ct = 0.1 + 0.8 * std::fmod(k * 0.618034, 1.0), cp = 0.1 + 0.8 * std::fmod(k * 0.414214, 1.0);
    worst = std::max(worst, std::abs(m.lookup(0, ct, cp).correlation - 2.0 - std::sin(3 * ct) * std::cos(2 * cp)));
  }
  // h = 0.05, finite-difference slopes: O(h³) ≈ 1e-4 · derivatives of order 10.
  CHECK(worst < 5e-4);
}

TEST_CASE("material lookup: phi_eff that follows the nominal azimuth is reproduced", "[material]") {
  // φ_eff = φ_i + a smooth offset: the offset is interpolated, so the steep acos near cos φ_i = 1
  // costs nothing (interpolating φ_eff itself missed it by up to 4°).
  FeatherMaterial m = grid_material([](double, double) { return 1.0; });
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) m.node(0, i, j).phi_eff = std::acos(j / 20.0) - 0.02 * (i / 20.0);
  }
  double worst = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const double cp = k / 1000.0, ct = 0.3 + 0.0004 * k;
    worst = std::max(worst, std::abs(m.lookup(0, ct, cp).phi_eff - std::acos(cp) + 0.02 * ct));
  }
  CHECK(worst < 1e-12);
}

TEST_CASE("material wavelength bins: floor binning, clamped", "[material]") {
  FeatherMaterial m = grid_material([](double, double) { return 1.0; });
  CHECK(m.wavelength_bin(399.0) == 0);
  CHECK(m.wavelength_bin(405.9) == 0);
  CHECK(m.wavelength_bin(406.0) == 1);
  CHECK(m.wavelength_bin(800.0) == 1);
}
