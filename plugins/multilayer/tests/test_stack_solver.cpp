// The multilayer recursion against closed forms (Fresnel, Airy sum, quarter-wave stack) and
// against the physics it must respect (energy conservation, passivity, finiteness).
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "plumage/simd_math.hpp"
#include "stack_solver.hpp"

using plumage::multilayer::Complex;
using plumage::multilayer::reflect_stack;
using plumage::multilayer::solve_stack;

namespace {

constexpr double kPi = 3.14159265358979323846;

// cos θ_j from Snell's law, written independently of the solver (n_0 sin θ_0 = n_j sin θ_j).
Complex snell_cos(Complex n0, double theta0, Complex nj) {
  const Complex s = n0 * std::sin(theta0) / nj;
  Complex c = std::sqrt(1.0 - s * s);
  if ((nj * c).imag() < 0) c = -c;
  return c;
}

// Textbook Fresnel coefficients: s for E, p for H (tangential-H convention).
Complex fresnel_s(Complex ni, Complex ci, Complex nj, Complex cj) {
  return (ni * ci - nj * cj) / (ni * ci + nj * cj);
}
Complex fresnel_p(Complex ni, Complex ci, Complex nj, Complex cj) {
  return (nj * ci - ni * cj) / (nj * ci + ni * cj);
}

}  // namespace

TEST_CASE("single interface equals the Fresnel equations", "[multilayer]") {
  const Complex n0{1.0, 0.0};
  for (Complex n1 : {Complex{1.56, 0.0}, Complex{1.73, 0.07}, Complex{2.5, 0.4}}) {
    for (double deg : {0.0, 15.0, 45.0, 60.0, 80.0, 89.0}) {
      const double th = deg * kPi / 180.0;
      const double sin2 = std::sin(th) * std::sin(th);
      std::vector<Complex> index{n0, n1};
      const auto r = reflect_stack(index, {}, 550.0, sin2);
      const Complex c0 = std::cos(th), c1 = snell_cos(n0, th, n1);
      CHECK(std::abs(r.r_s - fresnel_s(n0, c0, n1, c1)) < 1e-13);
      CHECK(std::abs(r.r_p - fresnel_p(n0, c0, n1, c1)) < 1e-13);
    }
  }
  // Sign sanity of the spec: air -> n = 1.5 at normal incidence, r_s = -0.2 (E), r_p = +0.2 (H).
  std::vector<Complex> glass{Complex{1.0, 0}, Complex{1.5, 0}};
  const auto r = reflect_stack(glass, {}, 500.0, 0.0);
  CHECK(r.r_s.real() == Approx(-0.2).margin(1e-15));
  CHECK(r.r_p.real() == Approx(0.2).margin(1e-15));
}

TEST_CASE("single film equals the closed-form Airy sum to 1e-12", "[multilayer]") {
  const Complex n0{1.0, 0.0}, n2{1.0, 0.0};
  for (Complex n1 : {Complex{1.55, 0.0}, Complex{1.75, 0.1}}) {
    for (double d : {50.0, 300.0, 1234.5}) {
      for (double deg : {0.0, 30.0, 70.0}) {
        for (double lambda : {400.0, 550.0, 700.0}) {
          const double th = deg * kPi / 180.0;
          const Complex c0 = std::cos(th), c1 = snell_cos(n0, th, n1), c2 = snell_cos(n0, th, n2);
          const Complex phase = std::exp(Complex(0, 2) * (2 * kPi / lambda) * n1 * c1 * d);
          // Airy: r = r01 + t01 t10 r12 e^{2iδ} / (1 − r10 r12 e^{2iδ}).
          auto airy = [&](auto fresnel) {
            const Complex r01 = fresnel(n0, c0, n1, c1), r10 = fresnel(n1, c1, n0, c0);
            const Complex r12 = fresnel(n1, c1, n2, c2);
            const Complex t01 = 1.0 + r01, t10 = 1.0 + r10;
            return r01 + t01 * t10 * r12 * phase / (1.0 - r10 * r12 * phase);
          };
          std::vector<Complex> index{n0, n1, n2};
          std::vector<double> thick{d};
          const auto r = reflect_stack(index, thick, lambda, std::sin(th) * std::sin(th));
          CHECK(std::abs(r.r_s - airy(fresnel_s)) < 1e-12);
          CHECK(std::abs(r.r_p - airy(fresnel_p)) < 1e-12);
        }
      }
    }
  }
}

TEST_CASE("lossless stacks conserve energy to 1e-12; absorbing ones absorb", "[multilayer]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> n(1.0, 2.4), d(10.0, 400.0), th(0.0, 1.55);
  for (int trial = 0; trial < 200; ++trial) {
    const int layers = 1 + trial % 25;
    std::vector<Complex> index{Complex{1.0, 0.0}};
    std::vector<double> thick;
    for (int j = 0; j < layers; ++j) {
      index.push_back({n(rng), 0.0});
      thick.push_back(d(rng));
    }
    index.push_back({trial % 2 ? 1.0 : 1.5, 0.0});
    const double t = th(rng);
    const auto s = solve_stack(index, thick, 550.0, std::sin(t) * std::sin(t));
    CHECK(std::abs(s.R_s + s.T_s - 1.0) < 1e-12);
    CHECK(std::abs(s.R_p + s.T_p - 1.0) < 1e-12);
    // The same stack with melanin-like absorption in every second layer: A = 1 − R − T > 0.
    for (std::size_t j = 1; j + 1 < index.size(); j += 2) index[j] += Complex(0.0, 0.05);
    const auto a = solve_stack(index, thick, 550.0, std::sin(t) * std::sin(t));
    CHECK(1.0 - a.R_s - a.T_s >= 0.0);
    CHECK(1.0 - a.R_p - a.T_p >= 0.0);
    CHECK(a.R_s <= 1.0);
    CHECK(a.R_p <= 1.0);
  }
}

TEST_CASE("quarter-wave stack: peak wavelength and reflectance match the closed form", "[multilayer]") {
  const double nH = 2.0, nL = 1.5, ns = 1.5, lambda0 = 550.0;
  const int pairs = 8;
  std::vector<Complex> index{Complex{1.0, 0.0}};
  std::vector<double> thick;
  for (int p = 0; p < pairs; ++p) {
    index.push_back({nH, 0});
    thick.push_back(lambda0 / (4 * nH));
    index.push_back({nL, 0});
    thick.push_back(lambda0 / (4 * nL));
  }
  index.push_back({ns, 0});
  // Admittance of (HL)^N on the substrate: Y = (nH/nL)^{2N} ns, R = ((1 − Y)/(1 + Y))².
  const double Y = std::pow(nH / nL, 2 * pairs) * ns;
  const double R_closed = std::pow((1 - Y) / (1 + Y), 2);
  const auto peak = solve_stack(index, thick, lambda0, 0.0);
  CHECK(std::abs(peak.R_s - R_closed) < 1e-12);
  CHECK(std::abs(peak.R_p - R_closed) < 1e-12);
  // The maximum over a fine scan sits at λ0.
  double best_lambda = 0, best_R = -1;
  for (double l = 500.0; l <= 600.0; l += 0.01) {
    const double R = solve_stack(index, thick, l, 0.0).R_s;
    if (R > best_R) best_R = R, best_lambda = l;
  }
  CHECK(std::abs(best_lambda - lambda0) <= 0.01);
}

TEST_CASE("200 layers of 1 um melanin stay finite, also at grazing and under TIR", "[multilayer]") {
  const Complex melanin{1.7263, 0.0730};  // Eq. 1 at 550 nm
  for (Complex ambient : {Complex{1.0, 0.0}, Complex{1.6, 0.0}}) {
    std::vector<Complex> index{ambient};
    std::vector<double> thick;
    for (int j = 0; j < 200; ++j) {
      index.push_back(j % 2 ? melanin : Complex{1.0, 0.0});
      thick.push_back(1000.0);
    }
    index.push_back({1.0, 0.0});
    for (double deg : {0.0, 45.0, 80.0, 89.9, 89.9999, 90.0}) {
      const double s = ambient.real() * std::sin(deg * kPi / 180.0);
      for (double lambda : {400.0, 550.0, 700.0}) {
        const auto r = solve_stack(index, thick, lambda, s * s);
        INFO("ambient " << ambient << " angle " << deg << " lambda " << lambda);
        REQUIRE(std::isfinite(r.r_s.real()));
        REQUIRE(std::isfinite(r.r_s.imag()));
        REQUIRE(std::isfinite(r.r_p.real()));
        REQUIRE(std::isfinite(r.r_p.imag()));
        REQUIRE(std::isfinite(r.t_s.real()));
        REQUIRE(std::isfinite(r.t_p.real()));
        CHECK(r.R_s <= 1.0 + 1e-12);
        CHECK(r.R_p <= 1.0 + 1e-12);
        CHECK(r.T_s == Approx(0.0).margin(1e-12));  // 100 µm of melanin is opaque
      }
    }
  }
  // Total internal reflection at a lossless interface: |r| = 1 exactly.
  std::vector<Complex> tir{Complex{1.5, 0.0}, Complex{1.0, 0.0}};
  const double s = 1.5 * std::sin(60.0 * kPi / 180.0);
  const auto r = solve_stack(tir, {}, 550.0, s * s);
  CHECK(std::abs(std::abs(r.r_s) - 1.0) < 1e-14);
  CHECK(std::abs(std::abs(r.r_p) - 1.0) < 1e-14);
  CHECK(r.T_s == 0.0);
  // Grazing incidence on any stack reflects everything: r = −1 for both polarizations.
  std::vector<Complex> film{Complex{1.0, 0}, Complex{1.55, 0}, Complex{1.0, 0}};
  std::vector<double> d{300.0};
  const auto g = reflect_stack(film, d, 550.0, 1.0);
  CHECK(std::abs(g.r_s - Complex(-1.0, 0.0)) < 1e-12);
  CHECK(std::abs(g.r_p - Complex(-1.0, 0.0)) < 1e-12);
}

TEST_CASE("lane sincos and exp agree with the C library to 2 ulp", "[multilayer][lanes]") {
  namespace simd = plumage::simd;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_sin = 0, worst_cos = 0, worst_exp = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = u(rng) * std::pow(10.0, (i % 6) - 1);  // |x| up to 1e4
    simd::v4d s, c;
    simd::sincos(simd::splat(x), s, c);
    worst_sin = std::max(worst_sin, std::abs(s[0] - std::sin(x)));
    worst_cos = std::max(worst_cos, std::abs(c[0] - std::cos(x)));
    const double y = -std::abs(x) * 0.07;  // down to −700
    worst_exp = std::max(worst_exp, std::abs(simd::exp_nonpositive(simd::splat(y))[0] - std::exp(y)) / std::exp(y));
  }
  CHECK(worst_sin <= 4.5e-16);
  CHECK(worst_cos <= 4.5e-16);
  CHECK(worst_exp <= 4.5e-16);
  CHECK(simd::exp_nonpositive(simd::splat(-800.0))[0] == 0.0);
}

TEST_CASE("the vectorised lanes equal the scalar recursion", "[multilayer][lanes]") {
  using plumage::multilayer::kLanes;
  using plumage::multilayer::reflect_stack_lanes;
  using plumage::multilayer::StackReflection;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> n(1.0, 2.0), k(0.0, 0.2), d(5.0, 2000.0), s(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int layers = trial % 40;
    std::vector<std::vector<Complex>> index(kLanes);
    std::vector<std::vector<double>> thick(kLanes);
    std::vector<Complex> eps((layers + 2) * kLanes);
    std::vector<double> thickness(layers * kLanes), k0(kLanes), sin2(kLanes);
    for (int l = 0; l < kLanes; ++l) {
      index[l].push_back({1.0, 0.0});
      for (int j = 0; j < layers; ++j) {
        index[l].push_back({n(rng), trial % 2 ? k(rng) : 0.0});
        thick[l].push_back(trial == 7 ? 5e6 : d(rng));  // trial 7: beyond the lane reduction range
      }
      index[l].push_back({trial % 3 ? 1.0 : 1.5, 0.0});
      for (int j = 0; j < layers + 2; ++j) eps[j * kLanes + l] = index[l][j] * index[l][j];
      for (int j = 0; j < layers; ++j) thickness[j * kLanes + l] = thick[l][j];
      // Include normal and exactly grazing incidence among random angles.
      sin2[l] = l == 0 ? 0.0 : (l == 1 && trial % 5 == 0 ? 1.0 : s(rng));
      k0[l] = 2.0 * kPi / (400.0 + trial);
    }
    StackReflection lanes[kLanes];
    reflect_stack_lanes(layers, eps.data(), thickness.data(), k0.data(), sin2.data(), lanes);
    for (int l = 0; l < kLanes; ++l) {
      const auto r = reflect_stack(index[l], thick[l], 2.0 * kPi / k0[l], sin2[l]);
      INFO("trial " << trial << " lane " << l);
      CHECK(std::abs(lanes[l].r_s - r.r_s) < 1e-13);
      CHECK(std::abs(lanes[l].r_p - r.r_p) < 1e-13);
    }
  }
}
