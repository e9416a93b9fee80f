// Issue 9, stability campaign of the FDTD plug-in: each failure mode is detected and reported —
// a plumage::warn() code (echoed on stderr) and a "WARNING: … [code]" in the table's notes (the
// .plt metadata) — and the safe counterpart of each case raises nothing. Small cells only: every
// case runs in a few seconds (NOTES "Warnings (issue 9)").
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/table_builder.hpp"
#include "layered_cell.hpp"
#include "table_build.hpp"

using namespace plumage;

namespace {

bool has_note(const ReflectionTable& t, std::string_view code) {
  const std::string& n = t.metadata().notes;
  return n.find("WARNING:") != std::string::npos && n.find("[" + std::string(code) + "]") != std::string::npos;
}

// The layered reference cell (layered_cell.hpp).
fdtd::Cell layered(double h_um, int nx, double lambda_um) { return fdtd_reference::layered_cell(h_um, nx, lambda_um); }

// A cheap grating with a long period: keratin with one melanin rod per period a_x, 20 nm grid.
fdtd::Cell grating(double ax_um, double lambda_um) {
  fdtd::Cell c = layered(0.02, 1, lambda_um);
  c.ax = ax_um;
  c.slabs.clear();
  c.circles = {{0.5 * ax_um, 0.12, 0.08, 2}};
  c.structure_depth = 0.2;
  return c;
}

TableGrid grid_of(std::vector<double> lambda, std::vector<double> cos_theta, std::vector<double> cos_phi) {
  TableGrid g;
  g.lambda_nm = std::move(lambda);
  g.cos_theta = std::move(cos_theta);
  g.cos_phi = std::move(cos_phi);
  return g;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("engine guard: a time step 0.2 % over the limit is caught early, stable runs stay far below the threshold",
          "[warnings][courant]") {
  const double h = 0.01;
  const fdtd::Cell cell = layered(h, 2, -1.0);
  std::vector<double> omegas;
  for (double l = 0.40; l <= 0.7001; l += 0.02) omegas.push_back(2 * fdtd::kPi / l);
  fdtd::SimParams p;
  p.nx = 2;
  // Safe: the energy of the main grid stays within a small factor of nx × its normalisation grid.
  for (auto [kx, ky] : {std::pair{0.0, 0.0}, std::pair{-6.0, -6.0}}) {
    const auto s = fdtd::run_spectrum(cell, kx, ky, omegas, p);
    std::printf("[warnings] layered nx=2 (%g, %g) courant %.2f: energy ratio %.3g, %d steps\n", kx, ky,
                s.stats.dt / s.stats.dt_limit, s.stats.energy_ratio, s.stats.steps);
    CHECK(s.stats.converged);
    CHECK(s.stats.energy_ratio > 0.1);
    CHECK(s.stats.energy_ratio < 100.0);  // guard threshold blowup_factor = 1e4
    CHECK(std::abs(s.stats.dt / s.stats.dt_limit - 0.95) < 1e-12);
  }
  // 1.002 × the limit: grows during the source phase; detected against the clean air reference
  // (the old check against the polluted source-phase maximum fired only after the source, at
  // t = 9.85 um/c with energy 2e87).
  p.allow_unstable_dt = true;
  p.dt = 1.002 * fdtd::stable_time_step(cell, h, 0.0, p.lorentz_update);
  try {
    fdtd::run_spectrum(cell, 0.0, 0.0, omegas, p);
    FAIL("no blow-up detected");
  } catch (const fdtd::FieldBlowUp& e) {  // typed: a plumage::NumericalError with the numbers
    const std::string msg = e.what();
    std::printf("[warnings] %s\n", msg.c_str());
    CHECK(dynamic_cast<const NumericalError*>(&e) != nullptr);
    CHECK(e.step > 0);
    CHECK(e.time_um == Approx(e.step * e.dt));
    CHECK(e.dt / e.dt_limit == Approx(1.002));
    CHECK(msg.find("blow-up") != std::string::npos);
    CHECK(msg.find("normalisation-run energy") != std::string::npos);
    CHECK(msg.find("1.002 of the stability limit") != std::string::npos);
    const double t = std::stod(msg.substr(msg.find("t = ") + 4));
    CHECK(t < 6.0);
  }
}

TEST_CASE("table at the Courant limit warns; over it is refused or caught and rerun; a safe one is silent",
          "[warnings][courant]") {
  const double h = 0.01;
  const int nx = 2;
  auto make = [&](double l) { return layered(h, nx, l); };
  const TableGrid g = grid_of({450, 600}, {1.0}, {0.8, 1.0});
  fdtd_table::Options opt;
  opt.nx = nx;
  opt.k_step_per_um = 0.5;
  const auto t0 = std::chrono::steady_clock::now();

  ReflectionTable safe = [&] {
    CapturedWarnings w;
    const ReflectionTable t = fdtd_table::build_table(make, h * nx, g, {}, opt, {});
    CHECK(diagnostics().empty());
    CHECK(w.echoed().empty());
    CHECK(t.metadata().notes.find("WARNING") == std::string::npos);
    return t;
  }();

  {  // exactly at the limit (the builder's largest `courant`): reported, result still sound
    CapturedWarnings w;
    fdtd_table::Options o = opt;
    o.sim.courant = 1.0;
    const ReflectionTable t = fdtd_table::build_table(make, h * nx, g, {}, o, {});
    std::printf("[warnings] courant 1.0: %s\n", w.message("fdtd.courant").c_str());
    CHECK(w.count("fdtd.courant") == 1);
    CHECK(w.echoed("fdtd.courant"));
    CHECK(has_note(t, "fdtd.courant"));
    CHECK(w.message("fdtd.courant").find("is 1 of the stability limit") != std::string::npos);
  }

  const double lim = fdtd::stable_time_step(make(-1.0), h, 0.0, fdtd::LorentzUpdate::Bilinear);
  {  // certainly unstable: refused before any run, the message names dt and the factor
    CapturedWarnings w;
    fdtd_table::Options o = opt;
    o.sim.dt = 1.01 * lim;
    try {
      fdtd_table::build_table(make, h * nx, g, {}, o, {});
      FAIL("not refused");
    } catch (const Error& e) {
      const std::string msg = e.what();
      std::printf("[warnings] refused: %s\n", msg.c_str());
      CHECK(msg.find("certainly unstable") != std::string::npos);
      CHECK(msg.find("1.01 of the stability limit") != std::string::npos);
    }
  }
  {  // the same with the refusal off: every run blows up, is caught by the energy guard, rerun
     // at half the time step and reported; the table equals the safe one to the time-step error
    CapturedWarnings w;
    fdtd_table::Options o = opt;
    o.sim.dt = 1.01 * lim;
    o.sim.allow_unstable_dt = true;
    const ReflectionTable t = fdtd_table::build_table(make, h * nx, g, {}, o, {});
    const std::string& notes = t.metadata().notes;
    std::printf("[warnings] over the limit: %s\n", notes.c_str());
    CHECK(w.count("fdtd.courant") == 2);  // before the runs (certainly unstable) + the blow-ups
    CHECK(w.echoed("fdtd.courant"));
    CHECK(has_note(t, "fdtd.courant"));
    CHECK(notes.find("certainly unstable") != std::string::npos);
    CHECK(notes.find("blew up") != std::string::npos);
    CHECK(notes.find("rerun at half the time step (0.505 of the stability limit)") != std::string::npos);
    double worst = 0;
    for (std::size_t l = 0; l < 2; ++l)
      for (std::size_t j = 0; j < 2; ++j) {
        const auto a = t.at(l, 0, j), b = safe.at(l, 0, j);
        CHECK(std::isfinite(std::abs(a.ss)));
        worst = std::max({worst, std::abs(a.ss - b.ss), std::abs(a.pp - b.pp)});
      }
    std::printf("[warnings] rerun table vs courant-0.95 table: max |dJ| = %.2e\n", worst);
    CHECK(worst < 5e-3);  // O((ω dt)²) time-step error of the two dt (NOTES §3b: ~1e-3)
  }
  std::printf("[warnings] courant cases: %.1f s\n", seconds_since(t0));
}

TEST_CASE("builder: courant above 1 is a ConfigError naming the field; courant 1 warns through the plug-in",
          "[warnings][courant][plugin]") {
  PluginRegistry registry;
  registry.load_library(std::filesystem::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_fdtd_periodic.so");
  {
    const ConfigDocument doc = ConfigDocument::parse("courant: 1.2\n", "builder.yaml");
    try {
      registry.create_named<TableBuilder>("fdtd_periodic", doc.root(), registry.context());
      FAIL("courant 1.2 accepted");
    } catch (const ConfigError& e) {
      std::printf("[warnings] %s\n", e.what());
      CHECK(e.field().find("courant") != std::string::npos);
    }
  }
  CapturedWarnings w;
  const ConfigDocument doc = ConfigDocument::parse("courant: 1.0\nresolution_nm: 19\n", "builder.yaml");
  auto builder = registry.create_named<TableBuilder>("fdtd_periodic", doc.root(), registry.context());
  const CrystalCell cc = load_crystal_cell(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs/crystals/mallard-green.yaml");
  const ReflectionTable t = builder->build(cc, grid_of({545}, {1.0}, {1.0}), {});
  CHECK(w.count("fdtd.courant") == 1);
  CHECK(w.echoed("fdtd.courant"));
  CHECK(has_note(t, "fdtd.courant"));
  const double R = std::norm(t.at(0, 0, 0).ss);
  CHECK(R > 0.05);  // the run itself is still sound at the limit (|r_s|² ≈ 0.15 at 545 nm)
  CHECK(R < 0.5);
}

TEST_CASE("entries below kz_min raise fdtd.grazing_continued with their count", "[warnings][grazing]") {
  const double h = 0.01;  // coarse: the count is the point, not the accuracy (~4× cheaper than 5 nm)
  auto make = [&](double l) { return layered(h, 1, l); };
  fdtd_table::Options opt;
  opt.nx = 1;
  opt.k_step_per_um = 0.5;
  {  // cos θ cos φ = 0.1, 0.2 (< kz_min 0.25), 0.6, 1.0: 2 of 4 entries continued
    const auto t1 = std::chrono::steady_clock::now();
    CapturedWarnings w;
    const ReflectionTable t = fdtd_table::build_table(make, h, grid_of({550}, {1.0}, {0.1, 0.2, 0.6, 1.0}), {}, opt, {});
    std::printf("[warnings] grazing (%.1f s): %s\n", seconds_since(t1), w.message("fdtd.grazing_continued").c_str());
    CHECK(w.count("fdtd.grazing_continued") == 1);
    CHECK(w.message("fdtd.grazing_continued").find("2 of 4 entries") != std::string::npos);
    CHECK(w.message("fdtd.grazing_continued").find("2 with k_z/k0 < kz_min = 0.25") != std::string::npos);
    CHECK(w.echoed("fdtd.grazing_continued"));
    CHECK(has_note(t, "fdtd.grazing_continued"));
    CHECK(!w.count("fdtd.grazing_simulated"));
    // the continued entries go to −1 at grazing: between the simulated value and −1
    CHECK(std::abs(t.at(0, 0, 0).ss + 1.0) < std::abs(t.at(0, 0, 2).ss + 1.0));
  }
  {  // a kz_min below 0.1 simulates entries where the engine is least accurate: reported (one
     // run per entry, so the entry at 0.08 is simulated at its own k, not from k-grid corners
     // beyond the light line)
    const auto t1 = std::chrono::steady_clock::now();
    CapturedWarnings w;
    fdtd_table::Options o = opt;
    o.k_step_per_um = 0.0;
    o.sim.kz_min = 0.05;
    const ReflectionTable t = fdtd_table::build_table(make, h, grid_of({550}, {1.0}, {0.08, 0.6}), {}, o, {});
    std::printf("[warnings] grazing simulated (%.1f s): %s\n", seconds_since(t1), w.message("fdtd.grazing_simulated").c_str());
    CHECK(!w.count("fdtd.grazing_continued"));
    CHECK(w.count("fdtd.grazing_simulated") == 1);
    CHECK(w.message("fdtd.grazing_simulated").find("1 simulated entries have k_z/k0 < 0.1 (down to 0.08") !=
          std::string::npos);
    CHECK(has_note(t, "fdtd.grazing_simulated"));
  }
  {  // all entries above kz_min: nothing
    CapturedWarnings w;
    const ReflectionTable t = fdtd_table::build_table(make, h, grid_of({550}, {1.0}, {0.6, 1.0}), {}, opt, {});
    CHECK(diagnostics().empty());
    CHECK(t.metadata().notes.find("WARNING") == std::string::npos);
  }
}

TEST_CASE("a period longer than lambda/(1 + sin) raises fdtd.other_orders; a short one does not",
          "[warnings][orders]") {
  fdtd_table::Options opt;
  opt.k_step_per_um = 0.0;  // one run per entry at its exact k: flags belong to the entry itself
  const auto t0 = std::chrono::steady_clock::now();
  {
    const double ax = 0.6;
    opt.nx = 30;  // 20 nm
    CapturedWarnings w;
    const TableGrid g = grid_of({450, 650}, {1.0}, {0.8, 1.0});
    const ReflectionTable t = fdtd_table::build_table([&](double l) { return grating(ax, l); }, ax, g, {}, opt, {});
    // Expected from the grating equation: order n propagates iff |k_x + 2πn/a_x| < k0 (k_y = 0 here).
    int expected = 0;
    for (double lam : g.lambda_nm)
      for (double cp : g.cos_phi) {
        const double k0 = 2 * fdtd::kPi / (lam * 1e-3), kx = -k0 * std::sqrt(1 - cp * cp), G = 2 * fdtd::kPi / ax;
        if (std::abs(kx + G) < k0 || std::abs(kx - G) < k0) ++expected;
      }
    std::printf("[warnings] other orders (expected %d of 4): %s\n", expected, w.message("fdtd.other_orders").c_str());
    CHECK(expected == 3);  // 450 nm both angles; 650 nm only at sin φ = 0.6 (a_x < λ at normal incidence)
    CHECK(w.count("fdtd.other_orders") == 1);
    CHECK(w.message("fdtd.other_orders").find(std::to_string(expected) + " of 4 samples") != std::string::npos);
    CHECK(w.message("fdtd.other_orders").find("of the incident power") != std::string::npos);
    CHECK(w.echoed("fdtd.other_orders"));
    CHECK(has_note(t, "fdtd.other_orders"));
    // pre-issue-9 text kept
    CHECK(t.metadata().notes.find("samples with other propagating diffraction orders") != std::string::npos);
  }
  {
    const double ax = 0.2;  // < 450 nm/(1 + 0.6): no second order anywhere on the grid
    opt.nx = 10;
    CapturedWarnings w;
    const ReflectionTable t = fdtd_table::build_table([&](double l) { return grating(ax, l); }, ax,
                                                      grid_of({450, 650}, {1.0}, {0.8, 1.0}), {}, opt, {});
    CHECK(!w.count("fdtd.other_orders"));
    CHECK(diagnostics().empty());
    CHECK(t.metadata().notes.find("WARNING") == std::string::npos);
  }
  std::printf("[warnings] other-order cases: %.1f s\n", seconds_since(t0));
}

TEST_CASE("runs stopped by max_time before converging raise fdtd.not_converged", "[warnings][convergence]") {
  const double h = 0.005;
  auto make = [&](double l) { return layered(h, 1, l); };
  fdtd_table::Options opt;
  opt.nx = 1;
  opt.k_step_per_um = 0.5;
  opt.sim.dft_tol = 1e-14;  // unreachable: every run stops at the time cap
  opt.sim.max_time = 0.0;   // the cap is then t_source_end + 10 um/c
  const auto ck = std::filesystem::temp_directory_path() / "plumage_test_fdtd_warnings.partial";
  std::filesystem::remove(ck);
  opt.checkpoint = ck.string();
  opt.checkpoint_tag = "not-converged-test";
  {
    CapturedWarnings w;
    const ReflectionTable t = fdtd_table::build_table(make, h, grid_of({550}, {1.0}, {1.0}), {}, opt, {});
    std::printf("[warnings] %s\n", w.message("fdtd.not_converged").c_str());
    CHECK(w.count("fdtd.not_converged") == 1);
    CHECK(w.message("fdtd.not_converged").find("4 of 4 fdtd runs") != std::string::npos);
    CHECK(w.echoed("fdtd.not_converged"));
    CHECK(has_note(t, "fdtd.not_converged"));
  }
  {  // all four runs resumed from the checkpoint: the flag travels with them
    CapturedWarnings w;
    const ReflectionTable t = fdtd_table::build_table(make, h, grid_of({550}, {1.0}, {1.0}), {}, opt, {});
    CHECK(t.metadata().notes.find("4 resumed from a checkpoint") != std::string::npos);
    CHECK(w.message("fdtd.not_converged").find("4 of 4 fdtd runs") != std::string::npos);
    CHECK(has_note(t, "fdtd.not_converged"));
  }
  std::filesystem::remove(ck);
}
