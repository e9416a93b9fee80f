// Issue 9, stability campaign: where the approximate solver holds against the full-wave BEM as the
// top surface gets rougher and more curved, and at grazing incidence. Hidden tags (BEM runs):
// `make validate` runs them (ctest label `validation`, tests/CMakeLists.txt), writing
// solver_stability_roughness.csv / solver_stability_grazing.csv into the working directory
// (build/tests under ctest); scripts/plot_solver_stability.py draws the chart of docs/validation.md.
//
// The bodies: a 300 nm keratin film, 4 µm wide, in air, flat, curved or rough (the generator is
// validation_shape `slab` with `roughness` and `radius_um`; configs/validation/rough-film*.yaml and
// curved-film.yaml are examples), and melanin cylinders; solved by the approximate solver and by the
// bem plug-in under the same Gaussian footprint (s = W/5, so the edges stay dark). The error is the
// relative L2 distance of the unpolarised reflectance density U(φ_o) on the 400 pattern bins, the
// metric of `plumage compare`. What is asserted: wherever the solver's own criteria
// (surface_validity.hpp) stay silent the error is below the bound, on every body and every grazing
// case; where they warn it is above the bound on every grazing case and on most bodies (their mean
// above a higher bound) — the criteria are checked against the BEM, not set by fiat.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "plumage/diagnostics.hpp"
#include <iostream>
#include "plumage/far_field.hpp"
#include "plumage/pattern_metrics.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "solver/surface_validity.hpp"
#include "test_registry.hpp"

using namespace plumage;

namespace {

struct Body {
  double rms_slope = 0.0;      // nominal σ/τ of the profile
  double correlation_um = 1.0;  // τ
  double radius_um = 0.0;       // 0: flat
  int seed = 1;
  double width_um = 4.0;
  double cylinder_um = 0.0;  // > 0: a melanin cylinder of this radius instead of the film
};

constexpr double kWindowFraction = 0.2;
// A free keratin film, 300 nm: the local reflection is a thin-film interference (the paper's
// subject), exact for the flat film, and both faces are modelled by both solvers. Wavelengths 550
// and 650 nm, away from the film's reflection zero near 480 nm (where R ≈ 0.01 and whatever the
// approximation leaves out — edge diffraction — dominates the error of even the flat film: L2 0.87
// at 450 nm, φ_i = −30°, measured). A keratin cortex on melanin was tried first: its 0.8 µm stack
// makes r vary fast with angle across the narrow beam's angular spread (s = 0.8 µm), which the
// solver's one-angle-per-node local reflection misses: flat-body errors of 0.3–0.56 at φ_i = −30°,
// unrelated to roughness.
constexpr const char* kLayers = "[{material: keratin, thickness_nm: 300}]";

// A species config for the rough / curved film, written to a scratch file (load_species_config
// reads files; the committed configs/validation/rough-film*.yaml are the same bodies as examples).
std::filesystem::path write_config(const Body& b, const std::string& solver) {
  std::ostringstream y;
  y << "species: rough-film\ncommon_name: rough keratin film\n"
    << "nominal_stack:\n  layers: " << kLayers << "\n  substrate: air\n"
    << "reflection: {model: multilayer}\n"
    << "structure:\n  generator: validation_shape\n  spacing_nm: 10\n";
  if (b.cylinder_um > 0) {
    y << "  shape: circle\n  material: melanin\n  radius_nm: " << 1000.0 * b.cylinder_um << "\n";
  } else {
    y << "  shape: slab\n  width_um: " << b.width_um << "\n  stack:\n    layers: " << kLayers
      << "\n    substrate: air\n";
  }
  if (b.radius_um > 0) y << "  radius_um: " << b.radius_um << "\n";
  if (b.rms_slope > 0) {
    y << "  roughness: {rms_nm: " << 1000.0 * b.rms_slope * b.correlation_um << ", correlation_um: " << b.correlation_um
      << ", seed: " << b.seed << "}\n";
  }
  y << "solver: " << solver << "\n";
  const auto dir = std::filesystem::temp_directory_path() / "plumage-test-stability";
  std::filesystem::create_directories(dir);
  static int counter = 0;
  const auto file = dir / ("body" + std::to_string(counter++) + ".yaml");
  std::ofstream(file) << y.str();
  return file;
}

// Both solvers under the same Gaussian footprint (window_fraction = kWindowFraction).
constexpr const char* kApproximateSolver = "{type: approximate, window_fraction: 0.2}";
std::string bem_solver(int points_per_wavelength) {
  return "{type: bem, incidence: beam, window_fraction: 0.2, points_per_wavelength: " +
         std::to_string(points_per_wavelength) + "}";
}

}  // namespace

// Bound on the mean relative L2 error (λ = 550/650 nm × φ_i = 0°/−30°) inside the stated range:
// about 4× the flat film's own 0.039 (the 4 µm body's edges and the narrow beam's angular spread,
// which the windowed local reflection does not reproduce exactly).
constexpr double kHoldBound = 0.15;
// Beyond the range a warning says "unreliable", not "certainly wrong": random profiles of equal rms
// slope scatter (0.13–0.25 just past the limit), so there the statistics are asserted — most warned
// bodies (≥ 3/4) above kHoldBound and their mean above kFailBound.
constexpr double kFailBound = 0.2;

struct Flags {
  bool rough = false, curved = false, grazing = false;
  bool any() const { return rough || curved || grazing; }
};

Flags raised() {
  return {diagnostics().has("approx.rough_surface"), diagnostics().has("approx.high_curvature"),
          diagnostics().has("approx.grazing")};
}

TEST_CASE("approximate solver against BEM on rough and curved films", "[.][stability-study]") {
  const auto dirs = pattern_directions(400).phi_o_rad;
  std::vector<Body> bodies;
  for (double radius : {0.0, 16.0, 8.0, 5.0, 4.0, 3.0, 2.5}) bodies.push_back({0.0, 1.0, radius, 1});
  // Melanin cylinders (top = upper half circle, window s = 0.2 × diameter): radii toward λ.
  for (double radius : {3.0, 2.0, 1.5, 1.0, 0.6}) bodies.push_back({0.0, 1.0, 0.0, 1, 2 * radius, radius});
  for (double tau : {0.25, 0.5, 1.0}) {
    for (double slope : {0.05, 0.1, 0.2, 0.3, 0.45}) {
      for (int seed : {1, 2}) bodies.push_back({slope, tau, 0.0, seed});
    }
  }
  for (double slope : {0.05, 0.1, 0.2, 0.3, 0.45}) {
    for (int seed : {1, 2}) bodies.push_back({slope, 0.5, 4.0, seed});
  }
  const std::vector<double> phis{0.0, deg_to_rad(-30.0)};
  const std::vector<double> lambdas{550.0, 650.0};
  std::ofstream csv("solver_stability_roughness.csv");
  csv << "body,rms_slope_nominal,correlation_um,radius_um,seed,lambda_nm,phi_i_deg,rough_slope_rad,mean_radius_um,"
         "curvature_spread_rad,rel_l2,R_approx,R_bem,warn_rough,warn_curvature,warn_grazing,bem_s\n";
  diagnostics().set_echo(nullptr);  // the study raises warnings by design; collected per body below
  double worst_inside = 0.0, warned_sum = 0.0;
  int inside = 0, warned = 0, warned_above = 0;
  for (const Body& b : bodies) {
    const auto approx = load_species_config(write_config(b, kApproximateSolver), testing::registry());
    const auto bem = load_species_config(write_config(b, bem_solver(20)), testing::registry());
    const CrossSection cs = approx.structure->generate(0);
    const auto stats = detail::top_surface_statistics(cs, kWindowFraction);
    const double mean_radius_um = stats.mean_curvature_per_nm > 0 ? 1e-3 / stats.mean_curvature_per_nm : 0.0;
    const auto pb = bem.solver->prepare(cs, bem.reflection);
    double sum = 0.0;
    Flags body_flags;
    for (double lambda : lambdas) {
      diagnostics().clear();
      const auto pa = approx.solver->prepare(cs, approx.reflection);
      const auto fa = approx.solver->solve(*pa, lambda, 0.0, phis, dirs);
      const Flags f = raised();  // the solver's own verdict on this input
      body_flags.rough |= f.rough, body_flags.curved |= f.curved, body_flags.grazing |= f.grazing;
      const auto t0 = std::chrono::steady_clock::now();
      const auto fb = bem.solver->solve(*pb, lambda, 0.0, phis, dirs);
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      for (std::size_t a = 0; a < phis.size(); ++a) {
        const double e = unpolarised_relative_l2(fa[a], fb[a]);
        sum += e;
        const double dphi = kPi / 400;
        const double ra = 0.5 * (fa[a].reflected_fraction(0, dphi) + fa[a].reflected_fraction(1, dphi));
        const double rb = 0.5 * (fb[a].reflected_fraction(0, dphi) + fb[a].reflected_fraction(1, dphi));
        csv << (b.cylinder_um > 0 ? "melanin_cylinder" : "keratin_film") << ',' << b.rms_slope << ','
            << b.correlation_um << ',' << (b.cylinder_um > 0 ? b.cylinder_um : b.radius_um) << ',' << b.seed << ','
            << lambda << ',' << rad_to_deg(phis[a]) << ',' << stats.rough_slope_rad << ',' << mean_radius_um << ','
            << stats.curvature_spread_rad << ',' << e << ',' << ra << ',' << rb << ',' << f.rough << ',' << f.curved << ',' << f.grazing << ',' << secs
            << '\n';
      }
    }
    const double mean = sum / static_cast<double>(lambdas.size() * phis.size());
    std::printf("%s slope %.2f (measured %.3f) tau %.2f R %.1f um seed %d: mean rel L2 %.3f  warnings%s%s%s\n",
                b.cylinder_um > 0 ? "melanin cylinder" : "keratin film", b.rms_slope, stats.rough_slope_rad,
                b.correlation_um, b.cylinder_um > 0 ? b.cylinder_um : b.radius_um, b.seed, mean,
                body_flags.rough ? " rough" : "", body_flags.curved ? " curvature" : "",
                body_flags.grazing ? " grazing" : "");
    std::fflush(stdout);
    INFO("body slope " << b.rms_slope << " tau " << b.correlation_um << " R " << b.radius_um << " cylinder "
                       << b.cylinder_um << " seed " << b.seed << ": mean rel L2 " << mean);
    if (!body_flags.any()) {
      // Inside the stated range: the approximate solver holds, on every body.
      worst_inside = std::max(worst_inside, mean);
      ++inside;
      CHECK(mean <= kHoldBound);
    } else {
      ++warned;
      warned_sum += mean;
      warned_above += mean > kHoldBound;
    }
  }
  diagnostics().set_echo(&std::cerr);
  diagnostics().clear();
  std::printf("inside the range: %d bodies, worst mean error %.3f; warned: %d bodies, %d above %.2f, mean %.3f\n", inside,
              worst_inside, warned, warned_above, kHoldBound, warned ? warned_sum / warned : 0.0);
  CHECK(inside >= 20);
  REQUIRE(warned >= 20);
  CHECK(4 * warned_above >= 3 * warned);
  CHECK(warned_sum / warned > kFailBound);
}

TEST_CASE("approximate solver against BEM toward grazing incidence", "[.][stability-grazing]") {
  const auto dirs = pattern_directions(400).phi_o_rad;
  std::ofstream csv("solver_stability_grazing.csv");
  csv << "width_um,rms_slope_nominal,correlation_um,seed,lambda_nm,theta_i_deg,phi_i_deg,cos_local,spill,rel_l2,"
         "shape_l2,R_approx,R_bem,warn_grazing\n";
  diagnostics().set_echo(nullptr);
  int warned = 0, silent = 0;
  // Flat films of two widths (the criterion must follow the window, not the angle alone) and a
  // rough one (slope 0.1 nominal, 0.076 measured: inside the roughness range at φ_i ≤ 30°).
  for (const Body& b : {Body{0.0, 1.0, 0.0, 1, 12.0}, Body{0.0, 1.0, 0.0, 1}, Body{0.1, 1.0, 0.0, 1}}) {
    const auto approx = load_species_config(write_config(b, kApproximateSolver), testing::registry());
    const auto bem = load_species_config(write_config(b, bem_solver(20)), testing::registry());
    const CrossSection cs = approx.structure->generate(0);
    const auto stats = detail::top_surface_statistics(cs, kWindowFraction);
    const auto pa = approx.solver->prepare(cs, approx.reflection);
    const auto pb = bem.solver->prepare(cs, bem.reflection);
    const double lambda = 650.0;
    for (double theta_deg : {0.0, 60.0, 75.0, 84.0}) {
      std::vector<double> phis;
      for (double p : {0.0, -30.0, -45.0, -60.0, -75.0, -84.0}) phis.push_back(deg_to_rad(p));
      const double theta = deg_to_rad(theta_deg);
      const auto fb = bem.solver->solve(*pb, lambda, theta, phis, dirs);
      for (std::size_t a = 0; a < phis.size(); ++a) {
        diagnostics().clear();
        const double one[1] = {phis[a]};
        const auto fa = approx.solver->solve(*pa, lambda, theta, one, dirs);
        const bool flagged = diagnostics().has("approx.grazing");
        const double e = unpolarised_relative_l2(fa[0], fb[a]);
        const double dphi = kPi / 400;
        const double ra = 0.5 * (fa[0].reflected_fraction(0, dphi) + fa[0].reflected_fraction(1, dphi));
        const double rb = 0.5 * (fb[a].reflected_fraction(0, dphi) + fb[a].reflected_fraction(1, dphi));
        const double c = std::cos(theta) * std::cos(phis[a]);
        const double q = detail::horizon_spill(stats, lambda, theta, phis[a]);
        // The pattern's shape alone (each normalised to unit integral): the BEM's Φ_i of the
        // Gaussian footprint is itself approximate when the projected footprint nears λ.
        auto ua = unpolarised_density(fa[0]), ub = unpolarised_density(fb[a]);
        double sa = 0, sb = 0;
        for (std::size_t j = 0; j < ua.size(); ++j) sa += ua[j], sb += ub[j];
        for (std::size_t j = 0; j < ua.size(); ++j) ua[j] /= sa, ub[j] /= sb;
        const double shape = relative_l2(ua, ub);
        csv << b.width_um << ',' << b.rms_slope << ',' << b.correlation_um << ',' << b.seed << ',' << lambda << ','
            << theta_deg << ',' << rad_to_deg(phis[a]) << ',' << c << ',' << q << ',' << e << ',' << shape << ',' << ra
            << ',' << rb << ',' << flagged << '\n';
        std::printf("W %.0f slope %.2f theta %.0f phi %.0f cos %.3f spill %.2f: L2 %.3f shape %.3f  R %.4f / %.4f%s\n",
                    b.width_um, b.rms_slope, theta_deg, rad_to_deg(phis[a]), c, q, e, shape, ra, rb,
                    flagged ? "  [approx.grazing]" : "");
        std::fflush(stdout);
        INFO("W " << b.width_um << " slope " << b.rms_slope << " theta " << theta_deg << " phi " << rad_to_deg(phis[a])
                  << ": spill " << q << ", rel L2 " << e);
        CHECK(flagged == (q > detail::kMaxHorizonSpill));
        if (flagged) {
          ++warned;
          CHECK(e > kHoldBound);  // a warning marks a result that is really off
        } else {
          ++silent;
          CHECK(e <= kHoldBound);  // and silence one that holds
        }
      }
    }
  }
  diagnostics().set_echo(&std::cerr);
  diagnostics().clear();
  CHECK(warned >= 20);
  CHECK(silent >= 15);
}

// The statistics the criteria use, on every species' real barbules (default variant, 6
// instances): printed for docs/validation.md, which states which species sit inside the
// measured range.
TEST_CASE("top-surface statistics of the species' barbules", "[.][stability-species]") {
  for (const char* name : {"rockdove", "starling", "bronzewing", "hummingbird", "mallard", "magpie", "peacock"}) {
    const auto config = testing::species(name);
    const auto solver = config.root.child_if("solver");
    const double fraction = solver ? solver->number_or("window_fraction", 0.25) : 0.25;
    for (std::uint64_t instance = 0; instance < 6; ++instance) {
      const CrossSection cs = config.structure->generate(instance);
      const auto s = detail::top_surface_statistics(cs, fraction);
      std::printf("%-12s instance %llu: width %.1f um, rough slope %.3f rad (limit %.3f), curvature spread %.3f rad, "
                  "mean radius %.1f um\n",
                  name, static_cast<unsigned long long>(instance), cs.width_nm() / 1000.0, s.rough_slope_rad,
                  detail::max_rough_slope(s.curvature_spread_rad), s.curvature_spread_rad,
                  s.mean_curvature_per_nm > 0 ? 1e-3 / s.mean_curvature_per_nm : 0.0);
    }
  }
}

// The study's BEM runs ask for 20 points per wavelength (production: 30): checked at one rough body
// and one cylinder, both wavelengths, the two incident azimuths — the 20-vs-30 ppw difference must
// be far (≤ 1/5) below the approximate solver's error at the roughness limit (~0.1–0.15). Measured:
// ≤ 2.4e-4 on the film, 0 on the cylinder: the bodies' 10 nm vertex spacing (32–42 points per
// wavelength in keratin and melanin) is already finer than either target, so the BEM meshes the
// polygon as it is and only the film's 300 nm side walls are subdivided differently.
TEST_CASE("BEM at 20 against 30 points per wavelength on the study's bodies", "[.][stability-mesh]") {
  const auto dirs = pattern_directions(400).phi_o_rad;
  const std::vector<double> phis{0.0, deg_to_rad(-30.0)};
  double worst = 0.0;
  for (const Body& b : {Body{0.2, 0.5, 0.0, 1}, Body{0.0, 1.0, 0.0, 1, 2.0, 1.0}}) {
    const auto coarse = load_species_config(
        write_config(b, bem_solver(20)),
        testing::registry());
    const auto fine = load_species_config(
        write_config(b, bem_solver(30)),
        testing::registry());
    const CrossSection cs = coarse.structure->generate(0);
    const auto pc = coarse.solver->prepare(cs, coarse.reflection);
    const auto pf = fine.solver->prepare(cs, fine.reflection);
    for (double lambda : {550.0, 650.0}) {
      const auto fc = coarse.solver->solve(*pc, lambda, 0.0, phis, dirs);
      const auto ff = fine.solver->solve(*pf, lambda, 0.0, phis, dirs);
      for (std::size_t a = 0; a < phis.size(); ++a) {
        const double e = unpolarised_relative_l2(fc[a], ff[a]);
        std::printf("%s, %.0f nm, phi_i %.0f: BEM 20 vs 30 ppw relative L2 %.2e\n",
                    b.cylinder_um > 0 ? "melanin cylinder 1 um" : "rough film slope 0.2 tau 0.5", lambda,
                    rad_to_deg(phis[a]), e);
        worst = std::max(worst, e);
      }
    }
  }
  CHECK(worst <= 0.02);
}
