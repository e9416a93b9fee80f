// Probe: preconditioners of method hmatrix on a species barbule segment (development tool, not a
// test; NOTES.md §5 "Preconditioner hodlr"). Usage:
//   bem_probe_hodlr <species.yaml> <width_um> <lambda_nm> <ppw> <near_field|hodlr> [nrhs] [dense 0/1]
// env: GMAX (GMRES iterations per right-hand side, 1500), HTOL (hodlr_tolerance), HLEAF (hodlr_leaf_size), HRANK (hodlr_max_rank), GTOL (GMRES, 1e-6),
// THETA (rad), LEAF (H-matrix leaf_size), GBLOCK (gmres_block: right-hand sides solved together). Prints setup and solve times (wall and process CPU),
// iterations per right-hand side, peak RSS, and with dense = 1 the far-field intensity against dense LU.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "bem_solver.hpp"
#include "radiation.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::bem;

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
double cpu() { return double(std::clock()) / CLOCKS_PER_SEC; }
double peak_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1e6;
}
double env(const char* k, double d) { return getenv(k) ? atof(getenv(k)) : d; }

// Relative L2 of the far-field intensity per right-hand side, worst of them.
double far_l2(const Eigen::MatrixXcd& fa, const Eigen::MatrixXcd& fb) {
  double worst = 0;
  for (Eigen::Index c = 0; c < fa.cols(); ++c) {
    double num = 0, den = 0;
    for (Eigen::Index d = 0; d < fa.rows() / 3; ++d) {
      double ia = 0, ib = 0;
      for (int k = 0; k < 3; ++k) ia += std::norm(fa(3 * d + k, c)), ib += std::norm(fb(3 * d + k, c));
      num += (ia - ib) * (ia - ib), den += ia * ia;
    }
    worst = std::max(worst, std::sqrt(num / den));
  }
  return worst;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) return 2;
  const double width = atof(argv[2]), lambda = atof(argv[3]), ppw = atof(argv[4]);
  const std::string pre = argv[5];
  const int nrhs = argc > 6 ? atoi(argv[6]) : 4;
  const bool dense = argc > 7 && atoi(argv[7]);
  const CrossSection cs = load_species_segment(argv[1], width, plumage::testing::registry()).structure->generate(0);
  BemOptions o;
  o.points_per_wavelength = ppw;
  o.method = BemOptions::Method::hmatrix;
  o.gmres_tolerance = env("GTOL", 1e-6);
  o.gmres_max_iterations = static_cast<int>(env("GMAX", 1500));
  o.hmatrix.leaf_size = static_cast<int>(env("LEAF", o.hmatrix.leaf_size));
  if (pre == "hodlr") o.hmatrix.preconditioner = HMatrixOptions::Preconditioner::hodlr;
  o.hodlr.tolerance = env("HTOL", o.hodlr.tolerance);
  o.hodlr.leaf_size = static_cast<int>(env("HLEAF", o.hodlr.leaf_size));
  o.hodlr.max_rank = static_cast<int>(env("HRANK", o.hodlr.max_rank));
  o.gmres_block = static_cast<int>(env("GBLOCK", o.gmres_block));
  const double theta = env("THETA", 0.0);
  const auto prep = prepare_geometry(cs);
  auto t0 = std::chrono::steady_clock::now();
  double c0 = cpu();
  const auto sys = build_system(prep->geometry, lambda, theta, o, nrhs);
  const int n = sys->mesh.unknowns();
  const HMatrixStats& st = sys->hmatrix->stats();
  std::printf("%s width %.2f um, %.0f nm, %.0f ppw: N %d; H-matrix %.1f s (near %.1f, ACA %.1f; %.2f GB); "
              "preconditioner %s %.1f s; setup %.1f s wall %.1f s CPU; RSS peak %.2f GB\n",
              argv[1], width, lambda, ppw, n, sys->assembly_seconds, st.near_seconds, st.aca_seconds, st.memory_gb(),
              pre.c_str(), sys->factor_seconds, since(t0), cpu() - c0, peak_gb());
  if (sys->hodlr) {
    const HodlrStats& hs = sys->hodlr->stats();
    std::printf("  hodlr tol %.0e leaf %d: levels %d, rank mean %.1f max %d, capped %d, %.2f GB; thread-s compress "
                "%.1f factor %.1f\n", o.hodlr.tolerance, o.hodlr.leaf_size, hs.levels, hs.mean_rank, hs.max_rank,
                hs.capped_blocks, hs.memory_gb, hs.seconds_compress, hs.seconds_factor);
  }
  std::fflush(stdout);
  Eigen::MatrixXcd B(n, nrhs);
  for (int c = 0; c < nrhs; ++c) {
    const double phi = std::acos(0.05 * (c / 2 + 1));
    fill_rhs(sys->mesh, sys->k0, incident_for(*prep, o, sys->k0, theta, phi, c % 2), B.col(c));
  }
  std::vector<int> its;
  t0 = std::chrono::steady_clock::now();
  c0 = cpu();
  const Eigen::MatrixXcd X = sys->solve(B, o, &its);
  std::printf("  GMRES %.0e: %.1f s wall %.1f s CPU, iterations", o.gmres_tolerance, since(t0), cpu() - c0);
  for (int i : its) std::printf(" %d", i);
  std::printf("; RSS peak %.2f GB\n", peak_gb());
  std::fflush(stdout);
  if (getenv("GBLOCK2")) {  // the same system again with another gmres_block: time and solution change
    BemOptions o2 = o;
    o2.gmres_block = static_cast<int>(env("GBLOCK2", 1));
    std::vector<int> its2;
    t0 = std::chrono::steady_clock::now();
    c0 = cpu();
    const Eigen::MatrixXcd X2 = sys->solve(B, o2, &its2);
    std::printf("  GMRES with gmres_block %d: %.1f s wall %.1f s CPU, iterations", o2.gmres_block, since(t0), cpu() - c0);
    for (int i : its2) std::printf(" %d", i);
    std::printf("; |X - X_block%d| / |X| = %.2e\n", o.gmres_block, (X2 - X).norm() / X.norm());
    std::fflush(stdout);
  }
  if (dense) {
    BemOptions d;
    d.points_per_wavelength = ppw;
    const auto ds = build_system(prep->geometry, lambda, theta, d, nrhs);
    const Eigen::MatrixXcd Xd = ds->solve(B, d);
    std::vector<double> po;
    for (int k = 0; k < 181; ++k) po.push_back(-1.55 + 3.1 * k / 180.0);
    const Eigen::MatrixXcd F = far_field_operator(sys->mesh, sys->k0, theta, po);
    std::printf("  vs dense LU: |x - x_LU|/|x_LU| = %.2e, far-field intensity L2 (181 directions) %.2e\n",
                (X - Xd).norm() / Xd.norm(), far_l2(F * Xd, F * X));
  }
}
