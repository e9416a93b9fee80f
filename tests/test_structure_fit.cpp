// Structure fitting (plumage/structure_fit.hpp, issue 25 part 3): synthetic recovery — a spectrum
// made by plumage's own forward model at known parameters plus seeded Gaussian noise, fitted from a
// start away from the truth; the truth must lie within 3 reported σ, and σ must agree with the
// linearised σ of an independent model (thin film: the Airy formula). Plus the spec's refusals.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/error.hpp"
#include "plumage/input_file.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_fit.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("plumage_structure_fit_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path file = temp_dir() / name;
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

std::string source_path(const std::string& relative) { return (fs::path(PLUMAGE_SOURCE_DIR) / relative).string(); }

// "- {lambda_nm: l, theta_deg: t, R: 0.1, polarization: pol}" for each λ from..to step and θ.
std::string point_list(double from, double to, double step, const std::vector<double>& thetas, const std::string& pol) {
  std::ostringstream y;
  for (double t : thetas)
    for (double l = from; l <= to + 1e-9; l += step)
      y << "    - {lambda_nm: " << l << ", theta_deg: " << t << ", R: 0.1, polarization: " << pol << "}\n";
  return y.str();
}

// The targets' reflectances set to the model's prediction at `truth` plus N(0, σ²) noise (seeded).
void make_synthetic(FitSpec& spec, const StructureForwardModel& model, const std::vector<double>& truth, double sigma,
                    std::uint64_t seed) {
  const std::vector<double> clean = model.predict(truth);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    spec.targets[i].reflectance = clean[i] + noise(rng);
    spec.targets[i].sigma = sigma;
  }
}

// Normal-incidence reflectance of a non-absorbing film (index n, thickness d) in air: the Airy
// sum r = (r01 + r12 e^{2iδ}) / (1 + r01 r12 e^{2iδ}), δ = 2π n d / λ (Born & Wolf §1.6).
double airy_film(double n, double d_nm, double lambda_nm) {
  const double r01 = (1.0 - n) / (1.0 + n), r12 = -r01;
  const std::complex<double> e = std::polar(1.0, 4.0 * M_PI * n * d_nm / lambda_nm);
  return std::norm((r01 + r12 * e) / (1.0 + r01 * r12 * e));
}
double keratin_index(double lambda_nm) { return 1.532 + 5890.0 / (lambda_nm * lambda_nm); }  // paper Eq. 1

std::string film_species(double d_nm) {
  return "species: film\ncommon_name: Keratin film\nvariant: plain\nvariants:\n  plain: {}\n"
         "nominal_stack:\n  layers:\n    - {material: keratin, thickness_nm: " +
         std::to_string(d_nm) + "}\n  substrate: air\nreflection: {model: multilayer}\n";
}

std::string refusal(const std::string& spec_text) {
  const fs::path spec = write_file("bad.yaml", spec_text);
  try {
    load_fit_spec(spec, testing::registry());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("fit: a keratin film's thickness from a noisy synthetic spectrum (Airy check)", "[structure-fit]") {
  write_file("film.yaml", film_species(380.0));
  const fs::path spec_file = write_file("film-fit.yaml",
      "model: nominal_stack\nconfig: film.yaml\nparameters:\n"
      "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500], start: 350}\n"
      "starts: 3\ntarget:\n  points:\n" + point_list(400, 700, 5, {0.0}, "unpolarized"));
  FitSpec spec = load_fit_spec(spec_file, testing::registry());
  const auto model = make_forward_model(spec, testing::registry());
  // The forward model is the Airy formula (an independent implementation of a single film).
  const std::vector<double> at_410 = model->predict({410.0});
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    const double l = spec.targets[i].lambda_nm;
    CHECK(at_410[i] == Approx(airy_film(keratin_index(l), 410.0, l)).margin(1e-10));
  }
  const double truth = 410.0, sigma = 0.005;
  make_synthetic(spec, *model, {truth}, sigma, 11);
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  REQUIRE(r.covariance_note.empty());
  CHECK(std::abs(r.value[0] - truth) < 3.0 * r.sigma[0]);
  // The linearised σ of the Airy model: σ_d = σ / sqrt(Σ (dR/dd)²), dR/dd by central differences.
  double sum = 0.0;
  for (const FitTarget& t : spec.targets) {
    const double n = keratin_index(t.lambda_nm);
    const double g = (airy_film(n, truth + 0.01, t.lambda_nm) - airy_film(n, truth - 0.01, t.lambda_nm)) / 0.02;
    sum += g * g;
  }
  const double expected = sigma / std::sqrt(sum);
  // s² of 60 degrees of freedom is within ±40% of 1 at ~3 standard deviations (sqrt(2/60) = 0.18).
  CHECK(r.sigma[0] > 0.6 * expected);
  CHECK(r.sigma[0] < 1.4 * expected);
  CHECK(r.reduced_chi2 == Approx(1.0).margin(0.5));
  CHECK(r.starts.size() == 3);
}

// One value, one parameter (the magpie worked cases): a solve. Its σ is the stated σ carried
// through the model's slope: σ_d = σ / |dR/dd| (Airy formula), and s² is undefined.
TEST_CASE("fit: one value for one parameter solves it, with sigma from the stated sigma", "[structure-fit]") {
  write_file("film.yaml", film_species(380.0));
  const double truth = 410.0, lambda = 520.0, sigma = 0.005;
  const double n = keratin_index(lambda);
  const fs::path spec_file = write_file("film-solve.yaml",
      "model: nominal_stack\nconfig: film.yaml\nparameters:\n"
      "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [395, 425], start: 400}\n"
      "target: {points: [{lambda_nm: 520, theta_deg: 0, R: " + std::to_string(airy_film(n, truth, lambda)) +
      ", sigma: 0.005}]}\n");
  FitSpec spec = load_fit_spec(spec_file, testing::registry());
  const auto model = make_forward_model(spec, testing::registry());
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  CHECK(r.value[0] == Approx(truth).margin(0.01));
  const double slope = (airy_film(n, truth + 0.01, lambda) - airy_film(n, truth - 0.01, lambda)) / 0.02;
  CHECK(r.sigma[0] == Approx(sigma / std::abs(slope)).epsilon(0.02));
  CHECK(std::isnan(r.reduced_chi2));
  CHECK_THAT(fit_summary_text(spec, *model, r), Contains("as many targets as parameters"));
}

TEST_CASE("fit: parabola_peak_nm finds a parabola's vertex and clamps a window without a maximum", "[structure-fit]") {
  std::vector<double> l, r, rising;
  for (double x = 500; x <= 540 + 1e-9; x += 5) {
    l.push_back(x);
    r.push_back(0.3 - 1e-4 * (x - 523.7) * (x - 523.7));
    rising.push_back(0.1 + 1e-3 * (x - 500) + 1e-6 * (x - 500) * (x - 500));
  }
  CHECK(parabola_peak_nm(l, r) == Approx(523.7).margin(1e-9));
  // On the flank (vertex 20 nm beyond the window's end) the vertex is still found.
  std::vector<double> flank;
  for (double x : l) flank.push_back(0.3 - 1e-4 * (x - 560.0) * (x - 560.0));
  CHECK(parabola_peak_nm(l, flank) == Approx(560.0).margin(1e-9));
  CHECK(parabola_peak_nm(l, rising) == 540.0);
  std::vector<double> falling(rising.rbegin(), rising.rend());
  CHECK(parabola_peak_nm(l, falling) == 500.0);
}

// A quarter-wave keratin film: R(λ) of a lossless film in air is largest near where its phase
// δ = 2π n(λ) d / λ is (m + ½)π (Born & Wolf §1.6), so a peak target at λ_t gives
// d ≈ (m + ½) λ_t / (2 n(λ_t)). Not exactly: keratin's dispersion raises the film's finesse to the
// blue, which puts the true maximum of R(λ) at d_exact 1.4 nm blue of λ_t, and the parabola
// through the 40 nm window leans 0.6 nm back (δ ∝ n(λ)/λ), so the vertex is 0.9 nm blue of λ_t,
// i.e. the fitted d is 0.42 nm thicker (numbers from the Airy formula); 0.6 nm bounds that.
// Exactly: the model's peak equals the parabola through the independent Airy formula.
TEST_CASE("fit: a keratin film's thickness from a peak position (quarter-wave condition)", "[structure-fit]") {
  write_file("film.yaml", film_species(380.0));
  const double lambda_t = 550.0;
  const double d_exact = 1.5 * lambda_t / (2.0 * keratin_index(lambda_t));  // m = 1: 265.9 nm
  const fs::path spec_file = write_file("film-peak.yaml",
      "model: nominal_stack\nconfig: film.yaml\nparameters:\n"
      "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [240, 290], start: 255}\n"
      "target: {peaks: [{lambda_nm: 550, sigma_nm: 0.5, window_nm: 40, step_nm: 5}]}\n");
  const FitSpec spec = load_fit_spec(spec_file, testing::registry());
  REQUIRE(spec.targets.size() == 1);
  CHECK(fit_model_samples(spec.targets).size() == 9);
  const auto model = make_forward_model(spec, testing::registry());
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  CHECK(r.prediction[0] == Approx(lambda_t).margin(0.01));
  CHECK(r.value[0] == Approx(d_exact).margin(0.6));
  std::vector<double> l, airy;
  for (double x = lambda_t - 20; x <= lambda_t + 20 + 1e-9; x += 5)
    l.push_back(x), airy.push_back(airy_film(keratin_index(x), r.value[0], x));
  CHECK(r.prediction[0] == Approx(parabola_peak_nm(l, airy)).margin(1e-6));
  // A film 1 % thicker moves its peak 1 % to the red: the prediction follows the physics.
  CHECK(model->predict({d_exact * 1.01})[0] == Approx(lambda_t * 1.01).margin(1.5));
  CHECK_THAT(fit_summary_text(spec, *model, r), Contains("peak at theta 0 deg"));
}

TEST_CASE("fit: the rock dove's cortex and air gap from a noisy two-angle measured file", "[structure-fit]") {
  const std::string species = source_path("configs/species/rockdove.yaml");
  const std::string params =
      "parameters:\n"
      "  - {path: variants.forest.nominal_stack.layers.0.thickness_nm, bounds: [450, 750], start: 560}\n"
      "  - {path: variants.forest.nominal_stack.layers.1.thickness_nm, bounds: [250, 750], start: 450}\n";
  // The synthetic measurement: plumage's prediction at the file's own values (595, 500) + noise,
  // written as a measured file with one column per angle.
  const fs::path maker = write_file("rd-points.yaml", "model: nominal_stack\nconfig: " + species +
      "\nvariant: forest\n" + params + "target:\n  points:\n" + point_list(400, 700, 5, {0.0, 30.0}, "unpolarized"));
  FitSpec points = load_fit_spec(maker, testing::registry());
  const auto maker_model = make_forward_model(points, testing::registry());
  const double sigma = 0.01;
  make_synthetic(points, *maker_model, {595.0, 500.0}, sigma, 7);
  std::ostringstream csv;
  csv << "lambda_nm,R_0deg,R_30deg\n";
  const std::size_t n_lambda = points.targets.size() / 2;
  // Clipped at 0 as a spectrometer's export would be (the reader refuses negative reflectance).
  for (std::size_t i = 0; i < n_lambda; ++i)
    csv << points.targets[i].lambda_nm << ',' << std::max(0.0, points.targets[i].reflectance) << ','
        << std::max(0.0, points.targets[i + n_lambda].reflectance) << '\n';
  write_file("rd-measured.csv", csv.str());
  const fs::path spec_file = write_file("rd-fit.yaml", "model: nominal_stack\nconfig: " + species +
      "\nvariant: forest\n" + params + "target: {measured: rd-measured.csv, sigma: 0.01}\nstarts: 3\n");
  const FitSpec spec = load_fit_spec(spec_file, testing::registry());
  REQUIRE(spec.targets.size() == 2 * n_lambda);
  const auto model = make_forward_model(spec, testing::registry());
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  REQUIRE(r.covariance_note.empty());
  const double truth[] = {595.0, 500.0};
  for (int j = 0; j < 2; ++j) {
    CHECK(std::abs(r.value[j] - truth[j]) < 3.0 * r.sigma[j]);
    CHECK(r.sigma[j] > 0.01);  // not 0: noise of 0.01 in R cannot pin a thickness to 0.01 nm
    CHECK(r.sigma[j] < 10.0);  // not huge: the fringes fix the optical thickness to ~1 nm
    CHECK(!r.at_bound[j]);
  }
  CHECK(r.reduced_chi2 == Approx(1.0).margin(0.5));
  // The outputs: the new variant carries the fitted values and becomes the default.
  const fs::path out = temp_dir() / "rd-out";
  write_fit_outputs(spec, *model, r, out, false);
  const SpeciesConfig fitted = load_species_config(out / "fitted.yaml", testing::registry());
  CHECK(fitted.variant == "forest_fit");
  REQUIRE(fitted.nominal_stack);
  CHECK(fitted.nominal_stack->layers[0].thickness_nm == Approx(r.value[0]).epsilon(1e-12));
  CHECK(fitted.nominal_stack->layers[1].thickness_nm == Approx(r.value[1]).epsilon(1e-12));
  const SpeciesConfig original = load_species_config(out / "fitted.yaml", testing::registry(), "forest");
  CHECK(original.nominal_stack->layers[0].thickness_nm == 595.0);
  for (const char* name : {"fit.txt", "fit.csv", "fit_starts.csv", "fit_spectrum.csv"}) CHECK(fs::exists(out / name));
}

// The crystal forward model through the TableBuilder interface in the default suite: FDTD on a
// coarse 25 nm grid (0.22 s CPU per evaluation; the fit checks itself, so the grid need only be
// the same for the data and the model), one parameter at normal incidence.
TEST_CASE("fit: a mallard crystal cell's rod diameter (FDTD, coarse grid)", "[structure-fit]") {
  const fs::path spec_file = write_file("crystal-fit-1.yaml",
      "model: crystal_table\nconfig: " + source_path("configs/crystals/mallard-green.yaml") +
      "\nbuilder: {type: fdtd_periodic, fidelity: preview, exact_fill: true, resolution_nm: 25}\nrelative_step: 0.01\n"
      "parameters:\n  - {path: crystal.rod_diameter_nm, bounds: [130, 175], start: 140}\n"
      "target:\n  points:\n" + point_list(420, 690, 30, {0.0}, "unpolarized"));
  FitSpec spec = load_fit_spec(spec_file, testing::registry());
  const auto model = make_forward_model(spec, testing::registry());
  make_synthetic(spec, *model, {152.0}, 0.01, 5);
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  REQUIRE(r.covariance_note.empty());
  CHECK(std::abs(r.value[0] - 152.0) < 3.0 * r.sigma[0]);
  CHECK(r.sigma[0] > 0.01);
  CHECK(r.sigma[0] < 10.0);
  CHECK(r.evaluations > 0);
}

// The whole barbule (plumage simulate: approximate solver, 2 instances) as the forward model.
TEST_CASE("fit: the rock dove barbule's cortex through the whole-barbule simulation", "[structure-fit]") {
  const fs::path spec_file = write_file("barbule-fit.yaml",
      "model: barbule\nconfig: " + source_path("configs/species/rockdove.yaml") +
      "\nvariant: forest\ninstances: 2\nrelative_step: 0.01\n"
      "parameters:\n  - {path: variants.forest.structure.cortex_nm, bounds: [540, 650], start: 570}\n"
      "target:\n  points:\n" + point_list(420, 690, 30, {0.0}, "unpolarized"));
  FitSpec spec = load_fit_spec(spec_file, testing::registry());
  const auto model = make_forward_model(spec, testing::registry());
  make_synthetic(spec, *model, {595.0}, 0.005, 9);
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  REQUIRE(r.covariance_note.empty());
  CHECK(std::abs(r.value[0] - 595.0) < 3.0 * r.sigma[0]);
  CHECK(r.sigma[0] > 0.01);
  CHECK(r.sigma[0] < 10.0);
  const fs::path out = temp_dir() / "barbule-out";
  write_fit_outputs(spec, *model, r, out, false);
  const SpeciesConfig fitted = load_species_config(out / "fitted.yaml", testing::registry());
  CHECK(fitted.variant == "forest_fit");
  CHECK(fitted.root.child("structure").number("cortex_nm") == Approx(r.value[0]).epsilon(1e-12));
}

// FDTD at preview fidelity (15 nm): ~0.8 s CPU per evaluation, 2 parameters: 84 s CPU (validation).
TEST_CASE("fit: a mallard crystal cell's rod diameter and row spacing (FDTD preview)", "[.][structure-fit-crystal]") {
  const fs::path spec_file = write_file("crystal-fit.yaml",
      "model: crystal_table\nconfig: " + source_path("configs/crystals/mallard-green.yaml") +
      "\nbuilder: {type: fdtd_periodic, fidelity: preview, exact_fill: true}\nrelative_step: 0.01\n"
      "parameters:\n  - {path: crystal.rod_diameter_nm, bounds: [130, 175], start: 140}\n"
      "  - {path: crystal.a_z_nm, bounds: [155, 180], start: 170}\n"
      "target:\n  points:\n" + point_list(420, 690, 30, {0.0}, "unpolarized"));
  FitSpec spec = load_fit_spec(spec_file, testing::registry());
  REQUIRE(spec.targets.size() == 10);
  const auto model = make_forward_model(spec, testing::registry());
  const double truth[] = {152.0, 164.5};
  make_synthetic(spec, *model, {truth[0], truth[1]}, 0.01, 3);
  const FitResult r = fit_structure(spec, *model);
  INFO(fit_summary_text(spec, *model, r));
  REQUIRE(r.covariance_note.empty());
  for (int j = 0; j < 2; ++j) {
    CHECK(std::abs(r.value[j] - truth[j]) < 3.0 * r.sigma[j]);
    CHECK(r.sigma[j] > 0.01);
    CHECK(r.sigma[j] < 10.0);
  }
  const fs::path out = temp_dir() / "crystal-out";
  write_fit_outputs(spec, *model, r, out, false);
  CHECK(load_crystal_cell(out / "fitted.yaml").name == "mallard-green-fit");
  CHECK(load_crystal_cell(out / "fitted.yaml").rod_diameter_nm == Approx(r.value[0]).epsilon(1e-12));
}

TEST_CASE("fit spec: refusals name the spec's file, line and field", "[structure-fit]") {
  write_file("film.yaml", film_species(380.0));
  const std::string head = "model: nominal_stack\nconfig: film.yaml\nparameters:\n";
  const std::string target = "target:\n  points:\n" + point_list(400, 700, 50, {0.0}, "s");
  auto spec = [&](const std::string& parameter) { return head + "  - " + parameter + "\n" + target; };
  const std::string where = (temp_dir() / "bad.yaml").string() + ":4:";
  const std::string unknown = refusal(spec("{path: nominal_stack.layers.1.thickness_nm, bounds: [1, 2]}"));
  CHECK_THAT(unknown, Contains(where) && Contains("parameters[0].path") && Contains("'nominal_stack.layers.1' is not in"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layres.0.thickness_nm, bounds: [1, 2]}")),
             Contains("'nominal_stack.layres' is not in"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layers.0.thickness_nm, bounds: [500, 300]}")),
             Contains("bad.yaml:4:") && Contains("bounds"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layers.0.thickness_nm, bounds: [300, 300]}")),
             Contains("parameters[0].bounds") && Contains("below the upper"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500], start: 600}")),
             Contains(where) && Contains("parameters[0].start") && Contains("outside the bounds"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layers.0.thickness_nm, bounds: [400, 500]}")),
             Contains("(the file's value) is outside the bounds"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layers.0.material, bounds: [1, 2]}")),
             Contains("parameters[0].path") && Contains("is not a number"));
  CHECK_THAT(refusal(spec("{path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500], strat: 350}")),
             Contains("strat"));
  CHECK_THAT(refusal(head + "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500]}\n"
                     "target: {measured: x.csv, points: [{lambda_nm: 500, R: 0.1}]}\n"),
             Contains("bad.yaml:") && Contains("not both"));
  CHECK_THAT(refusal(head + "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500]}\n"
                     "target: {sigma: 0.1}\n"),
             Contains("bad.yaml:") && Contains("`peaks`"));
  CHECK_THAT(refusal(head + "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500]}\n"
                     "target: {peaks: [{lambda_nm: 500, window_nm: 8, step_nm: 5}]}\n"),
             Contains("bad.yaml:") && Contains("at least 3 samples"));
  // Two parameters, one value: refused (one value for one parameter is a solve, allowed).
  write_file("film2.yaml", "species: film2\ncommon_name: Two films\nvariant: plain\nvariants:\n  plain: {}\n"
                           "nominal_stack:\n  layers:\n    - {material: keratin, thickness_nm: 380}\n"
                           "    - {material: air, thickness_nm: 400}\n  substrate: melanin\nreflection: {model: multilayer}\n");
  CHECK_THAT(refusal("model: nominal_stack\nconfig: film2.yaml\nparameters:\n"
                     "  - {path: nominal_stack.layers.0.thickness_nm, bounds: [300, 500]}\n"
                     "  - {path: nominal_stack.layers.1.thickness_nm, bounds: [300, 500]}\n"
                     "target: {points: [{lambda_nm: 500, R: 0.1}]}\n"),
             Contains("at least as many values as parameters"));
  CHECK_THAT(refusal("model: crystal_table\nconfig: film.yaml\nparameters: []\n" + target),
             Contains("bad.yaml:"));
  // The base nominal_stack of a species whose variant has its own: loads, but cannot be fitted.
  const fs::path insensitive = write_file("insensitive.yaml",
      "model: nominal_stack\nconfig: " + source_path("configs/species/rockdove.yaml") + "\nvariant: forest\n"
      "parameters:\n  - {path: nominal_stack.layers.0.thickness_nm, bounds: [450, 750]}\n" + target);
  const FitSpec spec_insensitive = load_fit_spec(insensitive, testing::registry());
  const auto model = make_forward_model(spec_insensitive, testing::registry());
  CHECK_THROWS_WITH(fit_structure(spec_insensitive, *model),
                    Contains("insensitive.yaml:5:") && Contains("parameters[0].path") &&
                        Contains("does not change the prediction"));
}

TEST_CASE("ConfigDocument::derive indexes lists (a fit parameter's path)", "[structure-fit]") {
  const ConfigDocument doc = ConfigDocument::parse(
      "stack:\n  layers:\n    - {material: keratin, thickness_nm: 300}\n    - {material: air, thickness_nm: 200}\n", "doc");
  const ConfigDocument d = ConfigDocument::derive(doc.root(), {{"stack.layers.1.thickness_nm", "250"}}, "/tmp", "derived");
  const std::vector<ParamView> layers = d.root().child("stack").items("layers");
  REQUIRE(layers.size() == 2);
  CHECK(layers[0].number("thickness_nm") == 300.0);
  CHECK(layers[1].number("thickness_nm") == 250.0);
  CHECK(layers[1].text("material") == "air");
  // The source is untouched.
  CHECK(doc.root().child("stack").items("layers")[1].number("thickness_nm") == 200.0);
  CHECK_THROWS_WITH(ConfigDocument::derive(doc.root(), {{"stack.layers.2.thickness_nm", "1"}}, "/tmp", "derived"),
                    Contains("no list item '2'") && Contains("2 items"));
  CHECK_THROWS_WITH(ConfigDocument::derive(doc.root(), {{"stack.layers.x.thickness_nm", "1"}}, "/tmp", "derived"),
                    Contains("no list item 'x'"));
}
