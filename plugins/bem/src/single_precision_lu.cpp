// Blocked LU with partial pivoting in complex<float>; see single_precision_lu.hpp.
#include "single_precision_lu.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace plumage::bem {

namespace {

using cf = std::complex<float>;
using Sub = Eigen::Map<Eigen::MatrixXcf, 0, Eigen::OuterStride<>>;

Sub sub(cf* p, long ld, long r0, long c0, long rows, long cols) {
  return Sub(p + r0 + c0 * ld, rows, cols, Eigen::OuterStride<>(ld));
}

// Row interchanges k ↔ piv[k] for k in [k0, k1), in order, on every column of M (rows relative to M).
void swap_rows(cf* p, long ld, long cols, const int* piv, long k0, long k1) {
  for (long c = 0; c < cols; ++c) {
    cf* col = p + c * ld;
    for (long k = k0; k < k1; ++k) {
      if (piv[k] != k) std::swap(col[k], col[piv[k]]);
    }
  }
}

// LU with partial pivoting of the m × w panel at p (m ≥ w), recursive on the columns (Toledo):
// the halves' coupling is a triangular solve and one GEMM, so most of the panel's work is GEMM too.
// piv[k] (relative to the panel's first row) is the row swapped with row k.
void panel_lu(cf* p, long ld, long m, long w, int* piv) {
  if (w <= 8) {
    for (long j = 0; j < w; ++j) {
      long best = j;
      float best_value = -1.0f;
      for (long i = j; i < m; ++i) {
        const float v = std::norm(p[i + j * ld]);
        if (v > best_value) best_value = v, best = i;  // first maximum: deterministic
      }
      piv[j] = static_cast<int>(best);
      if (best != j) {
        for (long c = 0; c < w; ++c) std::swap(p[j + c * ld], p[best + c * ld]);
      }
      const cf d = p[j + j * ld];
      if (d != cf(0.0f)) {
        const cf inv = cf(1.0f) / d;
        for (long i = j + 1; i < m; ++i) p[i + j * ld] *= inv;
      }
      for (long c = j + 1; c < w; ++c) {
        const cf u = p[j + c * ld];
        if (u == cf(0.0f)) continue;
        for (long i = j + 1; i < m; ++i) p[i + c * ld] -= p[i + j * ld] * u;
      }
    }
    return;
  }
  const long w1 = w / 2, w2 = w - w1;
  panel_lu(p, ld, m, w1, piv);
  swap_rows(p + w1 * ld, ld, w2, piv, 0, w1);
  Sub a12 = sub(p, ld, 0, w1, w1, w2);
  sub(p, ld, 0, 0, w1, w1).triangularView<Eigen::UnitLower>().solveInPlace(a12);
  sub(p, ld, w1, w1, m - w1, w2).noalias() -= sub(p, ld, w1, 0, m - w1, w1) * a12;
  panel_lu(p + w1 + w1 * ld, ld, m - w1, w2, piv + w1);
  for (long k = w1; k < w; ++k) piv[k] += static_cast<int>(w1);
  swap_rows(p, ld, w1, piv, w1, w);
}

}  // namespace

SinglePrecisionLU::SinglePrecisionLU(Eigen::MatrixXcf&& A, int panel, const std::function<void(double)>& progress)
    : lu_(std::move(A)) {
  if (lu_.rows() != lu_.cols()) throw std::invalid_argument("SinglePrecisionLU: matrix is not square");
  if (panel < 1) throw std::invalid_argument("SinglePrecisionLU: panel width must be positive");
  const long n = lu_.rows(), ld = n;
  piv_.resize(n);
  cf* p = lu_.data();
  // Fixed column tiles: the same GEMMs whatever the number of threads (bit-identical factors).
  constexpr long kTile = 512;
  std::vector<int> lp;
  for (long k = 0; k < n; k += panel) {
    const long kb = std::min<long>(panel, n - k);
    lp.assign(kb, 0);
    panel_lu(p + k + k * ld, ld, n - k, kb, lp.data());
    for (long j = 0; j < kb; ++j) piv_[k + j] = static_cast<int>(k + lp[j]);
    // the panel's row swaps in the columns left of it (rows k..n of L)
    const long left_tiles = (k + kTile - 1) / kTile;
    tbb::parallel_for(0L, left_tiles, [&](long t) {
      const long c0 = t * kTile, c1 = std::min(k, c0 + kTile);
      swap_rows(p + k + c0 * ld, ld, c1 - c0, lp.data(), 0, kb);
    });
    // right of it: swaps, U12 = L11⁻¹ A12 and the trailing update A22 −= L21 U12, tile by tile
    const long r0 = k + kb;
    const long right_tiles = (n - r0 + kTile - 1) / kTile;
    tbb::parallel_for(0L, right_tiles, [&](long t) {
      const long c0 = r0 + t * kTile, nc = std::min(n, c0 + kTile) - c0;
      swap_rows(p + k + c0 * ld, ld, nc, lp.data(), 0, kb);
      Sub u12 = sub(p, ld, k, c0, kb, nc);
      sub(p, ld, k, k, kb, kb).triangularView<Eigen::UnitLower>().solveInPlace(u12);
      if (n > r0) sub(p, ld, r0, c0, n - r0, nc).noalias() -= sub(p, ld, r0, k, n - r0, kb) * u12;
    });
    if (progress) {
      const double left = double(n - r0) / double(n);
      progress(1.0 - left * left * left);  // the work of an LU is ∝ (rows left)³
    }
  }
}

void SinglePrecisionLU::apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const {
  Eigen::VectorXcf y = in.cast<cf>();
  for (std::size_t k = 0; k < piv_.size(); ++k) {
    if (piv_[k] != static_cast<int>(k)) std::swap(y[k], y[piv_[k]]);
  }
  lu_.triangularView<Eigen::UnitLower>().solveInPlace(y);
  lu_.triangularView<Eigen::Upper>().solveInPlace(y);
  out = y.cast<std::complex<double>>();
}

}  // namespace plumage::bem
