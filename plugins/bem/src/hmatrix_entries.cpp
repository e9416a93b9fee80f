// Entry oracle of the H-matrix (hmatrix_entries.hpp).
#include "hmatrix_entries.hpp"

#include <algorithm>

namespace plumage::bem {

namespace {

bool overlaps(double a0, double a1, double b0, double b1) { return a0 <= b1 && b0 <= a1; }

}  // namespace

std::vector<Vec2> unknown_positions(const Mesh& mesh) {
  std::vector<Vec2> pts(mesh.unknowns());
  for (int v = 0; v < mesh.n_t; ++v) pts[mesh.jt(v)] = pts[mesh.mt(v)] = mesh.vertices[v];
  for (int z = 0; z < mesh.n_z; ++z) pts[mesh.jz(z)] = pts[mesh.mz(z)] = mesh.vertices[mesh.z_vertex[z]];
  return pts;
}

HMatrixEntries::HMatrixEntries(const HMatrix& H, const Mesh& mesh, const std::vector<Medium>& media,
                               const std::vector<int>& perm)
    : H_(H), mesh_(mesh), media_(media), perm_(perm), ipos_(perm.size()) {
  for (std::size_t p = 0; p < perm_.size(); ++p) ipos_[perm_[p]] = static_cast<int>(p);
  slots_.resize(perm_.size());
  const int nd = static_cast<int>(H.domains_.size());
  row_blocks_.resize(nd), col_blocks_.resize(nd), row_box_.resize(nd), col_box_.resize(nd);
  for (int d = 0; d < nd; ++d) {
    const HMatrix::Domain& D = H.domains_[d];
    const int ns = static_cast<int>(D.seg.size());
    for (int s = 0; s < ns; ++s) {
      for (int l = 0; l < 8; ++l) slots_[D.loc2glob[8 * s + l]].push_back({d, s, l});
    }
    row_blocks_[d].resize(ns), col_blocks_[d].resize(ns);
    auto box_of = [&](int s0, int n) {
      Box b{1e300, -1e300, 1e300, -1e300};
      for (int s = s0; s < s0 + n; ++s) {
        const Segment& S = mesh.segments[D.seg[s]];
        b.xmin = std::min({b.xmin, S.p0.x, S.p1.x}), b.xmax = std::max({b.xmax, S.p0.x, S.p1.x});
        b.zmin = std::min({b.zmin, S.p0.z, S.p1.z}), b.zmax = std::max({b.zmax, S.p0.z, S.p1.z});
      }
      return b;
    };
    for (std::size_t k = 0; k < D.blocks.size(); ++k) {
      const HMatrix::LowRank& b = D.blocks[k];
      for (int s = b.r0; s < b.r0 + b.nr; ++s) row_blocks_[d][s].push_back(static_cast<int>(k));
      for (int s = b.c0; s < b.c0 + b.nc; ++s) col_blocks_[d][s].push_back(static_cast<int>(k));
      row_box_[d].push_back(box_of(b.r0, b.nr));
      col_box_[d].push_back(box_of(b.c0, b.nc));
    }
  }
}

double HMatrixEntries::memory_gb() const {
  double slots = 0, lists = 0;
  for (const auto& s : slots_) slots += static_cast<double>(s.size());
  for (const auto& d : row_blocks_)
    for (const auto& s : d) lists += 2.0 * static_cast<double>(s.size());
  return (12.0 * slots + 4.0 * lists + 8.0 * perm_.size()) / 1e9;
}

// A segment can carry an unknown of the window only if one of its end points lies in the window's box.
bool HMatrixEntries::segment_in(int dom, int s, const IndexBox& w) const {
  const Segment& S = mesh_.segments[H_.domains_[dom].seg[s]];
  auto in = [&](const Vec2& v) { return v.x >= w.xmin && v.x <= w.xmax && v.z >= w.zmin && v.z <= w.zmax; };
  return in(S.p0) || in(S.p1);
}

void HMatrixEntries::row(int p, const IndexBox& w, Eigen::VectorXcd& out) const {
  out = Eigen::VectorXcd::Zero(w.end - w.begin);
  const int g = perm_[p];
  using RowIt = Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor>::InnerIterator;
  for (RowIt it(H_.near_, g); it; ++it) {
    const int q = ipos_[it.col()];
    if (q >= w.begin && q < w.end) out[q - w.begin] += it.value();
  }
  far_part(p, w, false, out);
}

void HMatrixEntries::column(int p, const IndexBox& w, Eigen::VectorXcd& out) const {
  out = Eigen::VectorXcd::Zero(w.end - w.begin);
  const int g = perm_[p];
  // The near field's pattern is symmetric (every segment pair is scattered both ways, build_near_field),
  // so the rows holding column g are the columns of row g; each value Z(q, g) is found by bisection
  // in row q (no column-major copy: it was as large as the near field, NOTES.md §5).
  const auto& N = H_.near_;
  const int* outer = N.outerIndexPtr();
  const int* inner = N.innerIndexPtr();
  for (int k = outer[g]; k < outer[g + 1]; ++k) {
    const int qg = inner[k];
    const int q = ipos_[qg];
    if (q < w.begin || q >= w.end) continue;
    const int* at = std::lower_bound(inner + outer[qg], inner + outer[qg + 1], g);
    if (at != inner + outer[qg + 1] && *at == g) out[q - w.begin] += N.valuePtr()[at - inner];
  }
  far_part(p, w, true, out);
}

// The ACA blocks' share of row (transpose: column) perm[p]: for every (domain, segment, local
// index) carrying that unknown, the blocks on the segment's row (column), their kernel row
// (column) pair, and the local 8×8 algebra per partner segment inside the window's box.
void HMatrixEntries::far_part(int p, const IndexBox& w, bool transpose, Eigen::VectorXcd& out) const {
  using Mat = Eigen::MatrixXcd;
  for (const Slot& slot : slots_[perm_[p]]) {
    const HMatrix::Domain& D = H_.domains_[slot.dom];
    const auto& blocks = transpose ? col_blocks_[slot.dom][slot.s] : row_blocks_[slot.dom][slot.s];
    for (int k : blocks) {
      const HMatrix::LowRank& b = D.blocks[k];
      const Box& bx = transpose ? row_box_[slot.dom][k] : col_box_[slot.dom][k];
      if (!overlaps(bx.xmin, bx.xmax, w.xmin, w.xmax) || !overlaps(bx.zmin, bx.zmax, w.zmin, w.zmax)) continue;
      // kernel rows 2(s − r0) + {0, 1} (transpose: columns 2(s − c0) + {0, 1}), as 2 × 2 n_partner
      Mat K[3];
      const int off = 2 * (transpose ? slot.s - b.c0 : slot.s - b.r0);
      const int partners = transpose ? b.nr : b.nc;
      for (int kk = 0; kk < 3; ++kk) {
        const Mat& U = b.U[kk];
        const Mat& V = b.V[kk];
        if (U.cols() == 0) K[kk] = Mat::Zero(2, 2 * partners);
        else if (V.size() == 0) K[kk] = transpose ? Mat(U.middleCols(off, 2).transpose()) : Mat(U.middleRows(off, 2));
        else if (transpose) K[kk] = (U * V.middleCols(off, 2)).transpose();
        else K[kk] = U.middleRows(off, 2) * V;
      }
      const int first = transpose ? b.r0 : b.c0;
      for (int u = 0; u < partners; ++u) {
        const int t = first + u;
        if (!segment_in(slot.dom, t, w)) continue;
        const int sa = transpose ? t : slot.s, sb = transpose ? slot.s : t;
        const Segment& SA = mesh_.segments[D.seg[sa]];
        const Segment& SB = mesh_.segments[D.seg[sb]];
        const double hh = D.h[sa] * D.h[sb];  // kernels are stored ÷ h_A h_B
        PairIntegrals pi;
        for (int i = 0; i < 2; ++i) {
          for (int j = 0; j < 2; ++j) {
            // K[.](own tent, partner tent): own = test tent i (row) or basis tent j (transpose)
            const int own = transpose ? j : i, other = transpose ? i : j;
            const int c = 2 * u + other;
            pi.I[i][j] = hh * K[0](own, c);
            pi.P[i][j] = hh * (SA.n.x * K[1](own, c) + SA.n.z * K[2](own, c));
            pi.Q[i][j] = hh * (SB.n.x * K[1](own, c) + SB.n.z * K[2](own, c));
          }
        }
        const Local8 loc = local_pair(SA, SB, pi, slot.dom, media_[slot.dom], H_.k0_, H_.beta_);
        for (int m = 0; m < 8; ++m) {
          const int q = ipos_[D.loc2glob[8 * t + m]];
          if (q < w.begin || q >= w.end) continue;
          out[q - w.begin] += transpose ? loc[m][slot.l] : loc[slot.l][m];
        }
      }
    }
  }
}

}  // namespace plumage::bem
