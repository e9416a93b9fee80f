// Adaptive cross approximation of the far-field kernels of admissible blocks; see aca.hpp.
#include "aca.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "quadrature.hpp"

namespace plumage::bem {

namespace {

// Far-field kernel integrals of a segment pair (the 4×4 Gauss branch of pair_integrals, which every
// pair of an admissible block uses): I_ij = ∫∫ N_i N_j G, X_ij = ∫∫ N_i N_j G' R̂_x, Z_ij = ∫∫ N_i N_j G' R̂_z.
// Unlike P = n̂_A·(X, Z) and Q = n̂_B·(X, Z), these are smooth functions of the two positions only,
// so ACA compresses them reliably (the 8×8 local blocks contain factors such as t̂_A·n̂_B that are
// piecewise constant over a cluster: on the junction body ACA on those left 1e-4 mat-vec errors).
// They are stored divided by h_A h_B (averages over the two segments): the generator's sub-nm edges
// next to 10 nm segments would otherwise get ACA errors ε‖I‖ that the tent-derivative terms
// (÷ h_A h_B) amplify ~10³× (0.3 µm hummingbird segment: solution 5.7e-2 off dense LU).
struct FarKernels {
  Block2 k[3];
};
FarKernels far_kernels(const Segment& A, const Segment& B, cplx gamma, int points) {
  FarKernels out{};
  // w per unit length of both segments (see FarKernels).
  for_each_far_node(A, B, gamma, points,
                    [&](const double* Na, const double* Nb, const Vec2& d, double R, cplx G, cplx dG, double w) {
                      for (int i = 0; i < 2; ++i) {
                        for (int j = 0; j < 2; ++j) {
                          const double wn = w * Na[i] * Nb[j];
                          out.k[0][i][j] += wn * G;
                          out.k[1][i][j] += (wn * d.x / R) * dG;
                          out.k[2][i][j] += (wn * d.z / R) * dG;
                        }
                      }
                    });
  return out;
}

// Entry generator of one admissible block for the three kernels: rows of a test segment
// (2 tents × 2nc) and columns of a basis segment (2nr × 2 tents), cached for the block's lifetime
// (the three kernels' ACAs share them).
struct BlockGenerator {
  const Mesh& mesh;
  const std::vector<int>& order;
  cplx gamma;
  int points;
  int r0, nr, c0, nc;  // segment ranges in `order`
  std::map<int, std::array<Eigen::MatrixXcd, 3>> rows{}, cols{};

  const std::array<Eigen::MatrixXcd, 3>& seg_rows(int ka) {  // 3 × (2 × 2nc)
    auto it = rows.find(ka);
    if (it != rows.end()) return it->second;
    std::array<Eigen::MatrixXcd, 3> R;
    for (auto& m : R) m.resize(2, 2 * nc);
    const Segment& A = mesh.segments[order[r0 + ka]];
    for (int kb = 0; kb < nc; ++kb) {
      const FarKernels f = far_kernels(A, mesh.segments[order[c0 + kb]], gamma, points);
      for (int t = 0; t < 3; ++t) {
        for (int i = 0; i < 2; ++i) {
          for (int j = 0; j < 2; ++j) R[t](i, 2 * kb + j) = f.k[t][i][j];
        }
      }
    }
    return rows.emplace(ka, std::move(R)).first->second;
  }
  const std::array<Eigen::MatrixXcd, 3>& seg_cols(int kb) {  // 3 × (2nr × 2)
    auto it = cols.find(kb);
    if (it != cols.end()) return it->second;
    std::array<Eigen::MatrixXcd, 3> C;
    for (auto& m : C) m.resize(2 * nr, 2);
    const Segment& B = mesh.segments[order[c0 + kb]];
    for (int ka = 0; ka < nr; ++ka) {
      const FarKernels f = far_kernels(mesh.segments[order[r0 + ka]], B, gamma, points);
      for (int t = 0; t < 3; ++t) {
        for (int i = 0; i < 2; ++i) {
          for (int j = 0; j < 2; ++j) C[t](2 * ka + i, j) = f.k[t][i][j];
        }
      }
    }
    return cols.emplace(kb, std::move(C)).first->second;
  }
};

// One kernel (0: I, 1: X, 2: Z) of the block, 2nr × 2nc.
struct FamilyView {
  BlockGenerator& g;
  int kernel;
  int rows() const { return 2 * g.nr; }
  int cols() const { return 2 * g.nc; }
  Eigen::VectorXcd row(int i) { return g.seg_rows(i / 2)[kernel].row(i & 1).transpose(); }
  Eigen::VectorXcd col(int j) { return g.seg_cols(j / 2)[kernel].col(j & 1); }
  Eigen::MatrixXcd dense() {
    Eigen::MatrixXcd D(rows(), cols());
    for (int i = 0; i < rows(); ++i) D.row(i) = row(i).transpose();
    return D;
  }
};

// ACA with partial pivoting (Bebendorf): rank-1 updates from one residual row and one residual
// column at a time until ‖u_k‖‖v_k‖ ≤ ε ‖S_k‖_F (S_k the current approximation, its Frobenius
// norm updated exactly). Falls back to the full block when the rank would not save memory.
void aca(FamilyView& g, double eps, Eigen::MatrixXcd& U, Eigen::MatrixXcd& V) {
  const int m = g.rows(), n = g.cols();
  const int kmax = std::max(1, (m * n) / (m + n) / 2);
  std::vector<Eigen::VectorXcd> us, vs;
  std::vector<char> used(m, 0);
  double norm2 = 0.0;
  int i = 0;
  bool converged = false;
  while (static_cast<int>(us.size()) < kmax) {
    Eigen::VectorXcd r = g.row(i);
    for (std::size_t l = 0; l < us.size(); ++l) r -= us[l][i] * vs[l];
    used[i] = 1;
    Eigen::Index j = 0;
    const double rmax = r.size() ? r.cwiseAbs().maxCoeff(&j) : 0.0;
    if (rmax == 0.0 || rmax <= 1e-15 * std::sqrt(norm2 / (double(m) * n))) {
      // this row is already represented, or exactly zero (e.g. K_tt ∝ t̂_A·n̂_B vanishes for parallel
      // segments): try the other unused rows, spread over the cluster (golden-ratio stride), until
      // one is not — a structurally zero sub-block never gets here (skipped by the caller)
      int next = -1;
      const int stride = std::max(1, static_cast<int>(0.618 * m)) | 1;
      for (int t = 1; t <= m && next < 0; ++t) {
        const int cand = static_cast<int>((i + static_cast<long>(t) * stride) % m);
        if (!used[cand]) next = cand;
      }
      for (int t = 0; t < m && next < 0; ++t) {
        if (!used[t]) next = t;
      }
      if (next < 0) {
        converged = true;
        break;
      }
      i = next;
      continue;
    }
    Eigen::VectorXcd v = r / r[j];
    Eigen::VectorXcd u = g.col(static_cast<int>(j));
    for (std::size_t l = 0; l < us.size(); ++l) u -= vs[l][j] * us[l];
    const double uu = u.squaredNorm(), vv = v.squaredNorm();
    std::complex<double> crossed = 0.0;
    for (std::size_t l = 0; l < us.size(); ++l) crossed += us[l].dot(u) * vs[l].dot(v);
    norm2 += uu * vv + 2.0 * crossed.real();
    us.push_back(std::move(u));
    vs.push_back(std::move(v));
    if (std::sqrt(uu * vv) <= eps * std::sqrt(norm2)) {
      // Partial pivoting can stop on one group of rows while another group, coupled to other
      // columns, is not represented yet (seen on the junction body: 1.9e-3 mat-vec error at
      // ε = 1e-6). Check a few unused rows spread over the block; continue from the worst one.
      const int stride = std::max(1, static_cast<int>(0.618 * m)) | 1;
      double worst = 0.0;
      int worst_row = -1, checked = 0;
      for (int t = 1; t <= m && checked < 6; ++t) {
        const int cand = static_cast<int>((i + static_cast<long>(t) * stride) % m);
        if (used[cand]) continue;
        ++checked;
        Eigen::VectorXcd rc = g.row(cand);
        for (std::size_t l = 0; l < us.size(); ++l) rc -= us[l][cand] * vs[l];
        const double e = rc.norm();
        if (e > worst) worst = e, worst_row = cand;
      }
      if (worst_row < 0 || worst * std::sqrt(double(m)) <= eps * std::sqrt(norm2)) {
        converged = true;
        break;
      }
      i = worst_row;
      continue;
    }
    // next pivot row: largest entry of the new column among the unused rows
    double best = -1.0;
    const Eigen::VectorXcd& ul = us.back();
    for (int t = 0; t < m; ++t) {
      if (!used[t] && std::abs(ul[t]) > best) best = std::abs(ul[t]), i = t;
    }
    if (best < 0) {
      converged = true;
      break;
    }
  }
  if (!converged) {
    U = g.dense();
    V.resize(0, 0);
    return;
  }
  U.resize(m, static_cast<Eigen::Index>(us.size()));
  V.resize(static_cast<Eigen::Index>(us.size()), n);
  for (std::size_t l = 0; l < us.size(); ++l) {
    U.col(static_cast<Eigen::Index>(l)) = us[l];
    V.row(static_cast<Eigen::Index>(l)) = vs[l].transpose();
  }
}

}  // namespace

void compress_far_kernels(const Mesh& mesh, const std::vector<int>& order, cplx gamma, int points, int r0, int nr,
                          int c0, int nc, double eps, Eigen::MatrixXcd (&U)[3], Eigen::MatrixXcd (&V)[3]) {
  BlockGenerator g{mesh, order, gamma, points, r0, nr, c0, nc};
  for (int kernel = 0; kernel < 3; ++kernel) {
    FamilyView view{g, kernel};
    aca(view, eps, U[kernel], V[kernel]);
  }
}

}  // namespace plumage::bem
