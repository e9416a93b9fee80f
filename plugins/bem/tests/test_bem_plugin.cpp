// The "bem" plug-in through the registry, as a species config selects it (`solver: {type: bem}`):
//  * a flat keratin film (validation_shape slab) under the Gaussian beam reproduces the multilayer
//    plug-in's |r|² (spec §6.11 item 3), the beam's angular spectrum weighted exactly;
//  * a keratin cylinder under a plane wave gives the 2D differential scattering width of the series;
//  * the plug-in documents the solver's parameter table and registers its benchmark, whose solver
//    options go through that table.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>

#include "bem_test_support.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/config_document.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;

namespace {

std::filesystem::path config_path(const std::string& name) {
  return std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs" / "validation" / (name + ".yaml");
}

// Exact reflectance of the infinite planar stack for the beam: every plane-wave component α_q
// reflects with the multilayer's Jones matrix, powers add (components are orthogonal in k_x).
double beam_reflectance_reference(const SpeciesConfig& cfg, const bem::IncidentField& beam, double lambda) {
  double num = 0.0, den = 0.0;
  for (std::size_t q = 0; q < beam.alpha.size(); ++q) {
    const IncidentDirection inc{beam.theta, beam.alpha[q]};
    const auto pol = incident_polarization(beam.pol, inc);
    const Direction w = direction_from_angles(inc.theta_rad, inc.phi_rad);
    // ŝ = ω_i × ẑ / |…|
    std::array<double, 3> s{w.y, -w.x, 0.0};
    const double sl = std::hypot(s[0], s[1]);
    s = sl < 1e-4 ? std::array<double, 3>{0.0, 1.0, 0.0} : std::array<double, 3>{s[0] / sl, s[1] / sl, 0.0};
    const double ce = pol.e[0] * s[0] + pol.e[1] * s[1] + pol.e[2] * s[2];
    const double ch = pol.eta0_h[0] * s[0] + pol.eta0_h[1] * s[1] + pol.eta0_h[2] * s[2];
    LocalReflection::Request req;
    req.lambda_nm = lambda;
    req.incidence = {inc.theta_rad, inc.phi_rad};
    req.profile = &*cfg.nominal_stack;
    const JonesReflection r = cfg.reflection->reflect_one(req);
    const double R = std::norm(r.ss * ce + r.sp * ch) + std::norm(r.ps * ce + r.pp * ch);
    num += beam.amp[q] * beam.amp[q] * R;
    den += beam.amp[q] * beam.amp[q];
  }
  return num / den;
}

void check_slab(const std::string& name, const std::vector<double>& thetas_deg, const std::vector<double>& phis_deg,
                double lambda, double tol) {
  const SpeciesConfig cfg = load_species_config(config_path(name), plumage::testing::registry());
  REQUIRE(cfg.solver_type == "bem");
  const CrossSection cs = cfg.structure->generate(0);
  const auto prepared = cfg.solver->prepare(cs, cfg.reflection);
  const auto prep = bem::prepare_geometry(cs);
  const DirectionSet dirs = pattern_directions(400);
  const double dphi = kPi / 400;
  // the beam as the config's solver section defines it
  const bem::BemOptions options = bem::bem_options_table().read(cfg.root.node("solver"));
  for (double theta_deg : thetas_deg) {
    const double theta = deg_to_rad(theta_deg);
    std::vector<double> phis;
    for (double p : phis_deg) phis.push_back(deg_to_rad(p));
    const auto ffs = cfg.solver->solve(*prepared, lambda, theta, phis, dirs.phi_o_rad);
    REQUIRE(ffs.size() == phis.size());
    const double k0 = wavenumber_per_nm(lambda), g0 = k0 * std::cos(theta);
    for (std::size_t a = 0; a < phis.size(); ++a) {
      for (int pol = 0; pol < 2; ++pol) {
        const auto beam = bem::incident_for(*prep, options, k0, theta, phis[a], pol);
        double sum_amp2 = 0.0;
        for (double am : beam.amp) sum_amp2 += am * am;
        const double dalpha = beam.alpha.size() > 1 ? beam.alpha[1] - beam.alpha[0] : 1.0;
        // P_inc/(cos θ/(2η0)) = (2π/γ0) ∫|A|² dα;  P_refl/(cos θ/(2η0)) = ∫_{upper} |𝓔|² dφ_o
        const double p_inc = 2.0 * kPi / g0 * sum_amp2 / dalpha;
        double p_refl = 0.0;
        for (const auto& f : ffs[a].field[pol]) p_refl += (std::norm(f[0]) + std::norm(f[1]) + std::norm(f[2])) * dphi;
        const double r_bem = p_refl / p_inc;
        const double r_ref = beam_reflectance_reference(cfg, beam, lambda);
        // and the FarField normalisation (Φ_i of spec §1.7) gives the same fraction to the
        // accuracy of the Gaussian-footprint approximation of Φ_i
        const double r_ff = ffs[a].reflected_fraction(pol, dphi);
        std::printf("  %s lambda %.0f theta %2.0f phi %2.0f pol %d: BEM %.6f  multilayer %.6f  rel. diff %.2e  "
                    "(per Phi_i: %.6f)\n",
                    name.c_str(), lambda, theta_deg, rad_to_deg(phis[a]), pol + 1, r_bem, r_ref,
                    std::abs(r_bem - r_ref) / r_ref, r_ff);
        CHECK(std::abs(r_bem - r_ref) <= tol * r_ref);
        CHECK(std::abs(r_ff - r_bem) <= 2e-2 * r_bem);
      }
    }
  }
}

}  // namespace

TEST_CASE("bem plug-in: flat keratin film under the Gaussian beam reproduces the multilayer |r|^2") {
  check_slab("keratin-film-slab-bem", {30.0}, {0.0, 25.0}, 550.0, 1e-3);
}

TEST_CASE("bem plug-in: flat keratin film at theta_i = 0 vs multilayer", "[validation]") {
  check_slab("keratin-film-slab-bem", {0.0}, {0.0, 25.0}, 550.0, 1e-3);
}

TEST_CASE("bem plug-in: melanin/keratin slab (junctions at the sides) vs multilayer", "[validation]") {
  check_slab("melanin-keratin-slab-bem", {0.0, 30.0}, {0.0, 25.0}, 450.0, 1e-3);
}

TEST_CASE("bem plug-in: cylinder config with plane-wave incidence gives the differential scattering width") {
  const SpeciesConfig cfg = load_species_config(config_path("keratin-cylinder-bem"), plumage::testing::registry());
  REQUIRE(cfg.solver_type == "bem");
  const CrossSection cs = cfg.structure->generate(0);
  const auto prepared = cfg.solver->prepare(cs, cfg.reflection);
  const DirectionSet dirs = full_circle_directions(360);
  const double lambda = 550.0, theta = deg_to_rad(30.0), phi_i = 0.2;
  const std::vector<double> phis{phi_i};
  const auto ff = cfg.solver->solve(*prepared, lambda, theta, phis, dirs.phi_o_rad).front();
  for (int pol = 0; pol < 2; ++pol) {
    const auto s = oracle::solve_homogeneous_bh(0.25, Material::keratin().index(lambda), lambda / 1000.0, theta, pol + 1);
    double num = 0, den = 0;
    for (std::size_t d = 0; d < dirs.phi_o_rad.size(); ++d) {
      const double Phi = oracle::scattering_angle(dirs.phi_o_rad[d], phi_i);
      const double ref = 2.0 / (kPi * s.k0) * (std::norm(s.t_co(Phi)) + std::norm(s.t_cross(Phi))) * 1000.0;  // nm
      const double bem = ff.reflectance_density(pol, d);
      num += (bem - ref) * (bem - ref);
      den += ref * ref;
    }
    std::printf("  cylinder config pol %d: dsigma/dphi relative L2 vs series %.2e (polygon of the generator, 5 nm)\n",
                pol + 1, std::sqrt(num / den));
    CHECK(std::sqrt(num / den) <= 1e-3);
  }
}

TEST_CASE("bem plug-in: the registry documents the solver's parameter table and makes its benchmark") {
  const PluginRegistry& registry = plumage::testing::registry();
  const auto* solver = registry.find(ScatteringSolver::plugin_kind, "bem");
  REQUIRE(solver != nullptr);
  const auto specs = bem::bem_options_table().specs();
  REQUIRE(solver->info.params.size() == specs.size());
  for (std::size_t k = 0; k < specs.size(); ++k) {
    CHECK(solver->info.params[k].name == specs[k].name);
    CHECK(solver->info.params[k].default_value == specs[k].default_value);
    CHECK(solver->info.params[k].range == specs[k].range);
  }
  const auto* bench = registry.find(Benchmark::plugin_kind, "bem");
  REQUIRE(bench != nullptr);
  bool has_map = false;
  for (const ParamSpec& p : bench->info.params) has_map |= p.name == "bem" && p.type == "map";
  CHECK(has_map);
  // Its solver options are the solver's: a wrong key or value fails when the benchmark is made,
  // naming the parameter (nothing runs).
  const auto error_of = [&](const std::string& yaml) -> std::string {
    const ConfigDocument doc = ConfigDocument::parse(yaml, "command line");
    try {
      registry.create_named<Benchmark>("bem", doc.root(), registry.context());
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  CHECK_THAT(error_of("{bem: {ppw: '12'}}"),
             Catch::Contains("unknown key 'ppw'") && Catch::Contains("points_per_wavelength"));
  CHECK_THAT(error_of("{bem: {method: 'lu'}}"), Catch::Contains("method"));
  CHECK_THAT(error_of("{bem: {log_file: 'x'}}"), Catch::Contains("log_file"));
  CHECK_THAT(error_of("{width-um: [1]}"), Catch::Contains("width-um"));
  CHECK(error_of("{width_um: [1], bem: {method: 'dense', points_per_wavelength: '12'}}") == "no error");
}
