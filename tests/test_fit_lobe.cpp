// GGX fit on the cone (spec §4.2): recovery of known lobe parameters from synthetic patterns.
#include <catch2/catch.hpp>

#include <cmath>

#include "plumage/far_field.hpp"
#include "plumage/fitter.hpp"
#include "plumage/random.hpp"

using namespace plumage;

TEST_CASE("cone fit recovers (m, phi_c) of exact lobe patterns", "[fit]") {
  const auto phi_o = pattern_directions(400).phi_o_rad;
  struct Case { double ct, cp, m, phi_c_deg; };
  for (const Case c : {Case{1.0, 1.0, 0.05, 0.0}, Case{0.8, 0.6, 0.2, -40.0}, Case{0.5, 0.9, 0.012, 20.0},
                       Case{0.3, 0.5, 0.6, 55.0}, Case{1.0, 0.35, 0.08, 65.0}}) {
    const double theta = std::acos(c.ct), phi_i = std::acos(c.cp);
    auto u = cone_lobe_shape(theta, c.m, deg_to_rad(c.phi_c_deg), phi_o);
    for (double& v : u) v *= 3.7;  // scale must not matter (energy matching)
    const ConeFit f = fit_cone_lobe(theta, phi_i, phi_o, u);
    INFO("case m " << c.m << " phi_c " << c.phi_c_deg << " -> " << f.m << ", " << rad_to_deg(f.phi_c_rad));
    CHECK(f.m == Approx(c.m).epsilon(1e-4));
    CHECK(rad_to_deg(f.phi_c_rad) == Approx(c.phi_c_deg).margin(1e-3));
    CHECK(f.rel_l2 < 1e-5);
  }
}

TEST_CASE("cone fit with 10 % multiplicative noise stays close", "[fit]") {
  const auto phi_o = pattern_directions(400).phi_o_rad;
  RandomStream rng(42, "fit-noise");
  const double theta = std::acos(0.7), phi_i = std::acos(0.8);
  auto u = cone_lobe_shape(theta, 0.15, deg_to_rad(-30.0), phi_o);
  for (double& v : u) v *= 1.0 + 0.1 * rng.normal();
  const ConeFit f = fit_cone_lobe(theta, phi_i, phi_o, u);
  CHECK(f.m == Approx(0.15).epsilon(0.03));
  CHECK(rad_to_deg(f.phi_c_rad) == Approx(-30.0).margin(0.5));
  CHECK(f.rel_l2 == Approx(0.1).epsilon(0.3));  // the noise level, not more
}

TEST_CASE("cone fit grazing blend of phi_c (spec 4.2)", "[fit]") {
  const auto phi_o = pattern_directions(400).phi_o_rad;
  // w = cos θ cos φ ≤ 0.05: φ_c = φ_i whatever the pattern says; m still fitted.
  {
    const double theta = std::acos(0.2), phi_i = std::acos(0.2);
    const auto u = cone_lobe_shape(theta, 0.3, deg_to_rad(10.0), phi_o);
    const ConeFit f = fit_cone_lobe(theta, phi_i, phi_o, u);
    CHECK(f.phi_c_rad == Approx(phi_i).margin(1e-12));
    CHECK(f.m > 0.001);
  }
  // w = 0.075: halfway between φ_i and the fitted value.
  {
    const double theta = std::acos(0.25), phi_i = std::acos(0.3);
    const auto u = cone_lobe_shape(theta, 0.3, deg_to_rad(10.0), phi_o);
    const ConeFit f = fit_cone_lobe(theta, phi_i, phi_o, u);
    CHECK(f.phi_c_rad == Approx(0.5 * (phi_i + deg_to_rad(10.0))).margin(2e-4));
  }
}

TEST_CASE("cone fit is deterministic", "[fit]") {
  const auto phi_o = pattern_directions(400).phi_o_rad;
  RandomStream rng(7, "det");
  auto u = cone_lobe_shape(0.4, 0.07, 0.3, phi_o);
  for (double& v : u) v *= 1.0 + 0.2 * rng.uniform();
  const ConeFit a = fit_cone_lobe(0.4, 0.5, phi_o, u), b = fit_cone_lobe(0.4, 0.5, phi_o, u);
  CHECK(a.m == b.m);
  CHECK(a.phi_c_rad == b.phi_c_rad);
}
