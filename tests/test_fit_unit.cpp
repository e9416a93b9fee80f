// fit_unit (spec §4.1–4.6) on synthetic far fields with known statistics: random fields whose
// mean intensity follows a known lobe shape on the cone.
#include <catch2/catch.hpp>

#include <cmath>

#include "plumage/fitter.hpp"
#include "plumage/random.hpp"

using namespace plumage;

TEST_CASE("fit_unit recovers the lobe, energy, polarization share and coherent part of synthetic fields", "[fit]") {
  const double th = std::acos(0.7), ph = std::acos(0.8), m = 0.15, phi_c = -0.3;
  const auto pattern = pattern_directions(400);
  const auto projected = projected_directions(th, 1024);
  std::vector<double> phi = pattern.phi_o_rad;
  phi.insert(phi.end(), projected.phi_o_rad.begin(), projected.phi_o_rad.end());
  const auto shape = cone_lobe_shape(th, m, phi_c, phi);
  // Pol 1 carries 3× the intensity of pol 2 (share 0.75); a coherent part c·√shape in z.
  std::vector<FarField> inst(50);
  RandomStream rng(3, "fit-unit");
  const double coherent = 0.4;
  for (auto& f : inst) {
    f.incident = {th, ph};
    f.phi_o_rad = phi;
    f.incident_power = {1.0, 1.0};
    for (int p = 0; p < 2; ++p) {
      const double amp = p == 0 ? std::sqrt(1.5) : std::sqrt(0.5);
      f.field[p].resize(phi.size());
      for (std::size_t k = 0; k < phi.size(); ++k) {
        const double a = amp * std::sqrt(shape[k]);
        f.field[p][k] = {Complex(0, 0), Complex(0, 0),
                         Complex(coherent * a + a * rng.normal() * std::sqrt(0.5), a * rng.normal() * std::sqrt(0.5))};
      }
    }
  }
  UnitInput in;
  in.theta_i_rad = th;
  in.phi_i_rad = ph;
  in.pattern_count = 400;
  in.instances = inst;
  const UnitFit r = fit_unit(in);
  // 50 instances: the mean intensity fluctuates by ~1/√50 per sample; the fit averages it out.
  CHECK(r.node.m_eff == Approx(m).epsilon(0.03));
  CHECK(r.node.phi_eff == Approx(phi_c).margin(0.01));
  CHECK(r.node.pol_share == Approx(0.75).margin(0.02));
  // Coherent fraction: |c|²/(|c|² + 1) = 0.138; the statistics lobe has the same shape.
  CHECK(r.node.m_sta == Approx(m).epsilon(0.1));
  // F_sta / F_eff = s0 (same shapes) = E|mean|²/E|z|² = (c² + 1/50)/(c² + 1): the mean of 50
  // instances keeps 1/50 of the fluctuation power.
  CHECK(r.node.f_sta / r.node.f_eff == Approx((0.16 + 1.0 / 50) / 1.16).margin(0.02));
  // E = ∫ U dφ_o with U = the instance mean of the Eq. 10 density (far_field.hpp).
  double e = 0;
  for (const FarField& f : inst)
    for (std::size_t k = 0; k < 400; ++k) e += 0.5 * (f.reflectance_density(0, k) + f.reflectance_density(1, k));
  CHECK(r.energy == Approx(e / 50 * kPi / 400).epsilon(1e-12));
  // F_eff premultiplied by cos θ_i cos φ_i: F · ∫L_{F=1} = E.
  const double integral = hemisphere_lobe_integral(Lobe{r.node.m_eff, r.node.phi_eff, 0.04, 1.0}, th);
  CHECK(r.node.f_eff == Approx(r.energy / integral * 0.7 * 0.8).epsilon(1e-12));
  // The fluctuations are white across samples: l is below one lag (2/1024).
  CHECK(r.node.correlation < 2.0 / 1024);
  CHECK(r.node.correlation > 0.0);
  CHECK(r.rel_l2_eff < 0.2);
}
