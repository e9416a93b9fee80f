// BEM solver vs independent references (spec wave-simulation.md §6.11, issue 6 acceptance):
// exact cylinder series (reference/), optical theorem, Poynting flux, reciprocity, θ_i = 0
// decoupling. Tests tagged [validation] are the long ones (ctest label `validation`).
#include <catch2/catch.hpp>
#include <cstdio>

#include "bem_test_support.hpp"

using namespace plumage;
using namespace plumage::bem;
using namespace plumage::bem::testing;

namespace {

constexpr double kProductionPpw = 30.0;  // BemOptions default; NOTES.md §4 (convergence table)

struct CylinderCase {
  const char* name;
  std::vector<double> radii;  // nm, inner → outer
  std::vector<Material> mats;
};

std::vector<CylinderCase> acceptance_cases(bool large) {
  if (large) {
    return {{"keratin 250 + melanin shell 100", {250.0, 350.0}, {Material::keratin(), Material::melanin()}},
            {"keratin r=1000", {1000.0}, {Material::keratin()}}};
  }
  return {{"keratin r=250", {250.0}, {Material::keratin()}}, {"melanin r=100", {100.0}, {Material::melanin()}}};
}

oracle::CylinderSolution series(const CylinderCase& c, double lambda, double theta, int pol) {
  std::vector<double> r;
  std::vector<std::complex<double>> m;
  for (std::size_t k = 0; k < c.radii.size(); ++k) {
    r.push_back(c.radii[k] / 1000.0);
    m.push_back(c.mats[k].index(lambda));
  }
  return r.size() == 1 ? oracle::solve_homogeneous_bh(r[0], m[0], lambda / 1000.0, theta, pol + 1)
                       : oracle::solve_layered(r, m, lambda / 1000.0, theta, pol + 1);
}

void run_acceptance(bool large) {
  BemOptions opt;
  REQUIRE(opt.points_per_wavelength == kProductionPpw);
  const auto phi_o = full_circle(360);
  const double phi_i = 0.4;
  double worst = 0.0;
  for (const auto& c : acceptance_cases(large)) {
    for (double lambda : {400.0, 550.0, 700.0}) {
      for (double theta_deg : {0.0, 30.0}) {
        const double theta = deg_to_rad(theta_deg);
        const auto cs = layered_cylinder(c.radii, c.mats, lambda, opt.points_per_wavelength);
        const auto res = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, opt);
        for (int pol = 0; pol < 2; ++pol) {
          const auto cmp = compare_with_series(res.field, pol, series(c, lambda, theta, pol), phi_i, phi_o);
          std::printf("  %-32s lambda %3.0f theta %2.0f pol %d: N = %5d  intensity L2 %.2e  field L2 %.2e\n", c.name,
                      lambda, theta_deg, pol + 1, res.sys->mesh.unknowns(), cmp.intensity_l2, cmp.field_l2);
          INFO(c.name << " lambda " << lambda << " theta " << theta_deg << " pol " << pol + 1);
          CHECK(cmp.intensity_l2 <= 1e-3);
          worst = std::max(worst, cmp.intensity_l2);
        }
      }
    }
  }
  std::printf("  worst intensity L2: %.2e\n", worst);
}

// Optical theorem (extinction width from the forward far field), scattering width (far field over
// the full circle) and absorption width (Poynting flux of the boundary currents), all over |S_i|.
struct EnergyBudget {
  double ext, sca, abs;
};
EnergyBudget energy(const PlaneWaveResult& r, int pol, double theta, double phi_i, const std::vector<double>& phi_o) {
  const double k0 = r.sys->k0, g0 = k0 * std::cos(theta);
  // forward direction φ_o = φ_i + π: T_co(0) = 𝓔·e_p / (sqrt(2/(πγ0)) e^{3iπ/4}), C_ext = (4/k0) Re T_co(0)
  const std::vector<double> fwd{phi_i + std::numbers::pi};
  const Eigen::MatrixXcd F = far_field_operator(r.sys->mesh, k0, theta, fwd) * r.x.col(pol);
  const auto e = incident_polarization(pol, {theta, phi_i}).e;  // = the forward outgoing basis vector
  const std::complex<double> proj = F(0) * e[0] + F(1) * e[1] + F(2) * e[2];
  const std::complex<double> t = proj / (std::sqrt(2.0 / (std::numbers::pi * g0)) *
                                         std::polar(1.0, 0.75 * std::numbers::pi));
  EnergyBudget b{};
  b.ext = 4.0 / k0 * t.real();
  double sum = 0.0;
  for (std::size_t d = 0; d < phi_o.size(); ++d) {
    for (int c = 0; c < 3; ++c) sum += std::norm(r.field(3 * d + c, pol));
  }
  b.sca = std::cos(theta) * sum * 2.0 * std::numbers::pi / phi_o.size();
  b.abs = absorption_width(r.sys->mesh, r.x.col(pol));
  return b;
}

}  // namespace

TEST_CASE("bem: cylinders vs exact series at the production mesh (keratin r = 250, melanin r = 100)") {
  run_acceptance(false);
}

TEST_CASE("bem: coated cylinder and keratin r = 1 um vs exact series at the production mesh", "[validation]") {
  run_acceptance(true);
}

TEST_CASE("bem: convergence order vs the series (keratin r = 250 nm, coated, 550 nm, theta 30)") {
  const auto phi_o = full_circle(360);
  const double theta = deg_to_rad(30.0), phi_i = 0.4, lambda = 550.0;
  for (const auto& c : {CylinderCase{"keratin r=250", {250.0}, {Material::keratin()}},
                        CylinderCase{"coated", {250.0, 350.0}, {Material::keratin(), Material::melanin()}}}) {
    std::vector<double> err;
    const std::vector<double> ppws{8.0, 16.0, 32.0};
    for (double ppw : ppws) {
      BemOptions opt;
      opt.points_per_wavelength = ppw;
      const auto res = solve_plane_wave(layered_cylinder(c.radii, c.mats, lambda, ppw, 12), lambda, theta, phi_i, phi_o, opt);
      double e = 0.0;
      for (int pol = 0; pol < 2; ++pol) {
        e = std::max(e, compare_with_series(res.field, pol, series(c, lambda, theta, pol), phi_i, phi_o).intensity_l2);
      }
      err.push_back(e);
      std::printf("  %s ppw %4.0f: N = %5d  max intensity L2 %.3e\n", c.name, ppw, res.sys->mesh.unknowns(), e);
    }
    const double p1 = std::log2(err[0] / err[1]), p2 = std::log2(err[1] / err[2]);
    std::printf("  %s observed order: %.2f, %.2f\n", c.name, p1, p2);
    CHECK(p1 > 1.8);
    CHECK(p2 > 1.8);
  }
}

TEST_CASE("bem: theta_i = 0 decouples into TM_z (J_z, M_t) and TE_z (J_t, M_z)") {
  const double lambda = 550.0;
  const auto cs = layered_cylinder({250.0, 350.0}, {Material::keratin(), Material::melanin()}, lambda, 15.0);
  BemOptions opt;
  opt.points_per_wavelength = 15.0;
  const auto phi_o = full_circle(72);
  const auto res = solve_plane_wave(cs, lambda, 0.0, 0.3, phi_o, opt);
  const Mesh& m = res.sys->mesh;
  // TM_z: pol 1 (E along the axis) excites only J_z, M_t; TE_z: pol 2 only J_t, M_z.
  double tm_leak = 0, tm_norm = 0, te_leak = 0, te_norm = 0;
  for (int v = 0; v < m.n_t; ++v) {
    tm_leak = std::max({tm_leak, std::abs(res.x(m.jt(v), 0))});
    tm_norm = std::max({tm_norm, std::abs(res.x(m.mt(v), 0))});
    te_norm = std::max({te_norm, std::abs(res.x(m.jt(v), 1))});
    te_leak = std::max({te_leak, std::abs(res.x(m.mt(v), 1))});
  }
  for (int z = 0; z < m.n_z; ++z) {
    tm_leak = std::max({tm_leak, std::abs(res.x(m.mz(z), 0))});
    tm_norm = std::max({tm_norm, std::abs(res.x(m.jz(z), 0))});
    te_leak = std::max({te_leak, std::abs(res.x(m.jz(z), 1))});
    te_norm = std::max({te_norm, std::abs(res.x(m.mz(z), 1))});
  }
  std::printf("  theta 0: TM leak %.1e of %.2f, TE leak %.1e of %.2f\n", tm_leak, tm_norm, te_leak, te_norm);
  CHECK(tm_leak <= 1e-12 * tm_norm);
  CHECK(te_leak <= 1e-12 * te_norm);
  CHECK(tm_norm > 0.1);
  CHECK(te_norm > 0.1);
  // and the far field of pol 1 is purely axial (E ∥ ŷ), pol 2 purely in-plane
  double ax2 = 0, tot2 = 0;
  for (std::size_t d = 0; d < phi_o.size(); ++d) {
    ax2 += std::norm(res.field(3 * d + 0, 0)) + std::norm(res.field(3 * d + 2, 0)) + std::norm(res.field(3 * d + 1, 1));
    tot2 += std::norm(res.field(3 * d + 1, 0)) + std::norm(res.field(3 * d, 1)) + std::norm(res.field(3 * d + 2, 1));
  }
  CHECK(ax2 <= 1e-24 * tot2);
}

TEST_CASE("bem: energy budget (optical theorem vs far field vs boundary flux)") {
  const auto phi_o = full_circle(360);  // trapezoid on the circle: exact for the ≲ 40 harmonics present
  const double phi_i = 0.4, lambda = 550.0;
  SECTION("lossless cylinder n = 1.55, theta 30: extinction = scattering within 1e-4, no absorption") {
    const double theta = deg_to_rad(30.0);
    BemOptions opt;
    const auto res = solve_plane_wave(layered_cylinder({300.0}, {Material::constant(1.55)}, lambda, opt.points_per_wavelength),
                                      lambda, theta, phi_i, phi_o, opt);
    for (int pol = 0; pol < 2; ++pol) {
      const auto b = energy(res, pol, theta, phi_i, phi_o);
      std::printf("  lossless pol %d: C_ext %.6f nm, C_sca %.6f nm, C_abs %.2e nm, |ext - sca - abs|/ext %.2e\n", pol + 1,
                  b.ext, b.sca, b.abs, std::abs(b.ext - b.sca - b.abs) / b.ext);
      CHECK(std::abs(b.ext - b.sca) <= 1e-4 * b.ext);
      // The boundary-flux absorption is a near-field quantity of the tent-interpolated currents
      // (O(h²), observed 6.0e-5 of C_ext at 30 ppw, 1.1e-4 at 25): a consistency check, not the energy criterion.
      CHECK(std::abs(b.abs) <= 5e-4 * b.ext);
    }
  }
  SECTION("absorbing coated cylinder, theta 30: ext = sca + abs within 1e-4; abs vs series") {
    const double theta = deg_to_rad(30.0);
    BemOptions opt;
    const auto res = solve_plane_wave(
        layered_cylinder({250.0, 350.0}, {Material::keratin(), Material::melanin()}, lambda, opt.points_per_wavelength),
        lambda, theta, phi_i, phi_o, opt);
    for (int pol = 0; pol < 2; ++pol) {
      const auto b = energy(res, pol, theta, phi_i, phi_o);
      const auto s = oracle::solve_layered({0.25, 0.35}, {Material::keratin().index(lambda), Material::melanin().index(lambda)},
                                           lambda / 1000.0, theta, pol + 1);
      const double abs_series = s.q_abs * 2.0 * 350.0;  // efficiency per diameter → width in nm
      std::printf("  absorbing pol %d: C_ext %.5f, C_sca %.5f, C_abs %.5f (series %.5f), |ext - sca - abs|/ext %.2e\n",
                  pol + 1, b.ext, b.sca, b.abs, abs_series, std::abs(b.ext - b.sca - b.abs) / b.ext);
      CHECK(std::abs(b.ext - b.sca - b.abs) <= 1e-4 * b.ext);
      CHECK(std::abs(b.abs - abs_series) <= 1e-3 * abs_series);
    }
  }
  SECTION("lossless body with junctions (three regions touching), theta 20") {
    const double theta = deg_to_rad(20.0);
    BemOptions opt;
    const auto res = solve_plane_wave(junction_body(), lambda, theta, phi_i, phi_o, opt);
    for (int pol = 0; pol < 2; ++pol) {
      const auto b = energy(res, pol, theta, phi_i, phi_o);
      std::printf("  junction body pol %d: C_ext %.6f, C_sca %.6f, C_abs %.2e, |ext - sca|/ext %.2e\n", pol + 1, b.ext,
                  b.sca, b.abs, std::abs(b.ext - b.sca) / b.ext);
      CHECK(std::abs(b.ext - b.sca) <= 1e-4 * b.ext);
      // Boundary flux near the corners (field singularities of dielectric wedges): observed
      // 5.1e-4 and 1.5e-3 of C_ext at 30 ppw (1.3e-3, 3.4e-3 at 25); reported, checked loosely.
      CHECK(std::abs(b.abs) <= 5e-3 * b.ext);
    }
  }
}

TEST_CASE("bem: reciprocity on the specular cone (junction body, absorbing coated cylinder off centre)") {
  // e_b(−θ, φ_o)·𝓔_a(θ, φ_i → φ_o) = e_a(θ, φ_i)·𝓔_b(−θ, φ_o → φ_i)   (spec §6.11.6)
  const double lambda = 500.0, theta = deg_to_rad(25.0);
  const double phi_a = 0.3, phi_b = -1.9;
  auto check_body = [&](const CrossSection& cs, const char* name) {
    BemOptions opt;
    const std::vector<double> to_b{phi_b}, to_a{phi_a};
    const auto ra = solve_plane_wave(cs, lambda, theta, phi_a, to_b, opt);
    const auto rb = solve_plane_wave(cs, lambda, -theta, phi_b, to_a, opt);
    double worst = 0, scale = 0;
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        const auto eb = incident_polarization(b, {-theta, phi_b}).e;
        const auto ea = incident_polarization(a, {theta, phi_a}).e;
        std::complex<double> lhs = 0, rhs = 0;
        for (int c = 0; c < 3; ++c) {
          lhs += eb[c] * ra.field(c, a);
          rhs += ea[c] * rb.field(c, b);
        }
        worst = std::max(worst, std::abs(lhs - rhs));
        scale = std::max(scale, std::abs(lhs));
      }
    }
    std::printf("  reciprocity %s: max |lhs - rhs| / max |lhs| = %.2e\n", name, worst / scale);
    CHECK(worst <= 1e-12 * scale);  // the symmetric Galerkin assembly makes the discrete system reciprocal
  };
  check_body(junction_body(), "junction body");
  auto coated = layered_cylinder({200.0, 300.0}, {Material::keratin(), Material::melanin()}, lambda, 25.0);
  for (auto& reg : coated.regions) {
    for (auto& p : reg.outline) p.x += 120.0, p.z -= 60.0;
  }
  check_body(coated, "shifted coated cylinder");
}

TEST_CASE("bem: preconditioned GMRES (tolerance 1e-8) reproduces the LU solution (coated cylinder, junction body)") {
  const double lambda = 500.0, theta = deg_to_rad(30.0);
  const std::vector<double> phi_o = full_circle(90);
  auto run = [&](const CrossSection& cs, const char* name) {
    BemOptions dense, iterative;
    dense.points_per_wavelength = iterative.points_per_wavelength = 20.0;
    iterative.method = BemOptions::Method::gmres;
    const auto prep = prepare_geometry(cs);
    const auto a = build_system(prep->geometry, lambda, theta, dense);
    const auto b = build_system(prep->geometry, lambda, theta, iterative);
    const int n = a->mesh.unknowns();
    Eigen::MatrixXcd B(n, 2);
    for (int pol = 0; pol < 2; ++pol) fill_rhs(a->mesh, a->k0, plane_wave(theta, 0.7, pol), B.col(pol));
    std::vector<int> its;
    const Eigen::MatrixXcd xa = a->solve(B, dense), xb = b->solve(B, iterative, &its);
    const double diff = (xa - xb).norm() / xa.norm();
    std::printf("  GMRES %s: N = %d, iterations %d / %d, |x_gmres - x_lu| / |x_lu| = %.1e\n", name, n, its[0], its[1], diff);
    CHECK(diff <= 1e-5);
    CHECK(its[0] < 500);
  };
  // Near-field-LU preconditioner (default). Unpreconditioned, the junction body stagnates at a
  // residual of 4e-4 after 5000 iterations (NOTES.md §5).
  run(layered_cylinder({250.0, 350.0}, {Material::keratin(), Material::melanin()}, lambda, 20.0), "coated cylinder");
  run(junction_body(), "junction body");
}
