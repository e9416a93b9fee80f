// Solver core of the rcwa plug-in against independent references: the closed-form Airy
// recursion of a layered film (written here, not the plug-in's code), energy conservation,
// passivity with absorbing melanin, reciprocity of an asymmetric (blazed) staircase.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "plumage/crystal_cell.hpp"

#include "slicing.hpp"
#include "solver.hpp"

using namespace plumage;
using namespace plumage::rcwa;

namespace {

struct FilmLayer {
  Complex eps;
  double d_nm;
};

// Airy recursion, reference plane at the top interface, e^{-iωt}: Γ_s of E, Γ_p of H.
std::pair<Complex, Complex> airy(const std::vector<FilmLayer>& layers, Complex eps_sub, double lambda_nm, double sin2) {
  const double k0 = 2.0 * kPi / lambda_nm;
  auto kz = [&](Complex e) {
    Complex k = std::sqrt(e - sin2);
    if (k.imag() < 0) k = -k;
    return k;
  };
  std::vector<Complex> eps = {1.0};
  for (const FilmLayer& l : layers) eps.push_back(l.eps);
  eps.push_back(eps_sub);
  Complex gs = 0, gp = 0;
  for (int j = static_cast<int>(eps.size()) - 2; j >= 0; --j) {
    const Complex ki = kz(eps[j]), kj = kz(eps[j + 1]);
    const Complex rs = (ki - kj) / (ki + kj);
    const Complex rp = (eps[j + 1] * ki - eps[j] * kj) / (eps[j + 1] * ki + eps[j] * kj);
    const Complex ph = j + 1 < static_cast<int>(eps.size()) - 1
                           ? std::exp(Complex(0, 2.0 * k0 * layers[j].d_nm) * kj) : Complex(1.0);
    gs = (rs + gs * ph) / (1.0 + rs * gs * ph);
    gp = (rp + gp * ph) / (1.0 + rp * gp * ph);
  }
  return {gs, gp};
}

// A film of full-width boxes (the general eigen path, not the homogeneous shortcut).
SlicedCell film(const std::vector<std::pair<Material, double>>& layers, double period_nm) {
  SlicedCell c;
  c.period_nm = period_nm;
  c.materials = {Material::air(), Material::keratin()};
  for (const auto& [m, d] : layers) {
    c.materials.push_back(m);
    Slice s;
    s.thickness_nm = d;
    s.boxes.push_back({0.3 * period_nm, period_nm, static_cast<int>(c.materials.size()) - 1, 1});
    c.slices.push_back(s);
  }
  assign_slice_types(c);
  return c;
}

double max_abs(const JonesReflection& a, const JonesReflection& b) {
  return std::max({std::abs(a.ss - b.ss), std::abs(a.sp - b.sp), std::abs(a.ps - b.ps), std::abs(a.pp - b.pp)});
}

}  // namespace

TEST_CASE("rcwa: a layered keratin/melanin film equals the closed-form multilayer", "[rcwa]") {
  const std::vector<std::pair<Material, double>> layers = {
      {Material::keratin(), 120.0}, {Material::melanin(), 80.0}, {Material::keratin(), 95.0}, {Material::melanin(), 80.0}};
  const SlicedCell cell = film(layers, 190.0);
  for (double lambda : {420.0, 550.0, 690.0}) {
    // ... including cos θ cos φ = 0.25 and 0.1 (near grazing, where the FDTD is continued, NOTES.md §4)
    for (auto [theta, phi] : {std::pair{0.0, 0.0}, {0.4, 0.6}, {1.1, 0.3}, {0.2, 1.3}, {std::acos(0.25), 0.0},
                              {1.0, std::acos(0.1 / std::cos(1.0))}}) {
      const EntryResult r = solve_entry(cell, lambda, theta, phi, {.harmonics = 5, .li_rule = true});
      std::vector<FilmLayer> ref;
      for (const auto& [m, d] : layers) ref.push_back({m.index(lambda) * m.index(lambda), d});
      const double ca = std::cos(theta) * std::cos(phi);
      const Complex nk = Material::keratin().index(lambda);
      const auto [gs, gp] = airy(ref, nk * nk, lambda, 1.0 - ca * ca);
      const JonesReflection expect{gs, 0.0, 0.0, gp};
      CAPTURE(lambda, theta, phi, r.jones.ss, gs, r.jones.pp, gp);
      CHECK(max_abs(r.jones, expect) < 1e-10);
    }
  }
}

TEST_CASE("rcwa: repeated palindromic runs (odd and even) between host slices equal the closed-form multilayer",
          "[rcwa]") {
  // Runs of full-width layers between host-only slices, each occurring twice, so solve_stack builds
  // them once as H ⊗ s_mid ⊗ swap(H) (odd) and H ⊗ swap(H) (even), then recurses R through them.
  const double period = 190.0;
  SlicedCell c;
  c.period_nm = period;
  c.materials = {Material::air(), Material::keratin(), Material::melanin(), Material::constant({1.9, 0.0})};
  auto layer = [&](int material, double d) {
    Slice s;
    s.thickness_nm = d;
    s.boxes.push_back({0.0, period, material, 1});
    return s;
  };
  auto host = [](double d) {
    Slice s;
    s.thickness_nm = d;
    return s;
  };
  const std::vector<Slice> odd = {layer(2, 30), layer(3, 40), layer(2, 20), layer(3, 40), layer(2, 30)};
  const std::vector<Slice> even = {layer(2, 25), layer(3, 35), layer(3, 35), layer(2, 25)};
  for (const auto& run : {odd, even, odd, even}) {
    c.slices.push_back(host(50));
    c.slices.insert(c.slices.end(), run.begin(), run.end());
  }
  c.slices.push_back(host(40));
  assign_slice_types(c);
  for (double lambda : {430.0, 610.0}) {
    for (auto [theta, phi] : {std::pair{0.0, 0.0}, {0.5, 0.7}, {1.1, 0.3}}) {
      const EntryResult r = solve_entry(c, lambda, theta, phi, {.harmonics = 4, .li_rule = true});
      std::vector<FilmLayer> ref;
      for (const Slice& s : c.slices)
        ref.push_back({std::pow(c.materials[s.boxes.empty() ? 1 : s.boxes[0].material].index(lambda), 2), s.thickness_nm});
      const double ca = std::cos(theta) * std::cos(phi);
      const Complex nk = Material::keratin().index(lambda);
      const auto [gs, gp] = airy(ref, nk * nk, lambda, 1.0 - ca * ca);
      CAPTURE(lambda, theta, phi, r.jones.ss, gs, r.jones.pp, gp);
      CHECK(max_abs(r.jones, {gs, 0.0, 0.0, gp}) < 1e-10);
    }
  }
}

TEST_CASE("rcwa: R + T = 1 for a lossless crystal, A >= 0 with melanin", "[rcwa]") {
  CrystalCell c;
  c.name = "test";
  c.a_x_nm = 190, c.a_z_nm = 164.5, c.rod_diameter_nm = 152, c.rows = 3, c.cortex_nm = 60;
  c.rod = Material::constant({1.9, 0.0});
  const SlicedCell lossless = slice_crystal(c, 6);
  for (double lambda : {400.0, 560.0}) {
    for (auto [theta, phi] : {std::pair{0.0, 0.0}, {0.5, 0.7}, {1.0, 1.2}}) {
      for (bool li : {true, false}) {
        const EntryResult r =
            solve_entry(lossless, lambda, theta, phi, {.harmonics = 8, .li_rule = li, .transmission = true});
        CAPTURE(lambda, theta, phi, li, r.reflected[0], r.transmitted[0], r.reflected[1], r.transmitted[1]);
        CHECK(std::abs(r.reflected[0] + r.transmitted[0] - 1.0) < 1e-10);
        CHECK(std::abs(r.reflected[1] + r.transmitted[1] - 1.0) < 1e-10);
      }
    }
  }
  c.rod = Material::melanin();
  c.core_diameter_nm = 90;
  const SlicedCell lossy = slice_crystal(c, 6);
  for (double lambda : {400.0, 560.0, 700.0}) {
    const EntryResult r = solve_entry(lossy, lambda, 0.5, 0.7, {.harmonics = 8, .li_rule = true, .transmission = true});
    for (int q = 0; q < 2; ++q) {
      const double absorbed = 1.0 - r.reflected[q] - r.transmitted[q];
      CAPTURE(lambda, q, absorbed);
      CHECK(absorbed > 0.0);
      CHECK(absorbed < 1.0);
    }
  }
}

TEST_CASE("rcwa: next to a Rayleigh anomaly of the host (the S-matrices' gap medium switches)", "[rcwa]") {
  // solve_stack takes the host as the gap medium unless a host order has |γ| < 0.05 (then the
  // artificial gap). At normal incidence the host's orders ±1 have γ² = ε_host − (λ/Λ)²: choose λ
  // for γ on both sides of the switch and check against the closed-form film and R + T = 1 (with
  // the host as the gap down to γ = 1e-6, R + T − 1 is 3e-10 there: the switch is needed).
  const double period = 300.0;
  const SlicedCell film_cell = film({{Material::melanin(), 80.0}, {Material::keratin(), 95.0}, {Material::melanin(), 60.0}}, period);
  CrystalCell c;
  c.name = "test";
  c.a_x_nm = period, c.a_z_nm = 164.5, c.rod_diameter_nm = 152, c.rows = 2, c.cortex_nm = 60;
  c.rod = Material::constant({1.9, 0.0});
  c.host = Material::constant({1.56, 0.0});
  const SlicedCell lossless = slice_crystal(c, 6);
  for (double gamma : {1e-6, 1e-4, 0.02, 0.049, 0.051, 0.1}) {
    double lambda = 470.0;  // λ = Λ √(Re ε_host(λ) − γ²), by fixed-point iteration (ε_host varies slowly)
    for (int k = 0; k < 50; ++k) lambda = period * std::sqrt(std::norm(Material::keratin().index(lambda)) - gamma * gamma);
    const EntryResult r = solve_entry(film_cell, lambda, 0.0, 0.0, {.harmonics = 5, .li_rule = true});
    std::vector<FilmLayer> ref = {{std::pow(Material::melanin().index(lambda), 2), 80.0},
                                  {std::pow(Material::keratin().index(lambda), 2), 95.0},
                                  {std::pow(Material::melanin().index(lambda), 2), 60.0}};
    const Complex nk = Material::keratin().index(lambda);
    const auto [gs, gp] = airy(ref, nk * nk, lambda, 0.0);
    CAPTURE(gamma, lambda, r.jones.ss, gs, r.jones.pp, gp);
    CHECK(max_abs(r.jones, {gs, 0.0, 0.0, gp}) < 1e-10);
    const double lambda_c = period * std::sqrt(1.56 * 1.56 - gamma * gamma);
    for (auto [theta, phi] : {std::pair{0.0, 0.0}, {0.0, 0.02}}) {
      const EntryResult t = solve_entry(lossless, lambda_c, theta, phi, {.harmonics = 6, .li_rule = true, .transmission = true});
      CAPTURE(lambda_c, theta, phi, t.reflected[0], t.transmitted[0], t.reflected[1], t.transmitted[1]);
      CHECK(std::abs(t.reflected[0] + t.transmitted[0] - 1.0) < 1e-10);
      CHECK(std::abs(t.reflected[1] + t.transmitted[1] - 1.0) < 1e-10);
    }
  }
}

TEST_CASE("rcwa: reciprocity of a blazed staircase (no mirror symmetry)", "[rcwa]") {
  SlicedCell c;
  c.period_nm = 300;
  c.materials = {Material::air(), Material::keratin(), Material::melanin()};
  for (int k = 0; k < 5; ++k) {
    Slice s;
    s.thickness_nm = 40;
    s.boxes.push_back({40.0 + 25.0 * k, 200.0 - 30.0 * k, 2, 1});
    c.slices.push_back(s);
  }
  assign_slice_types(c);
  for (auto [theta, phi] : {std::pair{0.3, 0.5}, {0.7, 0.2}}) {
    const SolverSettings s{.harmonics = 10, .li_rule = true};
    const JonesReflection a = solve_entry(c, 520.0, theta, phi, s).jones;
    const JonesReflection b = solve_entry(c, 520.0, -theta, -phi, s).jones;
    CAPTURE(theta, phi, a.ss, b.ss, a.pp, b.pp, a.sp, a.ps, b.sp, b.ps);
    CHECK(std::abs(a.ss - b.ss) < 1e-10);
    CHECK(std::abs(a.pp - b.pp) < 1e-10);
    CHECK(std::abs(std::abs(a.sp) - std::abs(b.ps)) < 1e-10);
    CHECK(std::abs(a.sp) > 1e-4);  // conical incidence couples s and p: the check is not vacuous
  }
}

TEST_CASE("rcwa: TM convergence in harmonics with Li's rule beats Laurent's; slices converge as 1/S^2", "[rcwa]") {
  const CrystalCell c = load_crystal_cell(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
  const SlicedCell sliced = slice_crystal(c, 6);
  auto pp = [&](int M, bool li) { return std::norm(solve_entry(sliced, 545.0, 0.3, 0.5, {M, li}).jones.pp); };
  const double li_ref = pp(20, true), laurent_ref = pp(20, false);
  const double li_err = std::abs(pp(5, true) - li_ref), laurent_err = std::abs(pp(5, false) - laurent_ref);
  std::printf("rcwa TM |r_pp|^2 at M = 5 vs M = 20: Li %.2e, Laurent %.2e\n", li_err, laurent_err);
  CHECK(li_err < 2e-5);
  CHECK(laurent_err > 5.0 * li_err);
  // Staircase: the differences between 6, 12 and 24 slices shrink by ~4 (second order).
  auto ss = [&](int S) { return std::norm(solve_entry(slice_crystal(c, S), 545.0, 0.3, 0.5, {5, true}).jones.ss); };
  const double s6 = ss(6), s12 = ss(12), s24 = ss(24);
  const double ratio = (s12 - s6) / (s24 - s12);
  std::printf("rcwa |r_ss|^2 at 6/12/24 slices: %.6f %.6f %.6f (ratio %.2f)\n", s6, s12, s24, ratio);
  CHECK(ratio > 3.0);
  CHECK(ratio < 5.5);
  CHECK(std::abs(s24 - s12) < 2e-3);
  // Richardson from 6 and 12 slices lands nearer the 48-slice value than 24 slices do.
  const double s48 = ss(48);
  const EntryResult x = solve_entry_extrapolated(slice_crystal(c, 6), slice_crystal(c, 12), 545.0, 0.3, 0.5, {5, true});
  std::printf("rcwa |r_ss|^2 Richardson(6, 12) %.6f, 48 slices %.6f\n", std::norm(x.jones.ss), s48);
  CHECK(std::abs(std::norm(x.jones.ss) - s48) < 0.5 * std::abs(s24 - s48));
}

TEST_CASE("rcwa: the other_orders power appears only where a second order propagates", "[rcwa]") {
  CrystalCell c = load_crystal_cell(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/mallard-green.yaml");
  c.a_x_nm = 300;  // a wide period: at λ = 400 nm and normal incidence λ/a_x > 1 (specular only);
  // at θ = 0, φ = 80° the order m = +1 has k_x = −sin 80° + 400/300 = 0.35 and propagates.
  const SlicedCell sliced = slice_crystal(c, 6);
  const EntryResult normal = solve_entry(sliced, 400.0, 0.0, 0.0, {5, true});
  const EntryResult oblique = solve_entry(sliced, 400.0, 0.0, deg_to_rad(80.0), {5, true});
  CHECK_FALSE(normal.has_other_orders);
  CHECK(normal.other_orders[0] == 0.0);
  CHECK(oblique.has_other_orders);
  CHECK(oblique.other_orders[0] + oblique.other_orders[1] > 1e-6);
}

TEST_CASE("rcwa: decoupled n x n modes and the reflection-only recursion equal the coupled full recursion",
          "[rcwa]") {
  // The fast path (two planar eigenproblems, R recursed upward, repeated rows reused) against the
  // 2n x 2n coupled eigenproblem with full Redheffer star products, on three cell families.
  for (const char* name : {"mallard-green", "magpie-blue", "peacock-cyan"}) {
    const CrystalCell c = load_crystal_cell(std::string(PLUMAGE_SOURCE_DIR) + "/configs/crystals/" + name + ".yaml");
    const SlicedCell sliced = slice_crystal(c, 6);
    for (auto [theta, phi] : {std::pair{0.0, 0.0}, {0.6, 0.0}, {0.0, 0.9}, {0.8, 1.1}, {1.3, 0.4}}) {
      const SolverSettings fast{.harmonics = 5, .li_rule = true};
      const SolverSettings full{.harmonics = 5, .li_rule = true, .coupled_eigenproblem = true, .transmission = true};
      const EntryResult a = solve_entry(sliced, 480.0, theta, phi, fast), b = solve_entry(sliced, 480.0, theta, phi, full);
      CAPTURE(name, theta, phi, a.jones.ss, b.jones.ss, a.jones.pp, b.jones.pp);
      CHECK(max_abs(a.jones, b.jones) < 1e-10);
      CHECK(std::abs(a.reflected[0] - b.reflected[0]) < 1e-10);
      CHECK(std::abs(a.reflected[1] - b.reflected[1]) < 1e-10);
      CHECK(std::norm(a.jones.ss) > 1e-3);
    }
  }
}
