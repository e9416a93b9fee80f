// Hierarchical matrix: exact sparse near field + ACA blocks (aca.hpp); see hmatrix.hpp.
#include "hmatrix.hpp"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>

#include "aca.hpp"
#include "pair_integrals.hpp"
#include "plumage/memory_budget.hpp"

namespace plumage::bem {

namespace {

using Triplet = Eigen::Triplet<std::complex<double>>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A segment pair of one domain's near field.
struct NearPair {
  int dom, a, b;  // mesh segment indices, a before b in mesh.domain_segments[dom]
};

// The unordered segment pairs of the inadmissible leaf blocks of every domain.
std::vector<NearPair> near_pairs(const Mesh& mesh, const std::vector<ClusterTree>& trees,
                                 const std::vector<BlockPartition>& parts) {
  std::vector<NearPair> pairs;
  std::vector<std::vector<int>> pos(mesh.a_count, std::vector<int>(mesh.segments.size(), -1));
  for (int d = 0; d < mesh.a_count; ++d) {
    for (std::size_t k = 0; k < mesh.domain_segments[d].size(); ++k) pos[d][mesh.domain_segments[d][k]] = static_cast<int>(k);
  }
  for (int d = 0; d < mesh.a_count; ++d) {
    const ClusterTree& t = trees[d];
    for (const BlockPair& bp : parts[d].near) {
      const Cluster& r = t.nodes[bp.row];
      const Cluster& c = t.nodes[bp.col];
      if (r.begin > c.begin) continue;  // the mirrored block is filled from this one
      for (int x = r.begin; x < r.end; ++x) {
        for (int y = (bp.row == bp.col ? x : c.begin); y < c.end; ++y) {
          // test segment = the earlier one in the domain's list, as assemble_dense integrates it (the
          // near rules are not symmetric; with sub-nm generator edges the two orders differ by ~1e-3)
          int a = t.order[x], b = t.order[y];
          if (pos[d][a] > pos[d][b]) std::swap(a, b);
          pairs.push_back({d, a, b});
        }
      }
    }
  }
  return pairs;
}

}  // namespace

Local8 local_pair(const Segment& A, const Segment& B, const PairIntegrals& in, int dom, const Medium& m, double k0,
                  double beta) {
  const double sa = A.a == dom ? 1.0 : -1.0, sb = B.a == dom ? 1.0 : -1.0;
  Local8 loc{};
  local_block(A, B, in, m, k0, beta, sa * sb, loc);
  return loc;
}

double HMatrixStats::memory_gb() const {
  return (lowrank_entries * 16.0 + (near_nonzeros + preconditioner_nonzeros) * 20.0) / 1e9;
}

HMatrix::HMatrix(const Mesh& mesh, const std::vector<Medium>& md, double k0, double beta,
                 const QuadratureOptions& q, const HMatrixOptions& opt, std::string progress_step) {
  progress_step_ = std::move(progress_step);
  n_ = mesh.unknowns();
  k0_ = k0, beta_ = beta;
  domains_.resize(mesh.a_count);
  near_.resize(n_, n_);
  pre_.resize(n_, n_);
  std::vector<ClusterTree> trees(mesh.a_count);
  std::vector<BlockPartition> parts(mesh.a_count);
  for (int d = 0; d < mesh.a_count; ++d) {
    trees[d] = build_cluster_tree(mesh, mesh.domain_segments[d], opt.leaf_size);
    parts[d] = partition_blocks(trees[d], opt.eta, 1.01 * q.near_factor);
    Domain& D = domains_[d];
    const int ns = static_cast<int>(trees[d].order.size());
    D.loc2glob.resize(8 * ns);
    D.eps = md[d].eps;
    for (int k = 0; k < ns; ++k) {
      const Segment& S = mesh.segments[trees[d].order[k]];
      for (int l = 0; l < 8; ++l) D.loc2glob[8 * k + l] = global_index(mesh, S, l);
      D.seg.push_back(trees[d].order[k]);
      D.tx.push_back(S.t.x), D.tz.push_back(S.t.z), D.nx.push_back(S.n.x), D.nz.push_back(S.n.z);
      D.h.push_back(S.h), D.sign.push_back(S.a == d ? 1.0 : -1.0);
    }
  }
  build_near_field(mesh, md, q, opt, trees, parts);
  compress_blocks(mesh, md, q, opt, trees, parts);
}

// The exact near field N (all pairs of the inadmissible leaf blocks, integrated and symmetrised as
// assemble_dense does) and the preconditioner's part of it.
void HMatrix::build_near_field(const Mesh& mesh, const std::vector<Medium>& md, const QuadratureOptions& q,
                               const HMatrixOptions& opt, const std::vector<ClusterTree>& trees,
                               const std::vector<BlockPartition>& parts) {
  const double k0 = k0_, beta = beta_;
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<NearPair> pairs = near_pairs(mesh, trees, parts);
  stats_.near_pairs = static_cast<long>(pairs.size());
  const double pre_factor = opt.preconditioner_factor;
  const bool keep_pre = opt.preconditioner == HMatrixOptions::Preconditioner::near_field;
  constexpr std::size_t kChunk = 16384;
  std::vector<PairIntegrals> buf(kChunk);
  std::vector<Triplet> tn, tp;
  // Chunk matrices are summed like a binary counter (merge equal sizes), so building the near
  // field costs O(nnz log chunks) and the triplets of one chunk at a time.
  using RowSparse = Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor>;
  using ColSparse = Eigen::SparseMatrix<std::complex<double>>;
  std::vector<std::pair<RowSparse, int>> stack_n;
  std::vector<std::pair<ColSparse, int>> stack_p;
  auto push = [](auto& stack, auto&& m) {
    stack.emplace_back(std::move(m), 1);
    while (stack.size() >= 2 && stack[stack.size() - 2].second == stack.back().second) {
      auto top = std::move(stack.back());
      stack.pop_back();
      stack.back().first += top.first;
      stack.back().second *= 2;
    }
  };
  for (std::size_t p0 = 0; p0 < pairs.size(); p0 += kChunk) {
    const std::size_t p1 = std::min(pairs.size(), p0 + kChunk);
    tbb::parallel_for(p0, p1, [&](std::size_t p) {
      const Segment& A = mesh.segments[pairs[p].a];
      const Segment& B = mesh.segments[pairs[p].b];
      buf[p - p0] = pair_integrals(A, B, md[pairs[p].dom].gamma, pairs[p].a == pairs[p].b, q);
    });
    tn.clear();
    tp.clear();
    for (std::size_t p = p0; p < p1; ++p) {
      const int dom = pairs[p].dom;
      const Segment& A = mesh.segments[pairs[p].a];
      const Segment& B = mesh.segments[pairs[p].b];
      const PairIntegrals& in = buf[p - p0];
      const bool close = keep_pre && (pre_factor <= 0.0 || pairs[p].a == pairs[p].b ||
                         segment_distance(A, B) <= pre_factor * std::max(A.h, B.h));
      auto scatter = [&](const Segment& X, const Segment& Y, const PairIntegrals& pi) {
        const Local8 loc = local_pair(X, Y, pi, dom, md[dom], k0, beta);
        int ra[8], cb[8];
        for (int l = 0; l < 8; ++l) ra[l] = global_index(mesh, X, l), cb[l] = global_index(mesh, Y, l);
        for (int r = 0; r < 8; ++r) {
          for (int c = 0; c < 8; ++c) {
            tn.emplace_back(ra[r], cb[c], loc[r][c]);
            if (close) tp.emplace_back(ra[r], cb[c], loc[r][c]);
          }
        }
      };
      scatter(A, B, in);
      if (pairs[p].a == pairs[p].b) continue;
      PairIntegrals tr;  // (B, A): I' = Iᵀ, P' = −Qᵀ, Q' = −Pᵀ
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) {
          tr.I[j][i] = in.I[i][j];
          tr.P[j][i] = -in.Q[i][j];
          tr.Q[j][i] = -in.P[i][j];
        }
      }
      scatter(B, A, tr);
    }
    RowSparse cn(n_, n_);
    cn.setFromTriplets(tn.begin(), tn.end());
    push(stack_n, std::move(cn));
    ColSparse cp(n_, n_);
    cp.setFromTriplets(tp.begin(), tp.end());
    push(stack_p, std::move(cp));
    if (!progress_step_.empty()) {
      report_step(progress_step_, static_cast<double>(p1), static_cast<double>(pairs.size()), "near-field segment pairs");
    }
  }
  for (auto& m : stack_n) near_ += m.first;
  for (auto& m : stack_p) pre_ += m.first;
  stack_n.clear();
  stack_p.clear();
  std::vector<Triplet>().swap(tn);
  std::vector<Triplet>().swap(tp);
  near_.makeCompressed();
  pre_.makeCompressed();
  stats_.near_nonzeros = near_.nonZeros();
  stats_.preconditioner_nonzeros = pre_.nonZeros();
  stats_.near_seconds = seconds_since(t0);
}

// The admissible blocks by ACA, in parallel (each block independent and deterministic).
void HMatrix::compress_blocks(const Mesh& mesh, const std::vector<Medium>& md, const QuadratureOptions& q,
                              const HMatrixOptions& opt, const std::vector<ClusterTree>& trees,
                              const std::vector<BlockPartition>& parts) {
  const auto t0 = std::chrono::steady_clock::now();
  struct Job {
    int dom;
    BlockPair bp;
  };
  std::vector<Job> jobs;
  for (int d = 0; d < mesh.a_count; ++d) {
    for (const BlockPair& bp : parts[d].admissible) jobs.push_back({d, bp});
  }
  std::vector<LowRank> blocks(jobs.size());
  // In batches, so that long assemblies say how far they are (each block is independent and
  // deterministic: the batching changes no bit).
  constexpr std::size_t kBatch = 2048;
  for (std::size_t k0 = 0; k0 < jobs.size(); k0 += kBatch) {
    tbb::parallel_for(k0, std::min(jobs.size(), k0 + kBatch), [&](std::size_t k) {
      const int d = jobs[k].dom;
      const Cluster& r = trees[d].nodes[jobs[k].bp.row];
      const Cluster& c = trees[d].nodes[jobs[k].bp.col];
      LowRank& b = blocks[k];
      b.r0 = r.begin, b.nr = r.size(), b.c0 = c.begin, b.nc = c.size();
      compress_far_kernels(mesh, trees[d].order, md[d].gamma, q.far_points, r.begin, r.size(), c.begin, c.size(),
                           opt.aca_tolerance, b.U, b.V);
    });
    if (!progress_step_.empty()) {
      report_step(progress_step_ + " ACA", static_cast<double>(std::min(jobs.size(), k0 + kBatch)),
                  static_cast<double>(jobs.size()), "admissible blocks compressed");
    }
  }
  long rank_sum = 0, lowrank = 0;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    LowRank& b = blocks[k];
    for (int kernel = 0; kernel < 3; ++kernel) {
      if (b.V[kernel].size() == 0 && b.U[kernel].cols() == 2 * b.nc && b.nc > 0) {
        ++stats_.dense_blocks;
        stats_.lowrank_entries += b.U[kernel].size();
      } else {
        ++lowrank;
        rank_sum += b.U[kernel].cols();
        stats_.max_rank = std::max(stats_.max_rank, static_cast<int>(b.U[kernel].cols()));
        stats_.lowrank_entries += b.U[kernel].size() + b.V[kernel].size();
      }
    }
    domains_[jobs[k].dom].blocks.push_back(std::move(b));
  }
  stats_.admissible_blocks = static_cast<long>(jobs.size());
  stats_.mean_rank = lowrank ? double(rank_sum) / lowrank : 0.0;
  stats_.aca_seconds = seconds_since(t0);
}

void HMatrix::apply(const Eigen::VectorXcd& x, Eigen::VectorXcd& y) const {
  Eigen::MatrixXcd Y;
  apply(Eigen::MatrixXcd(x), Y);
  y = Y.col(0);
}

void HMatrix::apply(const Eigen::MatrixXcd& X, Eigen::MatrixXcd& Y) const {
  const Eigen::Index nv = X.cols();
  Y.resize(n_, nv);
  // near field: rows in parallel, each row's entries read once for all columns (Eigen's sparse × dense
  // product reads the sparse matrix once per column: 31 % of a 4-column GMRES step, NOTES.md §5);
  // each entry one sum in the row's order: deterministic on any thread count
  const Eigen::MatrixXcd Xt = X.transpose();  // nv × N: the columns' values of one unknown side by side
  const int* outer = near_.outerIndexPtr();
  const int* inner = near_.innerIndexPtr();
  const cplx* value = near_.valuePtr();
  constexpr int kRows = 2048;
  tbb::parallel_for(0, (n_ + kRows - 1) / kRows, [&](int b) {
    const int r1 = std::min(n_, (b + 1) * kRows);
    Eigen::VectorXcd acc(nv);
    for (int r = b * kRows; r < r1; ++r) {
      acc.setZero();
      for (int k = outer[r]; k < outer[r + 1]; ++k) acc += value[k] * Xt.col(inner[k]);
      Y.row(r) = acc.transpose();
    }
  });
  // Blocks in batches: the products of a batch in parallel, summed in block order (the same bits on
  // any thread count), so that the transient products stay ~kBatch blocks whatever the width.
  constexpr std::size_t kBatch = 512;
  std::vector<Eigen::MatrixXcd> part(kBatch);
  for (const Domain& d : domains_) {
    if (d.blocks.empty()) continue;
    const std::size_t nl = d.loc2glob.size();
    Eigen::MatrixXcd xl(nl, nv), yl = Eigen::MatrixXcd::Zero(nl, nv);
    for (std::size_t k = 0; k < nl; ++k) xl.row(k) = X.row(d.loc2glob[k]);
    for (std::size_t k0 = 0; k0 < d.blocks.size(); k0 += kBatch) {
      const std::size_t k1 = std::min(d.blocks.size(), k0 + kBatch);
      tbb::parallel_for(k0, k1, [&](std::size_t k) { apply_block(d, d.blocks[k], xl, part[k - k0]); });
      for (std::size_t k = k0; k < k1; ++k) yl.middleRows(8 * d.blocks[k].r0, 8 * d.blocks[k].nr) += part[k - k0];
    }
    for (std::size_t k = 0; k < nl; ++k) Y.row(d.loc2glob[k]) += yl.row(k);
  }
}

Eigen::MatrixXcf HMatrix::to_dense_single(const Mesh& mesh, const std::vector<Medium>& md) const {
  using cf = std::complex<float>;
  Eigen::MatrixXcf A = Eigen::MatrixXcf::Zero(n_, n_);
  for (int r = 0; r < near_.outerSize(); ++r) {
    for (Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor>::InnerIterator it(near_, r); it; ++it) {
      A(r, it.col()) += cf(it.value());
    }
  }
  // Admissible blocks in tiles of ≤ kRows × kCols segments: a batch of tiles is expanded in
  // parallel into buffers (8×8 per segment pair), then added to A serially in tile order, since
  // neighbouring segments share tent unknowns (rows/columns) across tiles.
  constexpr int kRows = 16, kCols = 256;
  struct Tile {
    int dom;
    const LowRank* b;
    int ka0, nka, kb0, nkb;
  };
  std::vector<Tile> tiles;
  for (int d = 0; d < static_cast<int>(domains_.size()); ++d) {
    for (const LowRank& b : domains_[d].blocks) {
      for (int ka0 = 0; ka0 < b.nr; ka0 += kRows) {
        for (int kb0 = 0; kb0 < b.nc; kb0 += kCols) {
          tiles.push_back({d, &b, ka0, std::min(kRows, b.nr - ka0), kb0, std::min(kCols, b.nc - kb0)});
        }
      }
    }
  }
  constexpr std::size_t kBatch = 64;
  std::vector<std::vector<cf>> buf(kBatch);
  for (std::size_t t0 = 0; t0 < tiles.size(); t0 += kBatch) {
    const std::size_t t1 = std::min(tiles.size(), t0 + kBatch);
    tbb::parallel_for(t0, t1, [&](std::size_t t) {
      const Tile& tile = tiles[t];
      const Domain& d = domains_[tile.dom];
      const LowRank& b = *tile.b;
      const int rows = 2 * tile.nka, cols = 2 * tile.nkb;
      auto kernel = [&](int k) -> Eigen::MatrixXcd {
        const Eigen::MatrixXcd& U = b.U[k];
        const Eigen::MatrixXcd& V = b.V[k];
        if (U.cols() == 0) return Eigen::MatrixXcd::Zero(rows, cols);
        if (V.size() == 0) return U.block(2 * tile.ka0, 2 * tile.kb0, rows, cols);  // stored in full
        return U.middleRows(2 * tile.ka0, rows) * V.middleCols(2 * tile.kb0, cols);
      };
      const Eigen::MatrixXcd KI = kernel(0), KX = kernel(1), KZ = kernel(2);
      std::vector<cf>& out = buf[t - t0];
      out.resize(std::size_t(64) * tile.nka * tile.nkb);
      for (int ka = 0; ka < tile.nka; ++ka) {
        const int s = b.r0 + tile.ka0 + ka;
        const Segment& SA = mesh.segments[d.seg[s]];
        for (int kb = 0; kb < tile.nkb; ++kb) {
          const int u = b.c0 + tile.kb0 + kb;
          const Segment& SB = mesh.segments[d.seg[u]];
          const double hh = d.h[s] * d.h[u];  // the kernels are stored ÷ h_A h_B
          PairIntegrals pi;
          for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < 2; ++j) {
              const int r = 2 * ka + i, c = 2 * kb + j;
              pi.I[i][j] = hh * KI(r, c);
              pi.P[i][j] = hh * (SA.n.x * KX(r, c) + SA.n.z * KZ(r, c));
              pi.Q[i][j] = hh * (SB.n.x * KX(r, c) + SB.n.z * KZ(r, c));
            }
          }
          const Local8 loc = local_pair(SA, SB, pi, tile.dom, md[tile.dom], k0_, beta_);
          cf* o = out.data() + std::size_t(64) * (std::size_t(ka) * tile.nkb + kb);
          for (int r = 0; r < 8; ++r) {
            for (int c = 0; c < 8; ++c) o[8 * r + c] = cf(loc[r][c]);
          }
        }
      }
    });
    for (std::size_t t = t0; t < t1; ++t) {
      const Tile& tile = tiles[t];
      const Domain& d = domains_[tile.dom];
      const LowRank& b = *tile.b;
      const cf* o = buf[t - t0].data();
      for (int ka = 0; ka < tile.nka; ++ka) {
        const int* ra = &d.loc2glob[8 * (b.r0 + tile.ka0 + ka)];
        for (int kb = 0; kb < tile.nkb; ++kb, o += 64) {
          const int* cb = &d.loc2glob[8 * (b.c0 + tile.kb0 + kb)];
          for (int c = 0; c < 8; ++c) {
            for (int r = 0; r < 8; ++r) A(ra[r], cb[c]) += o[8 * r + c];
          }
        }
      }
    }
  }
  return A;
}

// One admissible block: out (8 nr) = B x (8 nc), the algebra of local_block (assembly.cpp, §6.4)
// applied to the compressed kernels. Local unknowns per segment: [J_t0 J_t1 J_z0 J_z1 M_t0 M_t1 M_z0
// M_z1], rows [E_t E_z H_t H_z] likewise; d_i = ∓1 is the tent slope sign (N_i' = d_i / h).
void HMatrix::apply_block(const Domain& d, const LowRank& b, const Eigen::MatrixXcd& xl, Eigen::MatrixXcd& out) const {
  const cplx I1{0.0, 1.0};
  const double k0 = k0_, beta = beta_;
  const int nc = b.nc, nr = b.nr, nv = static_cast<int>(xl.cols());
  // right-hand columns (2 nc each, tents j of segment kb), σ_B applied, 12 per vector v:
  //   per family F ∈ {J (0), M (1)}: 0 t_x x_t, 1 t_z x_t, 2 ŵ (w = Σ_j d_j x_t,j / h on both tents),
  //   3 x_z, 4 n_x x_t, 5 n_z x_t
  Eigen::MatrixXcd R(2 * nc, 12 * nv);
  for (int q = 0; q < nv * nc; ++q) {
    const int v = q / nc, kb = q % nc;
    const int s = b.c0 + kb;
    const double sg = d.sign[s];
    for (int F = 0; F < 2; ++F) {
      const cplx xt0 = sg * xl(8 * s + 4 * F, v), xt1 = sg * xl(8 * s + 4 * F + 1, v);
      const cplx xz0 = sg * xl(8 * s + 4 * F + 2, v), xz1 = sg * xl(8 * s + 4 * F + 3, v);
      const cplx w = (xt1 - xt0) / d.h[s];
      const cplx xt[2] = {xt0, xt1}, xz[2] = {xz0, xz1};
      const double hb = d.h[s];  // kernels are stored ÷ h_A h_B
      for (int j = 0; j < 2; ++j) {
        const int row = 2 * kb + j;
        const int c = 12 * v + 6 * F;
        R(row, c + 0) = hb * d.tx[s] * xt[j];
        R(row, c + 1) = hb * d.tz[s] * xt[j];
        R(row, c + 2) = hb * w;
        R(row, c + 3) = hb * xz[j];
        R(row, c + 4) = hb * d.nx[s] * xt[j];
        R(row, c + 5) = hb * d.nz[s] * xt[j];
      }
    }
  }
  auto mul = [&](int kernel, const Eigen::MatrixXcd& in) -> Eigen::MatrixXcd {
    if (b.U[kernel].cols() == 0) return Eigen::MatrixXcd::Zero(2 * nr, in.cols());
    if (b.V[kernel].size() == 0) return b.U[kernel] * in;
    return b.U[kernel] * (b.V[kernel] * in);
  };
  Eigen::MatrixXcd IR = mul(0, R);
  // X applied to [n_x x_t (J), x_z (J), n_x x_t (M), x_z (M)], Z to the n_z counterparts
  Eigen::MatrixXcd RX(2 * nc, 4 * nv), RZ(2 * nc, 4 * nv);
  for (int v = 0; v < nv; ++v) {
    for (int F = 0; F < 2; ++F) {
      const int c = 12 * v + 6 * F, o = 4 * v + 2 * F;
      RX.col(o) = R.col(c + 4), RX.col(o + 1) = R.col(c + 3);
      RZ.col(o) = R.col(c + 5), RZ.col(o + 1) = R.col(c + 3);
    }
  }
  Eigen::MatrixXcd XR = mul(1, RX), ZR = mul(2, RZ);
  for (int ka = 0; ka < nr; ++ka) {
    const double ha = d.h[b.r0 + ka];
    IR.middleRows(2 * ka, 2) *= ha, XR.middleRows(2 * ka, 2) *= ha, ZR.middleRows(2 * ka, 2) *= ha;
  }
  out.setZero(8 * nr, nv);
  const cplx bE = 1.0 / d.eps;  // L[1, 1/ε] on J (E rows), L[ε, 1] on M (H rows)
  const cplx aH = d.eps;
  for (int q = 0; q < nv * nr; ++q) {
    const int v = q / nr, ka = q % nr;
    const int ci = 12 * v, cx = 4 * v;  // this vector's columns of IR and of XR, ZR
    const int s = b.r0 + ka;
    const double sa = d.sign[s], tx = d.tx[s], tz = d.tz[s], nx = d.nx[s], nz = d.nz[s], h = d.h[s];
    const int r0 = 2 * ka;
    // Σ over the row segment's two tents of the ŵ and x_z products (the S / col[j] terms)
    const cplx sumW_J = IR(r0, ci + 2) + IR(r0 + 1, ci + 2), sumZ_J = IR(r0, ci + 3) + IR(r0 + 1, ci + 3);
    const cplx sumW_M = IR(r0, ci + 8) + IR(r0 + 1, ci + 8), sumZ_M = IR(r0, ci + 9) + IR(r0 + 1, ci + 9);
    for (int i = 0; i < 2; ++i) {
      const int r = r0 + i;
      const double di = (i == 0 ? -1.0 : 1.0) / h;
      // Q x_t = X(n_x x_t) + Z(n_z x_t); P x_z = n_x X x_z + n_z Z x_z
      const cplx Qx_J = XR(r, cx + 0) + ZR(r, cx + 0), Px_J = nx * XR(r, cx + 1) + nz * ZR(r, cx + 1);
      const cplx Qx_M = XR(r, cx + 2) + ZR(r, cx + 2), Px_M = nx * XR(r, cx + 3) + nz * ZR(r, cx + 3);
      const cplx tI_J = tx * IR(r, ci + 0) + tz * IR(r, ci + 1), tnI_J = tx * IR(r, ci + 4) + tz * IR(r, ci + 5);
      const cplx tI_M = tx * IR(r, ci + 6) + tz * IR(r, ci + 7), tnI_M = tx * IR(r, ci + 10) + tz * IR(r, ci + 11);
      // E_t: L[1, 1/ε] J (tt, tz) − K M (tt, tz)
      cplx Et = I1 * k0 * tI_J - (I1 * bE / k0) * di * sumW_J + (beta * bE / k0) * di * sumZ_J;
      Et -= I1 * beta * tnI_M + Px_M;
      // E_z: L J (zt, zz) − K M (zt = −Q)
      cplx Ez = -(beta * bE / k0) * IR(r, ci + 2) + I1 * (k0 - bE * beta * beta / k0) * IR(r, ci + 3);
      Ez += Qx_M;
      // H_t: K J (tt, tz) + L[ε, 1] M
      cplx Ht = I1 * beta * tnI_J + Px_J;
      Ht += I1 * k0 * aH * tI_M - (I1 / k0) * di * sumW_M + (beta / k0) * di * sumZ_M;
      // H_z: K J (zt = −Q) + L M (zt, zz)
      cplx Hz = -Qx_J;
      Hz += -(beta / k0) * IR(r, ci + 8) + I1 * (k0 * aH - beta * beta / k0) * IR(r, ci + 9);
      out(8 * ka + i, v) = sa * Et;
      out(8 * ka + 2 + i, v) = sa * Ez;
      out(8 * ka + 4 + i, v) = sa * Ht;
      out(8 * ka + 6 + i, v) = sa * Hz;
    }
  }
}

}  // namespace plumage::bem
