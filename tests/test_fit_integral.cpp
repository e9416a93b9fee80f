// Hemisphere integral of the lobe (spec §4.3): graded Gauss–Legendre vs brute-force midpoint.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>

#include "plumage/fitter.hpp"

using namespace plumage;

namespace {
// Midpoint rule with n_theta × n_phi cells over (−π/2, π/2)², dω = cos θ_o dθ dφ.
double midpoint(const Lobe& l, double theta_i, int n_theta, int n_phi) {
  const double dt = kPi / n_theta, dp = kPi / n_phi;
  double s = 0;
  for (int a = 0; a < n_theta; ++a) {
    const double to = -0.5 * kPi + (a + 0.5) * dt;
    double r = 0;
    for (int b = 0; b < n_phi; ++b) r += lobe_value(l, theta_i, direction_from_angles(to, -0.5 * kPi + (b + 0.5) * dp));
    s += std::cos(to) * r;
  }
  return s * dt * dp;
}
}  // namespace

TEST_CASE("hemisphere integral agrees with a converged brute-force rule", "[fit][fit-integral]") {
  struct Case { double theta_deg, phi_c_deg, m, sigma; };
  double worst = 0, worst_spec = 0;
  for (const Case c : {Case{0, 0, 0.1, 0.04}, Case{30, 40, 0.05, 0.04}, Case{60, -20, 0.3, 0.08},
                       Case{80, 70, 0.02, 0.04}}) {
    const Lobe lobe{c.m, deg_to_rad(c.phi_c_deg), c.sigma, 1.0};
    const double theta = deg_to_rad(c.theta_deg);
    const double fast = hemisphere_lobe_integral(lobe, theta);
    // Reference: 8000 × 2500 midpoints (θ finer: a grazing lobe is ~0.003 rad thin in θ_o).
    // Converged: for the grazing case 10000…40000 × 2000…4000 cells agree to 5e-7.
    const double ref = midpoint(lobe, theta, 8000, 2500);
    const double spec = hemisphere_lobe_integral_midpoint(lobe, theta, 2000);  // the spec's rule
    const double err = std::abs(fast - ref) / ref;
    worst = std::max(worst, err);
    worst_spec = std::max(worst_spec, std::abs(spec - ref) / ref);
    INFO("theta " << c.theta_deg << " phi_c " << c.phi_c_deg << " m " << c.m << ": fast " << fast << " ref " << ref);
    CHECK(err < 2e-5);
  }
  std::cout << "hemisphere integral: worst relative error vs 8000x2500 midpoint " << worst
            << " (the spec's 2000^2 rule: " << worst_spec << ")\n";
}
