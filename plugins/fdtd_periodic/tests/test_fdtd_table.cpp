// The FDTD table builder (issue 5): Jones conversion and k-grid mapping against the multilayer's
// closed form on an x-invariant stack, the x-mirror rule on a crystal, and the plug-in.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "plumage/crystal_cell.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/table_builder.hpp"
#include "stack_solver.hpp"
#include "layered_cell.hpp"
#include "table_build.hpp"

using namespace plumage;

namespace {

// air | keratin 300 nm | melanin 200 nm | keratin, one grid cell wide (layered_cell.hpp).
fdtd::Cell layered(double h_um, double lambda_um) { return fdtd_reference::layered_cell(h_um, 1, lambda_um); }

multilayer::StackReflection closed_form(double lambda_nm, double cos_alpha) {
  const std::vector<Complex> index{1.0, Material::keratin().index(lambda_nm),
                                   Material::melanin().index(lambda_nm), Material::keratin().index(lambda_nm)};
  const std::vector<double> thick{300.0, 200.0};
  return multilayer::reflect_stack(index, thick, lambda_nm, 1.0 - cos_alpha * cos_alpha);
}

TableGrid tiny_grid() {
  TableGrid g;
  g.lambda_nm = {450, 550, 650};
  g.cos_theta = {0.6, 0.8, 1.0};
  g.cos_phi = {0.4, 0.6, 0.8, 1.0};
  return g;
}

}  // namespace

TEST_CASE("fdtd table of a layered cell reproduces the multilayer closed form", "[fdtd-table]") {
  const double h = 0.004;
  fdtd_table::Options opt;
  opt.nx = 1;
  opt.k_step_per_um = 0.0;  // one run per entry, exact ε(λ)
  const auto t0 = std::chrono::steady_clock::now();
  const ReflectionTable t = fdtd_table::build_table([&](double l) { return layered(h, l); }, h,
                                                    tiny_grid(), {}, opt, {});
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& g = t.grid();
  double worst = 0, worst_cross = 0;
  int compared = 0;
  for (std::size_t l = 0; l < 3; ++l)
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 4; ++j) {
        const double ca = g.cos_theta[i] * g.cos_phi[j];
        if (ca < 0.25) continue;  // blended toward grazing, not simulated
        const auto r = closed_form(g.lambda_nm[l], ca);
        const JonesReflection& J = t.at(l, i, j);
        worst = std::max({worst, std::abs(J.ss - r.r_s), std::abs(J.pp - r.r_p)});
        worst_cross = std::max({worst_cross, std::abs(J.sp), std::abs(J.ps)});
        ++compared;
      }
  std::printf("[fdtd-table] layered, h = 4 nm, per-entry: %d entries, max |dr| = %.2e, max |cross| = %.2e, %.1f s\n",
              compared, worst, worst_cross, secs);
  CHECK(compared == 33);  // 36 minus cos θ cos φ = 0.24 at three λ
  CHECK(worst < 2e-3);
  CHECK(worst_cross < 2e-3);
  // The entry below kz_min (cos θ cos φ = 0.24, not simulated) is continued to grazing in the
  // impedance form (src/grazing.hpp) from two exact-ε anchors on its radial k line; vs the
  // closed form (the old linear blend into diag(−1, −1) was off by 9.8e-2 here).
  double cont_err = 0;
  for (std::size_t l = 0; l < 3; ++l) {
    const auto r = closed_form(g.lambda_nm[l], 0.24);
    cont_err = std::max({cont_err, std::abs(t.at(l, 0, 0).ss - r.r_s), std::abs(t.at(l, 0, 0).pp - r.r_p)});
  }
  std::printf("[fdtd-table] continued entry (cos a = 0.24) vs closed form: max |dr| = %.2e\n", cont_err);
  CHECK(cont_err < 3e-3);
  CHECK(t.metadata().notes.find("continued to the grazing limit") != std::string::npos);
  // Query: exact grazing and the mirror rule.
  const auto gz = t.query(550, 0.3, kPi / 2);
  CHECK(gz.ss == Complex(-1.0, 0.0));
  CHECK(gz.pp == Complex(-1.0, 0.0));
}

TEST_CASE("fdtd table on a Bloch-k grid (broadband runs) against the closed form", "[fdtd-table]") {
  const double h = 0.005;
  fdtd_table::Options opt;
  opt.nx = 1;
  opt.k_step_per_um = 0.5;
  TableGrid g;
  g.lambda_nm = {550};
  g.cos_theta = {0.8, 1.0};
  g.cos_phi = {0.7, 1.0};
  const auto t0 = std::chrono::steady_clock::now();
  const ReflectionTable t = fdtd_table::build_table([&](double l) { return layered(h, l); }, h, g, {}, opt, {});
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double worst = 0;
  for (std::size_t l = 0; l < 1; ++l)
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t j = 0; j < 2; ++j) {
        const auto r = closed_form(g.lambda_nm[l], g.cos_theta[i] * g.cos_phi[j]);
        worst = std::max({worst, std::abs(t.at(l, i, j).ss - r.r_s), std::abs(t.at(l, i, j).pp - r.r_p)});
      }
  std::printf("[fdtd-table] layered, h = 5 nm, k grid 0.5/um (broadband fit): max |dr| = %.2e, %s, %.1f s\n",
              worst, t.metadata().notes.c_str(), secs);
  // Includes the Lorentz fit of melanin (|dn| up to 5e-3) and bilinear k interpolation.
  CHECK(worst < 1e-2);

  // Resumable: a checkpoint with a truncated last record resumes the finished runs only.
  const auto ck = std::filesystem::temp_directory_path() / "plumage_test_fdtd.partial";
  std::filesystem::remove(ck);
  opt.checkpoint = ck.string();
  opt.checkpoint_tag = "layered-test";
  const ReflectionTable first = fdtd_table::build_table([&](double l) { return layered(h, l); }, h, g, {}, opt, {});
  CHECK(first.content_hash() == t.content_hash());
  std::filesystem::resize_file(ck, std::filesystem::file_size(ck) - 100);
  const ReflectionTable again = fdtd_table::build_table([&](double l) { return layered(h, l); }, h, g, {}, opt, {});
  CHECK(again.content_hash() == t.content_hash());
  CHECK(again.metadata().notes.find("resumed from a checkpoint") != std::string::npos);
  std::printf("[fdtd-table] resumed build: %s\n", again.metadata().notes.c_str());
  std::filesystem::remove(ck);
}

TEST_CASE("x-mirror rule of the Jones matrix on a crystal cell", "[fdtd-table]") {
  const CrystalCell cc = load_crystal_cell(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs/crystals/mallard-green.yaml");
  const fdtd::Cell cell = fdtd_table::cell_from_crystal(cc, 0.55);
  fdtd::SimParams p;
  p.nx = 10;  // 19 nm: coarse, the symmetry holds at any resolution
  const double theta = 0.5, phi = 0.6;
  const std::vector<double> omegas{2 * fdtd::kPi / 0.55};
  const auto [kx, ky] = fdtd_table::engine_k(550, theta, phi);
  const auto [kxm, kym] = fdtd_table::engine_k(550, theta, -phi);
  const auto s = fdtd::run_batch(cell, {{kx, ky}, {kxm, kym}}, omegas, p, 2);
  const JonesReflection a = fdtd_table::jones_from_engine(s[0].freqs[0]);
  const JonesReflection b = fdtd_table::jones_from_engine(s[1].freqs[0]);
  std::printf("[fdtd-table] mirror: ss %.4f%+.4fi / %.4f%+.4fi, sp %.2e%+.2ei / %.2e%+.2ei\n", a.ss.real(),
              a.ss.imag(), b.ss.real(), b.ss.imag(), a.sp.real(), a.sp.imag(), b.sp.real(), b.sp.imag());
  CHECK(std::abs(a.sp) > 1e-3);  // conical incidence on a crystal couples s and p
  CHECK(std::abs(a.ss - b.ss) < 1e-5);
  CHECK(std::abs(a.pp - b.pp) < 1e-5);
  CHECK(std::abs(a.sp + b.sp) < 1e-5);
  CHECK(std::abs(a.ps + b.ps) < 1e-5);
}

TEST_CASE("fdtd_periodic plug-in builds a one-entry table", "[fdtd-table][plugin]") {
  PluginRegistry registry;
  registry.load_library(std::filesystem::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_fdtd_periodic.so");
  auto builder = registry.create_named<TableBuilder>("fdtd_periodic", ParamView{}, registry.context());
  const CrystalCell cc = load_crystal_cell(std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs/crystals/mallard-green.yaml");
  TableGrid g;
  g.lambda_nm = {545};
  g.cos_theta = {1.0};
  g.cos_phi = {1.0};
  std::size_t calls = 0;
  const ReflectionTable t = builder->build(cc, g, [&](std::size_t, std::size_t, std::string_view) { ++calls; });
  CHECK(calls >= 1);
  CHECK(t.metadata().crystal == "mallard-green");
  CHECK(t.metadata().period_nm == 190.0);
  const double R = std::norm(t.at(0, 0, 0).ss);
  std::printf("[fdtd-table] plug-in mallard-green 545 nm normal: |r_s|^2 = %.4f |r_p|^2 = %.4f (res %.1f nm)\n", R,
              std::norm(t.at(0, 0, 0).pp), t.metadata().resolution_nm);
  CHECK(R > 0.05);
  CHECK(R < 0.5);
}
