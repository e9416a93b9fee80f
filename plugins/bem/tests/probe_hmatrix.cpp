// Probe: hierarchical matrix vs the dense matrix on a species barbule or a coated cylinder
// (development tool, not a test). Usage:
//   bem_probe_hmatrix <species.yaml | coated> <lambda_nm> <ppw> <aca_tol> [dense 0/1] [eta] [leaf] [prefactor] [nrhs]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "bem_solver.hpp"
#include "bem_test_support.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::bem;

static double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int main(int argc, char** argv) {
  const std::string src = argv[1];
  const double lambda = atof(argv[2]), ppw = atof(argv[3]), tol = atof(argv[4]);
  const bool dense = argc > 5 && atoi(argv[5]);
  CrossSection cs;
  if (src == "coated") {
    cs = plumage::bem::testing::layered_cylinder({250.0, 350.0}, {Material::keratin(), Material::melanin()}, lambda, ppw);
  } else if (src == "junction") {
    cs = plumage::bem::testing::junction_body();
  } else {
    cs = load_species_config(src, plumage::testing::registry()).structure->generate(0);
  }
  BemOptions o;
  o.points_per_wavelength = ppw;
  o.method = BemOptions::Method::hmatrix;
  if (src == "coated" || src == "junction") o.incidence = BemOptions::Incidence::plane_wave;
  o.hmatrix.aca_tolerance = tol;
  if (argc > 6) o.hmatrix.eta = atof(argv[6]);
  if (argc > 7) o.hmatrix.leaf_size = atoi(argv[7]);
  if (argc > 8) o.hmatrix.preconditioner_factor = atof(argv[8]);
  const int nrhs = argc > 9 ? atoi(argv[9]) : 2;
  if (argc > 10) o.gmres_tolerance = atof(argv[10]);
  if (argc > 11) o.gmres_restart = atoi(argv[11]);
  o.gmres_max_iterations = 3000;
  const auto prep = prepare_geometry(cs);
  const double theta = getenv("THETA") ? atof(getenv("THETA")) : 0.0;
  auto t0 = std::chrono::steady_clock::now();
  const auto sys = build_system(prep->geometry, lambda, theta, o);
  const HMatrixStats& st = sys->hmatrix->stats();
  std::printf("N %d segments %zu: near %.1f s (%ld pairs, %ld nnz = %.0f/row), ACA %.1f s (%ld blocks, %ld dense, "
              "rank mean %.1f max %d), H memory %.2f GB, precond nnz %ld, LU %.1f s, total %.1f s\n",
              sys->mesh.unknowns(), sys->mesh.segments.size(), st.near_seconds, st.near_pairs, st.near_nonzeros,
              double(st.near_nonzeros) / sys->mesh.unknowns(), st.aca_seconds, st.admissible_blocks, st.dense_blocks,
              st.mean_rank, st.max_rank, st.memory_gb(), st.preconditioner_nonzeros, sys->factor_seconds, since(t0));
  std::fflush(stdout);
  const int n = sys->mesh.unknowns();
  if (getenv("ENTRYWISE")) {
    const Eigen::MatrixXcd Z = assemble_dense(sys->mesh, sys->media, sys->k0, sys->beta, o.quadrature);
    Eigen::MatrixXcd Zh(n, n);
    Eigen::VectorXcd e = Eigen::VectorXcd::Zero(n), col;
    for (int j = 0; j < n; ++j) {
      e[j] = 1;
      sys->hmatrix->apply(e, col);
      Zh.col(j) = col;
      e[j] = 0;
    }
    Eigen::Index bi, bj;
    const double m = (Zh - Z).cwiseAbs().maxCoeff(&bi, &bj);
    std::printf("max entry error %.3e at (%ld, %ld), Z there %.3e, max|Z| %.3e; n_t %d n_z %d; |Zh-Z|/|Z| %.2e\n", m, (long)bi,
                (long)bj, std::abs(Z(bi, bj)), Z.cwiseAbs().maxCoeff(), sys->mesh.n_t, sys->mesh.n_z, (Zh - Z).norm() / Z.norm());
    // worst rows
    Eigen::VectorXd rowerr = (Zh - Z).rowwise().norm();
    for (int k = 0; k < 8; ++k) {
      Eigen::Index r;
      rowerr.maxCoeff(&r);
      Eigen::Index c;
      (Zh - Z).row(r).cwiseAbs().maxCoeff(&c);
      std::printf("  row %ld err %.3e |Z row| %.3e worst col %ld\n", (long)r, rowerr[r], Z.row(r).norm(), (long)c);
      rowerr[r] = 0;
    }
    return 0;
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> nd;
  Eigen::VectorXcd x(n), y;
  for (int i = 0; i < n; ++i) x[i] = {nd(rng), nd(rng)};
  t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < 5; ++r) sys->hmatrix->apply(x, y);
  std::printf("mat-vec %.3f s\n", since(t0) / 5);
  std::fflush(stdout);
  // right-hand sides: beam at 20 azimuths as the solver does (first nrhs/2 azimuths)
  Eigen::MatrixXcd B(n, nrhs);
  for (int c = 0; c < nrhs; ++c) {
    const double phi = std::acos(0.05 * (c / 2 + 1));
    fill_rhs(sys->mesh, sys->k0, incident_for(*prep, o, sys->k0, theta, phi, c % 2), B.col(c));
  }
  for (int warm = 0; warm < 2; ++warm) {
    o.warm_start = warm;
    std::vector<int> its;
    t0 = std::chrono::steady_clock::now();
    Eigen::MatrixXcd X;
    try {
      X = sys->solve(B, o, &its);
    } catch (const std::exception& e) {
      std::printf("GMRES: %s\n", e.what());
      return 1;
    }
    std::printf("GMRES warm %d: %.1f s, iterations", warm, since(t0));
    for (int i : its) std::printf(" %d", i);
    std::printf("\n");
    std::fflush(stdout);
    if (dense && warm == 1) {
      t0 = std::chrono::steady_clock::now();
      const Eigen::MatrixXcd Z = assemble_dense(sys->mesh, sys->media, sys->k0, sys->beta, o.quadrature);
      const Eigen::VectorXcd yd = Z * x;
      std::printf("dense assembly %.1f s; mat-vec |Hx - Zx|/|Zx| = %.2e\n", since(t0), (y - yd).norm() / yd.norm());
      const auto& N = sys->hmatrix->near();
      double dmax = 0, zmax = Z.cwiseAbs().maxCoeff();
      for (int r = 0; r < N.outerSize(); ++r)
        for (Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor>::InnerIterator it(N, r); it; ++it)
          dmax = std::max(dmax, std::abs(it.value() - Z(it.row(), it.col())));
      std::printf("near entries max |N - Z| / max|Z| = %.2e\n", dmax / zmax);
      const Eigen::MatrixXcd Xd = Z.partialPivLu().solve(B);
      std::printf("solution |x_H - x_LU|/|x_LU| = %.2e\n", (X - Xd).norm() / Xd.norm());
    }
  }
}
