// Probe: where the time of one preconditioned GMRES iteration goes (development tool, not a test).
// Near-field LU (Eigen SparseLU/COLAMD; optionally others) fill-in, factor and solve times (1 and
// several right-hand sides at once), near-field SpMV and the full H mat-vec. Usage:
//   bem_probe_precond <species.yaml> <lambda_nm> <ppw> [nrhs] [variants: colamd,amdonly,umfpack]
// Environment: LEAF, ETA (H-matrix leaf size, admissibility), GMRES_RHS=k (also run GMRES on k beam right-hand sides), MATVEC_REPS=r (mat-vec
// timing only), COUNT_LEAVES=1 (near-field size per leaf size and eta, no integrals),
// UMF_ORDERING / UMF_STRATEGY / UMF_REPORT (UMFPACK controls).
#include <sys/resource.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "bem_solver.hpp"
#include "gmres.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::bem;
using SpMat = Eigen::SparseMatrix<std::complex<double>>;

static double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
static double cpu_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec + u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
}
static double rss_gb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1048576.0;
}

template <class Solver>
void time_solves(const char* name, const Solver& lu, const Eigen::MatrixXcd& B) {
  Eigen::VectorXcd x;
  auto t0 = std::chrono::steady_clock::now();
  double c0 = cpu_s();
  for (int r = 0; r < 3; ++r) x = lu.solve(B.col(0));
  std::printf("  %s solve 1 rhs: %.4f s (cpu %.4f)\n", name, since(t0) / 3, (cpu_s() - c0) / 3);
  t0 = std::chrono::steady_clock::now();
  c0 = cpu_s();
  Eigen::MatrixXcd X = lu.solve(B);
  std::printf("  %s solve %ld rhs at once: %.4f s per rhs (cpu %.4f)\n", name, (long)B.cols(), since(t0) / B.cols(),
              (cpu_s() - c0) / B.cols());
  std::fflush(stdout);
}

static Eigen::MatrixXcd run_gmres(const char* name, const HMatrix& H, const Op& M, const Eigen::MatrixXcd& B) {
  const Op A = [&](const Eigen::VectorXcd& in, Eigen::VectorXcd& out) { H.apply(in, out); };
  Eigen::MatrixXcd X(B.rows(), B.cols());
  std::printf("  %s GMRES 1e-6:", name);
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    Eigen::VectorXcd x = Eigen::VectorXcd::Zero(B.rows());
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_s();
    const GmresResult r = gmres(A, M, B.col(c), x, 1e-6, 300, 3000);
    std::printf(" [%d it, %.1f s, cpu %.1f, %.3f s/it]", r.iterations, since(t0), cpu_s() - c0,
                (cpu_s() - c0) / std::max(1, r.iterations));
    std::fflush(stdout);
    X.col(c) = x;
  }
  std::printf("\n");
  return X;
}

int main(int argc, char** argv) {
  const auto cfg = load_species_config(argv[1], plumage::testing::registry());
  const double lambda = atof(argv[2]), ppw = atof(argv[3]);
  const int nrhs = argc > 4 ? atoi(argv[4]) : 4;
  const std::string variants = argc > 5 ? argv[5] : "colamd";
  const CrossSection cs = cfg.structure->generate(0);
  const auto prep = prepare_geometry(cs);
  BemOptions o;
  o.points_per_wavelength = ppw;
  o.method = BemOptions::Method::hmatrix;
  if (getenv("LEAF")) o.hmatrix.leaf_size = atoi(getenv("LEAF"));
  if (getenv("ETA")) o.hmatrix.eta = atof(getenv("ETA"));
  const double k0 = 2.0 * std::numbers::pi / lambda, beta = 0.0;
  const Mesh mesh = build_mesh(prep->geometry, lambda, ppw);
  const auto med = media(prep->geometry, lambda, beta);
  if (getenv("COUNT_LEAVES")) {  // near-field size per leaf size, from the block partition only
    std::printf("N %d segments %zu domains %d\n", mesh.unknowns(), mesh.segments.size(), mesh.a_count);
    for (int leaf : {6, 8, 12, 16, 24}) {
      for (double eta : {1.0, 2.0}) {
        double nnz = 0, pre_close = 0;
        long adm = 0;
        for (int d = 0; d < mesh.a_count; ++d) {
          const ClusterTree t = build_cluster_tree(mesh, mesh.domain_segments[d], leaf);
          const BlockPartition part = partition_blocks(t, eta, 1.01 * o.quadrature.near_factor);
          adm += static_cast<long>(part.admissible.size());
          for (const BlockPair& bp : part.near) nnz += 64.0 * t.nodes[bp.row].size() * t.nodes[bp.col].size();
        }
        (void)pre_close;
        std::printf("leaf %d eta %.0f: near entries (with duplicates across domains) %.3g = %.0f/row, %.2f GB per copy; "
                    "admissible blocks %ld\n", leaf, eta, nnz, nnz / mesh.unknowns(), nnz * 20 / 1e9, adm);
      }
    }
    return 0;
  }
  auto t0 = std::chrono::steady_clock::now();
  HMatrix H(mesh, med, k0, beta, o.quadrature, o.hmatrix);
  const int n = H.size();
  const HMatrixStats& st = H.stats();
  std::printf("N %d: near nnz %ld (%.0f/row), blocks %ld rank %.1f, H %.2f GB, build %.1f s, rss %.2f GB\n", n,
              st.near_nonzeros, double(st.near_nonzeros) / n, st.admissible_blocks, st.mean_rank, st.memory_gb(),
              since(t0), rss_gb());
  SpMat S = H.take_preconditioner_matrix();
  std::mt19937 rng(7);
  std::normal_distribution<double> nd;
  Eigen::MatrixXcd B(n, nrhs);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < nrhs; ++c) B(i, c) = {nd(rng), nd(rng)};
  {
    Eigen::VectorXcd y;
    const Eigen::VectorXcd x = B.col(0);
    t0 = std::chrono::steady_clock::now();
    double c0 = cpu_s();
    const int reps = getenv("MATVEC_REPS") ? atoi(getenv("MATVEC_REPS")) : 5;
    for (int r = 0; r < reps; ++r) H.apply(x, y);
    std::printf("H mat-vec: %.4f s (cpu %.4f), |y| = %.17g\n", since(t0) / reps, (cpu_s() - c0) / reps, y.norm());
    t0 = std::chrono::steady_clock::now();
    c0 = cpu_s();
    for (int r = 0; r < 5; ++r) y = H.near() * x;
    std::printf("near SpMV (serial): %.4f s (cpu %.4f)\n", since(t0) / 5, (cpu_s() - c0) / 5);
    std::fflush(stdout);
    if (getenv("MATVEC_REPS")) return 0;
  }
  const int ngm = getenv("GMRES_RHS") ? atoi(getenv("GMRES_RHS")) : 0;
  Eigen::MatrixXcd Bb(n, ngm), Xref;
  for (int c = 0; c < ngm; ++c) {
    fill_rhs(mesh, k0, incident_for(*prep, o, k0, 0.0, std::acos(0.05 * (c / 2 + 1)), c % 2), Bb.col(c));
  }
  if (variants.find("colamd") != std::string::npos) {
    Eigen::SparseLU<SpMat> lu;
    t0 = std::chrono::steady_clock::now();
    double c0 = cpu_s();
    lu.analyzePattern(S);
    lu.factorize(S);
    std::printf("SparseLU COLAMD: factor %.2f s (cpu %.2f), nnz L %ld U %ld (%.1f x near), rss %.2f GB\n", since(t0),
                cpu_s() - c0, (long)lu.nnzL(), (long)lu.nnzU(), double(lu.nnzL() + lu.nnzU()) / S.nonZeros(), rss_gb());
    Eigen::VectorXcd x = lu.solve(B.col(0));
    std::printf("  COLAMD LU residual |S x - b|/|b| = %.2e\n", (S * x - B.col(0)).norm() / B.col(0).norm());
    time_solves("COLAMD", lu, B);
    if (ngm) {
      const Op M = [&](const Eigen::VectorXcd& in, Eigen::VectorXcd& out) { out = lu.solve(in); };
      const Eigen::MatrixXcd X = run_gmres("COLAMD", H, M, Bb);
      if (Xref.size()) std::printf("  |X_colamd - X_ref|/|X_ref| = %.2e\n", (X - Xref).norm() / Xref.norm());
      else Xref = X;
    }
  }
  if (variants.find("amdonly") != std::string::npos) {
    Eigen::SparseLU<SpMat, Eigen::AMDOrdering<int>> lu;
    t0 = std::chrono::steady_clock::now();
    double c0 = cpu_s();
    lu.analyzePattern(S);
    lu.factorize(S);
    std::printf("SparseLU AMD: factor %.2f s (cpu %.2f), nnz L %ld U %ld (%.1f x near), rss %.2f GB\n", since(t0),
                cpu_s() - c0, (long)lu.nnzL(), (long)lu.nnzU(), double(lu.nnzL() + lu.nnzU()) / S.nonZeros(), rss_gb());
    time_solves("AMD", lu, B);
  }
  if (variants.find("umfpack") != std::string::npos) {
    Eigen::UmfPackLU<SpMat> lu;
    if (getenv("UMF_ORDERING")) lu.umfpackControl()[UMFPACK_ORDERING] = atof(getenv("UMF_ORDERING"));
    if (getenv("UMF_STRATEGY")) lu.umfpackControl()[UMFPACK_STRATEGY] = atof(getenv("UMF_STRATEGY"));
    t0 = std::chrono::steady_clock::now();
    double c0 = cpu_s();
    lu.compute(S);
    std::printf("UMFPACK: factor %.2f s (cpu %.2f), info %d, rss %.2f GB\n", since(t0), cpu_s() - c0, (int)lu.info(),
                rss_gb());
    std::fflush(stdout);
    if (getenv("UMF_REPORT")) lu.printUmfpackInfo();
    std::fflush(stdout);
    time_solves("UMFPACK", lu, B);
  }
  std::printf("peak rss %.2f GB\n", rss_gb());
}
