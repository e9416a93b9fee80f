// ACA with partial pivoting and QR + SVD recompression for the HODLR off-diagonal blocks (hodlr.hpp).
#include <Eigen/QR>
#include <algorithm>
#include <Eigen/SVD>
#include <cmath>
#include <vector>

#include "hodlr.hpp"

namespace plumage::bem {

namespace {

using Mat = Eigen::MatrixXcd;
using Vec = Eigen::VectorXcd;

// Rows and columns checked when the ACA stopping test passes.
constexpr int kChecks = 8;

// U V = Qu (Ru Rvᵀ) Qvᵀ; the small core's SVD truncated where the dropped singular values carry
// a relative Frobenius share ≤ eps.
void recompress(Mat& U, Mat& V, double eps) {
  const Eigen::Index k = U.cols();
  if (k == 0) return;
  Eigen::HouseholderQR<Mat> qu(U);
  Eigen::HouseholderQR<Mat> qv(V.transpose());
  const Eigen::Index ku = std::min(k, U.rows()), kv = std::min(k, V.cols());
  const Mat Ru = qu.matrixQR().topRows(ku).triangularView<Eigen::Upper>();
  const Mat Rv = qv.matrixQR().topRows(kv).triangularView<Eigen::Upper>();
  const Mat core = Ru * Rv.transpose();  // ku × kv
  Eigen::BDCSVD<Mat> svd(core, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double total = s.squaredNorm();
  Eigen::Index r = s.size();
  double tail = 0;
  while (r > 0 && tail + s[r - 1] * s[r - 1] <= eps * eps * total) {
    --r;
    tail += s[r] * s[r];
  }
  const Mat Qu = qu.householderQ() * Mat::Identity(U.rows(), ku);
  const Mat Qv = qv.householderQ() * Mat::Identity(V.cols(), kv);
  U = Qu * (svd.matrixU().leftCols(r) * s.head(r).asDiagonal());
  V = (Qv * svd.matrixV().leftCols(r).conjugate()).transpose();
}

}  // namespace

bool aca_block(const HodlrLU::Entries& row, const HodlrLU::Entries& column, const IndexBox& rows, const IndexBox& cols,
               double eps, int max_rank, Mat& U, Mat& V) {
  const int m = rows.size(), n = cols.size();
  const int cap = std::min({max_rank, m, n});
  std::vector<Vec> us, vs;
  std::vector<char> used(m, 0);
  double norm2 = 0;
  int i = 0, checked = 0;
  bool converged = false;
  Vec r, c;
  auto residual_row = [&](int ii, Vec& out) {
    row(rows.begin + ii, cols, out);
    for (std::size_t l = 0; l < us.size(); ++l) out -= us[l][ii] * vs[l];
  };
  auto next_unused = [&](int from) {
    for (int t = 0; t < m; ++t) {
      const int ii = (from + t) % m;
      if (!used[ii]) return ii;
    }
    return -1;
  };
  while (static_cast<int>(us.size()) < cap) {
    residual_row(i, r);
    used[i] = 1;
    Eigen::Index j = 0;
    const double pivot = r.cwiseAbs().maxCoeff(&j);
    if (!(pivot > 0)) {  // an exactly reproduced (or zero) row: try the next one
      i = next_unused(i + 1);
      if (i < 0 || ++checked > 8) { converged = true; break; }
      continue;
    }
    Vec v = r / r[j];
    column(cols.begin + static_cast<int>(j), rows, c);
    for (std::size_t l = 0; l < us.size(); ++l) c -= vs[l][j] * us[l];
    const double uu = c.squaredNorm(), vv = v.squaredNorm();
    double cross = 0;
    for (std::size_t l = 0; l < us.size(); ++l) cross += 2.0 * std::real(us[l].dot(c) * vs[l].dot(v));
    norm2 = std::max(norm2 + uu * vv + cross, uu * vv);
    us.push_back(c), vs.push_back(std::move(v));
    if (std::sqrt(uu * vv) <= eps * std::sqrt(norm2)) {
      // Stopping test passed: check unused rows and columns spread over the block (ACA can miss
      // row or column groups, e.g. the near-field band along the cut); continue from the worst.
      int worst = -1;
      double worst_norm = eps * eps * norm2 / std::max(1, std::min(m, n));
      for (int t = 1; t <= kChecks; ++t) {
        const int ii = next_unused((t * m) / (kChecks + 1));
        if (ii < 0) break;
        residual_row(ii, r);
        if (r.squaredNorm() > worst_norm) worst_norm = r.squaredNorm(), worst = ii;
      }
      for (int t = 1; t <= kChecks; ++t) {
        const int jj = (t * n) / (kChecks + 1);
        column(cols.begin + jj, rows, c);
        for (std::size_t l = 0; l < us.size(); ++l) c -= vs[l][jj] * us[l];
        Eigen::Index ii = 0;
        for (int q = 0; q < m; ++q) if (used[q]) c[q] = 0;  // rows already taken are exact
        if (c.squaredNorm() > worst_norm) worst_norm = c.squaredNorm(), c.cwiseAbs().maxCoeff(&ii), worst = int(ii);
      }
      if (worst < 0) { converged = true; break; }
      i = worst;
      continue;
    }
    Eigen::Index inext = -1;
    double best = -1;
    for (int t = 0; t < m; ++t) {
      if (!used[t] && std::abs(us.back()[t]) > best) best = std::abs(us.back()[t]), inext = t;
    }
    if (inext < 0) { converged = true; break; }
    i = static_cast<int>(inext);
  }
  if (static_cast<int>(us.size()) >= std::min(m, n)) converged = true;  // exact
  U.resize(m, static_cast<Eigen::Index>(us.size()));
  V.resize(static_cast<Eigen::Index>(vs.size()), n);
  for (std::size_t l = 0; l < us.size(); ++l) U.col(l) = us[l], V.row(l) = vs[l].transpose();
  recompress(U, V, eps);
  return converged;
}

}  // namespace plumage::bem
