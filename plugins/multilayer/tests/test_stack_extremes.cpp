// Extreme stacks (issue 9's stability campaign): thousands of layers, 100 µm of melanin, zero
// and sub-nanometre layers, indices from 1e-20 to 1e20, the critical angle of every medium, and
// the inputs that have no physical answer. Results must stay finite and passive, lossless
// stacks must conserve energy, the vectorised lanes must agree with the scalar recursion, and a
// refused input must be named (stack_solver.hpp, docs/validation.md §1 "Warnings (issue 9)").
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "stack_solver.hpp"

using plumage::multilayer::Complex;
using plumage::multilayer::kLanes;
using plumage::multilayer::reflect_stack;
using plumage::multilayer::reflect_stack_lanes;
using plumage::multilayer::solve_stack;
using plumage::multilayer::StackReflection;

namespace {

constexpr double kPi = 3.14159265358979323846;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

struct Stack {
  std::vector<Complex> index;  // ambient, layers, substrate
  std::vector<double> thick;
};

bool finite(Complex z) { return std::isfinite(z.real()) && std::isfinite(z.imag()); }

// The same stack in all four lanes at four angles (sin²α), against the scalar recursion.
double lanes_vs_scalar(const Stack& s, const std::array<double, kLanes>& sin2, double lambda) {
  const int layers = static_cast<int>(s.thick.size());
  std::vector<Complex> eps((layers + 2) * kLanes);
  std::vector<double> thickness(layers * kLanes), k0(kLanes, 2.0 * kPi / lambda);
  for (int l = 0; l < kLanes; ++l) {
    for (int j = 0; j < layers + 2; ++j) eps[j * kLanes + l] = s.index[j] * s.index[j];
    for (int j = 0; j < layers; ++j) thickness[j * kLanes + l] = s.thick[j];
  }
  StackReflection lanes[kLanes];
  reflect_stack_lanes(layers, eps.data(), thickness.data(), k0.data(), sin2.data(), lanes);
  double worst = 0;
  for (int l = 0; l < kLanes; ++l) {
    const auto r = reflect_stack(s.index, s.thick, lambda, sin2[l]);
    REQUIRE(finite(lanes[l].r_s));
    REQUIRE(finite(lanes[l].r_p));
    worst = std::max({worst, std::abs(lanes[l].r_s - r.r_s), std::abs(lanes[l].r_p - r.r_p)});
  }
  return worst;
}

// Checks every physical constraint on one stack at one angle; returns |R + T − 1| (lossless) or 0.
double check_physics(const Stack& s, double lambda, double sin2, bool lossless, double tol) {
  const auto r = solve_stack(s.index, s.thick, lambda, sin2);
  REQUIRE(finite(r.r_s));
  REQUIRE(finite(r.r_p));
  REQUIRE(finite(r.t_s));
  REQUIRE(finite(r.t_p));
  REQUIRE(std::isfinite(r.T_s));
  REQUIRE(std::isfinite(r.T_p));
  // Passive media: |r|² ≤ 1, T ≥ 0, R + T ≤ 1 (absorption ≥ 0), each up to `tol`.
  CHECK(r.R_s <= 1.0 + tol);
  CHECK(r.R_p <= 1.0 + tol);
  CHECK(r.T_s >= -tol);
  CHECK(r.T_p >= -tol);
  CHECK(r.R_s + r.T_s <= 1.0 + tol);
  CHECK(r.R_p + r.T_p <= 1.0 + tol);
  if (!lossless) return 0.0;
  const double e = std::max(std::abs(r.R_s + r.T_s - 1.0), std::abs(r.R_p + r.T_p - 1.0));
  CHECK(e <= tol);
  return e;
}

Stack bragg(int layers, Complex a, Complex b, double da, double db, Complex ambient, Complex substrate) {
  Stack s{{ambient}, {}};
  for (int j = 0; j < layers; ++j) {
    s.index.push_back(j % 2 ? b : a);
    s.thick.push_back(j % 2 ? db : da);
  }
  s.index.push_back(substrate);
  return s;
}

}  // namespace

TEST_CASE("thousands of lossless layers conserve energy; lanes agree", "[multilayer][extreme]") {
  // Up to 5000 layers (2.1 mm of stack): rounding grows with the layer count, measured
  // ≤ 1.5e-12 in R + T − 1 and ≤ 5e-14 lanes vs scalar at 5000.
  for (int layers : {500, 2000, 5000}) {
    const Stack s = bragg(layers, {1.8, 0.0}, {1.55, 0.0}, 75.0, 90.0, {1.0, 0.0}, {1.55, 0.0});
    double worst = 0;
    for (double sin2 : {0.0, 0.3, 0.7, 0.99}) worst = std::max(worst, check_physics(s, 550.0, sin2, true, 1e-11));
    INFO(layers << " layers: max |R + T - 1| " << worst);
    CHECK(lanes_vs_scalar(s, {0.0, 0.3, 0.7, 0.99}, 550.0) < 1e-12);
  }
}

TEST_CASE("100 um of melanin, zero and sub-nanometre layers", "[multilayer][extreme]") {
  const Complex air{1.0, 0.0}, keratin{1.55, 0.0}, melanin{1.7263, 0.0730};
  // A 100 µm melanin layer is opaque (e^{-167} round trip at 550 nm): T underflows to 0, R is
  // the keratin cortex over bulk melanin, finite at every angle including grazing.
  const Stack thick{{air, keratin, melanin, keratin, air}, {200.0, 1e5, 300.0}};
  for (double sin2 : {0.0, 0.5, 0.999999, 1.0}) {
    check_physics(thick, 550.0, sin2, false, 1e-14);
    CHECK(solve_stack(thick.index, thick.thick, 550.0, sin2).T_s < 1e-60);
  }
  // It equals the same stack on a melanin substrate (nothing comes back through 100 µm).
  const auto bulk = reflect_stack(std::vector<Complex>{air, keratin, melanin}, std::vector<double>{200.0}, 550.0, 0.3);
  const auto r = reflect_stack(thick.index, thick.thick, 550.0, 0.3);
  CHECK(std::abs(r.r_s - bulk.r_s) < 1e-14);
  CHECK(std::abs(r.r_p - bulk.r_p) < 1e-14);
  // Zero-thickness layers are no layers; 1e-6 nm layers differ from none by O(k0 d) = 1e-8.
  const std::vector<Complex> bare{air, keratin};
  const auto none = reflect_stack(bare, {}, 550.0, 0.3);
  for (double d : {0.0, 1e-6}) {
    const Stack s{{air, melanin, air, melanin, keratin}, {d, d, d}};
    const auto z = reflect_stack(s.index, s.thick, 550.0, 0.3);
    INFO("d = " << d);
    CHECK(std::abs(z.r_s - none.r_s) <= (d == 0.0 ? 1e-15 : 1e-7));
    CHECK(std::abs(z.r_p - none.r_p) <= (d == 0.0 ? 1e-15 : 1e-7));
    check_physics(s, 550.0, 0.3, false, 1e-14);
    CHECK(lanes_vs_scalar(s, {0.0, 0.3, 0.9, 1.0}, 550.0) < 1e-13);
  }
}

TEST_CASE("indices from 1e-20 to 1e20 give finite passive results", "[multilayer][extreme]") {
  // Before issue 9: NaN for |n| >= 1e100 (p polarization, ε q overflows) and for a 1e-160
  // substrate, R + T = 2.98 for an n = 1e-50 film on keratin (the Airy step at small q); now
  // |n| is limited to [1e-20, 1e20], where every product of the recursion stays in range.
  const Complex air{1.0, 0.0}, keratin{1.55, 0.0};
  double worst_lanes = 0;
  for (double e : {-20.0, -12.0, -6.0, -1.0, 1.0, 6.0, 12.0, 20.0}) {
    const double m = std::pow(10.0, e);
    // |n| = m: lossless, metal-like, purely imaginary, weakly absorbing.
    for (const Complex n : {Complex{m, 0.0}, std::polar(m, kPi / 4), Complex{0.0, m}, std::polar(m, 1e-3)}) {
      // As a film, as the substrate, and a huge next to a tiny one.
      const std::vector<Stack> stacks{
          {{air, n, keratin}, {100.0}},
          {{air, keratin, n}, {100.0}},
          {{air, n, Complex{m >= 1.0 ? 1e-20 : 1e20, 0.0}, n, air}, {10.0, 10.0, 10.0}},
      };
      for (const Stack& s : stacks) {
        const bool lossless = n.imag() == 0.0;
        for (double sin2 : {0.0, 0.25, 0.81, 1.0}) {
          INFO("n = " << n << ", sin2 = " << sin2 << ", stack of " << s.thick.size());
          check_physics(s, 550.0, sin2, lossless, 1e-10);
        }
        worst_lanes = std::max(worst_lanes, lanes_vs_scalar(s, {0.0, 0.25, 0.81, 1.0}, 550.0));
      }
    }
  }
  // Absorption far below the resolution of ε at the critical angle (|z|² underflows to 0).
  const Stack faint{{Complex{1.5, 0.0}, Complex{1.0, 1e-300}, keratin, air}, {100.0, 50.0}};
  check_physics(faint, 550.0, 1.0, false, 1e-12);
  worst_lanes = std::max(worst_lanes, lanes_vs_scalar(faint, {1.0, 0.99, 1.01, 0.5}, 550.0));
  INFO("lanes vs scalar " << worst_lanes);
  CHECK(worst_lanes < 1e-12);
}

TEST_CASE("critical angle and total internal reflection of lossless stacks", "[multilayer][extreme]") {
  // Ambient n = 1.5 over films and air substrates: sin²α at each medium's critical value ε_j
  // exactly, a few ulps either side, 1e-9 relative either side, and beyond (TIR). Before issue 9
  // the Airy step lost ε_mach/|q_j| here: |R + T − 1| up to 3.6e-7, R = 0.028 instead of 1 under
  // TIR through the 200-layer stack, lanes vs scalar 5e-8. The (1 + X, 1 − X) reduction keeps
  // full precision (measured 2.2e-14, 1.2e-14, 4.3e-14).
  const Complex glass{1.5, 0.0}, air{1.0, 0.0}, keratin{1.55, 0.0}, low{1.2, 0.0};
  const std::vector<Stack> stacks{
      {{glass, air}, {}},
      {{glass, keratin, air, keratin, air}, {100.0, 50.0, 200.0}},
      {{glass, low, air, low, air, keratin}, {80.0, 30.0, 500.0, 20.0}},
      bragg(200, air, low, 60.0, 90.0, glass, air),
  };
  double worst_energy = 0, worst_tir = 0, worst_lanes = 0;
  for (const Stack& s : stacks) {
    for (double critical : {1.0, 1.44}) {  // ε of air and of the n = 1.2 layers
      double x = critical;
      for (int k = 0; k < 4; ++x = std::nextafter(x, 0.0), ++k) {}  // start 4 ulps below
      std::vector<double> angles;
      for (int k = 0; k < 9; ++k, x = std::nextafter(x, 3.0)) angles.push_back(x);
      angles.push_back(critical * (1 - 1e-9));
      angles.push_back(critical * (1 + 1e-9));
      for (double sin2 : angles) {
        INFO("stack of " << s.thick.size() << " layers, sin2 = " << sin2);
        worst_energy = std::max(worst_energy, check_physics(s, 550.0, sin2, true, 1e-12));
        // Beyond the substrate's critical angle nothing is transmitted: |r| = 1.
        if (sin2 > std::norm(s.index.back())) {
          const auto r = solve_stack(s.index, s.thick, 550.0, sin2);
          CHECK(r.T_s == 0.0);
          worst_tir = std::max({worst_tir, std::abs(r.R_s - 1.0), std::abs(r.R_p - 1.0)});
        }
      }
      for (std::size_t a = 0; a + kLanes <= angles.size(); a += kLanes)
        worst_lanes = std::max(worst_lanes, lanes_vs_scalar(s, {angles[a], angles[a + 1], angles[a + 2], angles[a + 3]}, 550.0));
    }
    // Well inside TIR (sin²α = 2 > ε of the air substrate) R = 1 to rounding.
    if (std::norm(s.index.back()) < 2.0) {
      const auto deep = solve_stack(s.index, s.thick, 550.0, 2.0);
      CHECK(std::abs(deep.R_s - 1.0) < 1e-12);
      CHECK(std::abs(deep.R_p - 1.0) < 1e-12);
    }
  }
  INFO("max |R + T - 1| " << worst_energy << ", max |R - 1| under TIR " << worst_tir << ", lanes " << worst_lanes);
  CHECK(worst_tir <= 1e-12);
  CHECK(worst_lanes <= 1e-12);
}

TEST_CASE("inputs without a physical answer are refused, naming the medium", "[multilayer][extreme]") {
  using Catch::Contains;
  const Complex air{1.0, 0.0}, keratin{1.55, 0.0};
  auto refuse = [](std::vector<Complex> index, std::vector<double> thick, double lambda, double sin2) {
    std::string scalar_message, solve_message;
    try {
      reflect_stack(index, thick, lambda, sin2);
    } catch (const plumage::Error& e) {
      scalar_message = e.what();
    }
    try {
      solve_stack(index, thick, lambda, sin2);
    } catch (const plumage::Error& e) {
      solve_message = e.what();
    }
    CHECK(scalar_message == solve_message);
    return scalar_message;
  };
  // Gain (Im n < 0 under e^{-iωt}): before issue 9 this returned R = 18 without complaint.
  CHECK_THAT(refuse({air, Complex{1.5, -0.1}, air}, {500.0}, 550.0, 0.2), Contains("layer 1: index 1.5-0.1i is a gain medium"));
  CHECK_THAT(refuse({air, keratin, Complex{1.5, -1e-6}}, {500.0}, 550.0, 0.2), Contains("substrate: index") && Contains("gain medium"));
  // Negative, NaN and infinite thickness (NaN and inf used to give NaN, negative a plausible R).
  CHECK_THAT(refuse({air, keratin, keratin, air}, {100.0, -5.0}, 550.0, 0.2), Contains("layer 2: thickness -5 nm is negative"));
  CHECK_THAT(refuse({air, keratin, air}, {kNaN}, 550.0, 0.2), Contains("layer 1: thickness nan nm is NaN"));
  CHECK_THAT(refuse({air, keratin, air}, {kInf}, 550.0, 0.2), Contains("layer 1: thickness inf nm is infinite"));
  // Non-finite and out-of-range indices.
  CHECK_THAT(refuse({air, Complex{kNaN, 0.0}, air}, {100.0}, 550.0, 0.2), Contains("layer 1: index nan+0i is not finite"));
  CHECK_THAT(refuse({air, keratin, Complex{kInf, 0.0}}, {100.0}, 550.0, 0.2), Contains("substrate: index inf+0i is not finite"));
  CHECK_THAT(refuse({air, Complex{1e30, 0.0}, air}, {100.0}, 550.0, 0.2), Contains("layer 1: index 1e+30+0i has |n| outside [1e-20, 1e20]"));
  CHECK_THAT(refuse({air, keratin, Complex{1e-21, 0.0}}, {100.0}, 550.0, 0.2), Contains("substrate") && Contains("outside [1e-20, 1e20]"));
  // Absorbing ambient, bad wavelength or angle, wrong sizes.
  CHECK_THAT(refuse({Complex{1.0, 0.1}, keratin}, {}, 550.0, 0.2), Contains("ambient") && Contains("absorbs"));
  CHECK_THAT(refuse({air, keratin}, {}, -550.0, 0.2), Contains("wavelength -550 nm"));
  CHECK_THAT(refuse({air, keratin}, {}, kNaN, 0.2), Contains("wavelength nan nm"));
  CHECK_THAT(refuse({air, keratin}, {}, 550.0, kNaN), Contains("sin^2"));
  CHECK_THAT(refuse({air, keratin}, {}, 550.0, -0.1), Contains("sin^2"));
  CHECK_THAT(refuse({air, keratin}, {100.0}, 550.0, 0.1), Contains("2 indices for 1 layers"));

  // The lanes refuse the same inputs, naming lane and medium; valid lanes are not the problem.
  const int layers = 2;
  std::vector<Complex> eps((layers + 2) * kLanes, keratin * keratin);
  for (int l = 0; l < kLanes; ++l) eps[l] = 1.0;
  std::vector<double> thick(layers * kLanes, 100.0), k0(kLanes, 2 * kPi / 550.0), sin2(kLanes, 0.3);
  StackReflection out[kLanes];
  CHECK_NOTHROW(reflect_stack_lanes(layers, eps.data(), thick.data(), k0.data(), sin2.data(), out));
  auto lane_error = [&](auto mutate) {
    auto e = eps;
    auto t = thick;
    auto k = k0;
    auto s = sin2;
    mutate(e, t, k, s);
    try {
      reflect_stack_lanes(layers, e.data(), t.data(), k.data(), s.data(), out);
    } catch (const plumage::Error& err) {
      return std::string(err.what());
    }
    return std::string();
  };
  CHECK_THAT(lane_error([](auto& e, auto&, auto&, auto&) { e[1 * kLanes + 2] = Complex(2.25, -0.3); }),
             Contains("lane 2") && Contains("layer 1: permittivity 2.25-0.3i is a gain medium"));
  CHECK_THAT(lane_error([](auto&, auto& t, auto&, auto&) { t[1 * kLanes + 3] = -1.0; }),
             Contains("lane 3") && Contains("layer 2: thickness -1 nm is negative"));
  CHECK_THAT(lane_error([](auto&, auto& t, auto&, auto&) { t[0] = kNaN; }), Contains("lane 0") && Contains("layer 1: thickness nan nm is NaN"));
  CHECK_THAT(lane_error([](auto& e, auto&, auto&, auto&) { e[3 * kLanes + 1] = Complex(kInf, 0.0); }),
             Contains("lane 1") && Contains("substrate") && Contains("not finite"));
  CHECK_THAT(lane_error([](auto&, auto&, auto& k, auto&) { k[2] = 0.0; }), Contains("lane 2") && Contains("wavenumber 0"));
  CHECK_THAT(lane_error([](auto&, auto&, auto&, auto& s) { s[1] = kNaN; }), Contains("lane 1") && Contains("sin^2"));
}

TEST_CASE("the plug-in names the stack and wavelength of a refused profile", "[multilayer][extreme][plugin]") {
  using namespace plumage;
  PluginRegistry registry;
  registry.load_library(std::filesystem::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_multilayer.so");
  auto model = registry.create_named<LocalReflection>("multilayer", ParamView{}, registry.context());
  // A profile as a solver could build it (the config and --stack parsers refuse these already).
  LayerProfile bad;
  bad.layers = {{Material::keratin(), 300.0}, {Material::melanin(), -12.5}};
  LayerProfile good;
  good.layers = {{Material::keratin(), 300.0}, {Material::melanin(), 12.5}};
  // Scalar path (fewer than four requests) and lane path (four with the same layer count).
  for (std::size_t count : {1u, 4u}) {
    std::vector<LocalReflection::Request> requests(count, {600.0, {0.1, 0.2}, &good});
    requests.back().profile = &bad;
    std::vector<JonesReflection> out(requests.size());
    INFO(count << " requests");
    CHECK_THROWS_WITH(model->reflect(requests, out),
                      Catch::Contains("layer 2: thickness -12.5 nm is negative") && Catch::Contains("lambda = 600 nm") &&
                          Catch::Contains("stack 'air | keratin 300 | melanin -12.5 | air'"));
  }
  LayerProfile nan_layer = good;
  nan_layer.layers[0].thickness_nm = std::numeric_limits<double>::quiet_NaN();
  const LocalReflection::Request r{550.0, {}, &nan_layer};
  CHECK_THROWS_WITH(model->reflect_one(r), Catch::Contains("layer 1: thickness nan nm is NaN"));
  // A non-finite wavelength is named as such, not as the indices it makes non-finite.
  const LocalReflection::Request w{std::numeric_limits<double>::quiet_NaN(), {}, &good};
  CHECK_THROWS_WITH(model->reflect_one(w), Catch::Contains("wavelength nan nm"));
}

TEST_CASE("an unresolved interference phase is returned with multilayer.phase_precision", "[multilayer][extreme]") {
  using plumage::diagnostics;
  std::ostringstream echo;
  diagnostics().clear();
  diagnostics().set_echo(&echo);
  const Complex air{1.0, 0.0}, keratin{1.55, 0.0}, melanin{1.7263, 0.0730};
  // 100 µm and 1 m of keratin: phases 1.8e6 and 1.8e10 rad, resolved to < 1e-5 rad: no warning.
  for (double d : {1e5, 1e9}) {
    const Stack s{{air, keratin, air}, {d}};
    check_physics(s, 550.0, 0.3, true, 1e-12);
  }
  CHECK(diagnostics().empty());
  // 100 km of melanin: opaque, its phase does not matter: no warning either.
  check_physics(Stack{{air, melanin, air}, {1e14}}, 550.0, 0.3, false, 1e-12);
  CHECK(diagnostics().empty());
  // 100 km of keratin (phase 1.66e12 rad at sin²α = 0.3): still passive and energy-conserving, reported.
  const Stack far{{air, keratin, keratin, air}, {300.0, 1e14}};
  check_physics(far, 550.0, 0.3, true, 1e-12);
  CHECK(diagnostics().has("multilayer.phase_precision"));
  CHECK_THAT(echo.str(), Catch::StartsWith("warning: layer 2: one-way phase k0 d Re(q) = 1.66e+12 rad exceeds 1e+12 rad"));
  CHECK_THAT(echo.str(), Catch::EndsWith("[multilayer.phase_precision]\n"));
  // Through the lanes (which hand such phases to the scalar path) as well.
  diagnostics().clear();
  lanes_vs_scalar(far, {0.0, 0.3, 0.6, 0.9}, 550.0);
  CHECK(diagnostics().has("multilayer.phase_precision"));
  diagnostics().set_echo(&std::cerr);
  diagnostics().clear();
}
