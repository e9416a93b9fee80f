// HODLR preconditioner of method hmatrix (hodlr.hpp, hmatrix_entries.hpp; NOTES.md §5 "Preconditioner hodlr"):
// the entry oracle against the dense matrix, the factor's inverse against the dense matrix, and
// GMRES with it against dense LU on small multi-body problems, and its independence of the thread count.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <random>

#include "bem_test_support.hpp"
#include "hmatrix_entries.hpp"
#include "test_registry.hpp"

using namespace plumage;
using namespace plumage::bem;
using namespace plumage::bem::testing;

namespace {

// A keratin slab 1.2 µm × 0.4 µm holding a row of six melanin rods (r = 60 nm) and an air
// bubble: seven bodies inside one, the kind of structure a barbule is.
CrossSection slab_with_rods() {
  CrossSection cs;
  cs.label = "slab with rods";
  Polygon slab;
  const int nx = 24, nz = 8;
  for (int k = 0; k < nx; ++k) slab.push_back({-600.0 + 1200.0 * k / nx, -200.0});
  for (int k = 0; k < nz; ++k) slab.push_back({600.0, -200.0 + 400.0 * k / nz});
  for (int k = 0; k < nx; ++k) slab.push_back({600.0 - 1200.0 * k / nx, 200.0});
  for (int k = 0; k < nz; ++k) slab.push_back({-600.0, 200.0 - 400.0 * k / nz});
  cs.regions.push_back({slab, Material::keratin(), RegionRole::body});
  for (int r = 0; r < 7; ++r) {
    Polygon c = circle_polygon(60.0, 48);
    for (Vec2& v : c) v.x += -480.0 + 160.0 * r, v.z += (r % 2 ? 60.0 : -60.0);
    Region reg{c, r == 6 ? Material::constant(1.0) : Material::melanin(), RegionRole::body};
    reg.parent = 0;
    cs.regions.push_back(reg);
  }
  return cs;
}

struct Setup {
  std::unique_ptr<System> sys;
  Eigen::MatrixXcd Z;
};

Setup make(const CrossSection& cs, BemOptions o, double ppw) {
  o.points_per_wavelength = ppw;
  o.method = BemOptions::Method::hmatrix;
  o.hmatrix.aca_tolerance = 1e-8;
  const auto prep = prepare_geometry(cs);
  Setup s;
  s.sys = build_system(prep->geometry, 550.0, deg_to_rad(30.0), o);
  s.Z = assemble_dense(s.sys->mesh, s.sys->media, s.sys->k0, s.sys->beta, o.quadrature);
  return s;
}

}  // namespace

TEST_CASE("bem hodlr: rows and columns of the H-matrix (entry oracle) equal the dense matrix") {
  BemOptions o;
  const Setup s = make(slab_with_rods(), o, 12.0);
  const System& sys = *s.sys;
  const int n = sys.mesh.unknowns();
  HodlrOptions ho;
  ho.leaf_size = 64;
  const HodlrLU tree(unknown_positions(sys.mesh), ho);
  const std::vector<int>& perm = tree.perm();
  const HMatrixEntries entries(*sys.hmatrix, sys.mesh, sys.media, perm);
  // the full window and a window of the second half (its box from its points)
  const std::vector<Vec2> pts = unknown_positions(sys.mesh);
  auto window = [&](int b, int e) {
    IndexBox w{b, e, 1e300, -1e300, 1e300, -1e300};
    for (int p = b; p < e; ++p) {
      w.xmin = std::min(w.xmin, pts[perm[p]].x), w.xmax = std::max(w.xmax, pts[perm[p]].x);
      w.zmin = std::min(w.zmin, pts[perm[p]].z), w.zmax = std::max(w.zmax, pts[perm[p]].z);
    }
    return w;
  };
  double worst = 0;
  for (const IndexBox& w : {window(0, n), window(n / 2, n)}) {
    for (int p = 0; p < n; p += 97) {
      Eigen::VectorXcd r, c, rd(w.size()), cd(w.size());
      entries.row(p, w, r);
      entries.column(p, w, c);
      for (int q = w.begin; q < w.end; ++q) rd[q - w.begin] = s.Z(perm[p], perm[q]), cd[q - w.begin] = s.Z(perm[q], perm[p]);
      worst = std::max({worst, (r - rd).norm() / rd.norm(), (c - cd).norm() / cd.norm()});
    }
  }
  std::printf("  entry oracle, slab with rods: N = %d, worst row/column |Z_H - Z|/|Z| = %.1e\n", n, worst);
  CHECK(worst <= 1e-6);
}

TEST_CASE("bem hodlr: the factor inverts the operator to its tolerance; GMRES with it reproduces dense LU") {
  int near_field_iterations = 0;
  {
    BemOptions o;  // the near-field LU on the same problem, for comparison
    o.method = BemOptions::Method::hmatrix;
    o.gmres_tolerance = 1e-10;
    const Setup s = make(slab_with_rods(), o, 12.0);
    Eigen::MatrixXcd B(s.sys->mesh.unknowns(), 1);
    fill_rhs(s.sys->mesh, s.sys->k0, plane_wave(deg_to_rad(30.0), 0.7, 0), B.col(0));
    std::vector<int> its;
    (void)s.sys->solve(B, o, &its);
    near_field_iterations = its[0];
    std::printf("  near-field LU, slab with rods: %d iterations\n", near_field_iterations);
  }
  for (const double tol : {1e-2, 1e-4}) {
    BemOptions o;
    o.method = BemOptions::Method::hmatrix;
    o.hmatrix.preconditioner = HMatrixOptions::Preconditioner::hodlr;
    o.hodlr.tolerance = tol;
    o.hodlr.leaf_size = 64;
    o.gmres_tolerance = 1e-10;
    const Setup s = make(slab_with_rods(), o, 12.0);
    const System& sys = *s.sys;
    const int n = sys.mesh.unknowns();
    REQUIRE(sys.hodlr != nullptr);
    CHECK(sys.near_field == nullptr);
    // ‖H⁻¹ Z x − x‖ / ‖x‖ for a random x
    std::mt19937 rng(3);
    std::normal_distribution<double> nd;
    Eigen::VectorXcd x(n), y;
    for (int i = 0; i < n; ++i) x[i] = {nd(rng), nd(rng)};
    sys.hodlr->apply(s.Z * x, y);
    const double inverse_error = (y - x).norm() / x.norm();
    Eigen::MatrixXcd B(n, 4);
    for (int c = 0; c < 4; ++c) fill_rhs(sys.mesh, sys.k0, plane_wave(deg_to_rad(30.0), 0.7 + 0.2 * (c / 2), c % 2), B.col(c));
    std::vector<int> its;
    const Eigen::MatrixXcd xh = sys.solve(B, o, &its);
    const Eigen::MatrixXcd xd = s.Z.partialPivLu().solve(B);
    const double diff = (xh - xd).norm() / xd.norm();
    const HodlrStats& st = sys.hodlr->stats();
    std::printf("  hodlr tol %.0e, slab with rods: N = %d, levels %d, mean rank %.1f (max %d), %.3f GB, "
                "|H^-1 Z x - x|/|x| = %.1e, iterations %d %d %d %d, |x - x_LU|/|x_LU| = %.1e\n",
                tol, n, st.levels, st.mean_rank, st.max_rank, st.memory_gb, inverse_error, its[0], its[1], its[2],
                its[3], diff);
    CHECK(st.levels >= 3);
    CHECK(st.capped_blocks == 0);
    // the solution is the H-matrix's (ACA 1e-8: mat-vec error ~2e-8), whatever the preconditioner
    CHECK(diff <= 1e-7);
    if (tol < 1e-3) {
      CHECK(inverse_error <= 0.1);
      for (int it : its) CHECK(it <= 10);
      for (int it : its) CHECK(it < near_field_iterations);
    }
  }
}

TEST_CASE("bem hodlr: the factor does not depend on the thread count") {
  BemOptions o;
  o.method = BemOptions::Method::hmatrix;
  o.hmatrix.preconditioner = HMatrixOptions::Preconditioner::hodlr;
  o.hodlr.leaf_size = 64;
  o.points_per_wavelength = 12.0;
  const auto prep = prepare_geometry(slab_with_rods());
  Eigen::VectorXcd y[2];
  for (int threads = 1; threads <= 2; ++threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const auto sys = build_system(prep->geometry, 550.0, deg_to_rad(30.0), o);
    Eigen::VectorXcd x(sys->mesh.unknowns());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = {std::cos(0.37 * i), std::sin(0.11 * i)};
    sys->hodlr->apply(x, y[threads - 1]);
  }
  CHECK((y[0] - y[1]).cwiseAbs().maxCoeff() == 0.0);
}
