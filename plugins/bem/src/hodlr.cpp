// HODLR factorisation and solve (hodlr.hpp).
#include "hodlr.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace plumage::bem {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int levels_for(double n, int leaf) {
  int levels = 0;
  while (n > leaf) n /= 2, ++levels;
  return levels;
}

}  // namespace

double hodlr_memory_bound_bytes(double n, const HodlrOptions& o) {
  const int levels = levels_for(n, o.leaf_size);
  // leaves (dense LU) and per level V and D⁻¹U of both off-diagonal blocks (≤ max_rank × n each), in
  // complex<float>; plus the ACA's transient double columns and their float copies
  return 8.0 * n * o.leaf_size + levels * 2.0 * 8.0 * o.max_rank * n + 2.0 * (16.0 + 8.0) * o.max_rank * n;
}

HodlrLU::HodlrLU(const std::vector<Vec2>& points, const HodlrOptions& options) : options_(options) {
  std::vector<int> idx(points.size());
  std::iota(idx.begin(), idx.end(), 0);
  nodes_.reserve(4 * points.size() / std::max(1, options.leaf_size) + 2);
  build(idx, points, 0, static_cast<int>(points.size()), 0);
  perm_ = std::move(idx);
  for (const Node& nd : nodes_) stats_.levels = std::max(stats_.levels, nd.level);
}

// Median bisection along the longer side of the bounding box (ties by index: deterministic).
int HodlrLU::build(std::vector<int>& idx, const std::vector<Vec2>& pts, int begin, int end, int level) {
  const int k = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  IndexBox b{begin, end, 1e300, -1e300, 1e300, -1e300};
  for (int p = begin; p < end; ++p) {
    const Vec2& v = pts[idx[p]];
    b.xmin = std::min(b.xmin, v.x), b.xmax = std::max(b.xmax, v.x);
    b.zmin = std::min(b.zmin, v.z), b.zmax = std::max(b.zmax, v.z);
  }
  nodes_[k].box = b;
  nodes_[k].level = level;
  if (end - begin <= options_.leaf_size) return k;
  const bool along_x = b.xmax - b.xmin >= b.zmax - b.zmin;
  const int mid = (begin + end) / 2;
  std::nth_element(idx.begin() + begin, idx.begin() + mid, idx.begin() + end, [&](int a, int c) {
    const double ka = along_x ? pts[a].x : pts[a].z, kc = along_x ? pts[c].x : pts[c].z;
    return ka < kc || (ka == kc && a < c);
  });
  const int c0 = build(idx, pts, begin, mid, level + 1);
  const int c1 = build(idx, pts, mid, end, level + 1);
  nodes_[k].child[0] = c0, nodes_[k].child[1] = c1;
  return k;
}

void HodlrLU::factorise(const Entries& row, const Entries& column, const std::function<void(int, int)>& progress) {
  for (int level = stats_.levels; level >= 0; --level) {
    std::vector<int> at;
    for (int k = 0; k < static_cast<int>(nodes_.size()); ++k)
      if (nodes_[k].level == level) at.push_back(k);
    tbb::parallel_for(std::size_t{0}, at.size(), [&](std::size_t t) { factor_node(at[t], row, column); });
    if (progress) progress(stats_.levels - level + 1, stats_.levels + 1);
  }
  double bytes = 0;
  for (const Node& nd : nodes_) {
    // summed over the nodes (which run two at a time): thread seconds, not wall
    stats_.seconds_compress += nd.seconds_compress, stats_.seconds_factor += nd.seconds_factor;
    stats_.capped_blocks += nd.capped;
    bytes += 8.0 * (nd.V[0].size() + nd.V[1].size() + nd.Y[0].size() + nd.Y[1].size() + nd.leaf.matrixLU().size());
    bytes += 16.0 * nd.K.matrixLU().size();
    for (int s = 0; s < 2; ++s) {
      if (nd.child[0] < 0) continue;
      ++rank_count_;
      rank_sum_ += nd.V[s].rows();
      stats_.max_rank = std::max(stats_.max_rank, static_cast<int>(nd.V[s].rows()));
    }
  }
  stats_.memory_gb = bytes / 1e9;
  stats_.mean_rank = rank_count_ ? double(rank_sum_) / rank_count_ : 0.0;
}

void HodlrLU::factor_node(int k, const Entries& row, const Entries& column) {
  Node& nd = nodes_[k];
  if (nd.child[0] < 0) {
    const auto t0 = std::chrono::steady_clock::now();
    const int n = nd.box.size();
    Eigen::MatrixXcf A(n, n);
    Eigen::VectorXcd r;
    for (int i = 0; i < n; ++i) {
      row(nd.box.begin + i, nd.box, r);
      A.row(i) = r.transpose().cast<std::complex<float>>();
    }
    nd.leaf.compute(A);
    nd.seconds_factor = seconds_since(t0);
    return;
  }
  const Node& a = nodes_[nd.child[0]];
  const Node& b = nodes_[nd.child[1]];
  bool ok[2];
  const auto t0 = std::chrono::steady_clock::now();
  const auto compress = [&](int s, const IndexBox& rows, const IndexBox& cols) {
    Eigen::MatrixXcd U, V;
    ok[s] = aca_block(row, column, rows, cols, options_.tolerance, options_.max_rank, U, V);
    nd.Y[s] = U.cast<std::complex<float>>();
    nd.V[s] = V.cast<std::complex<float>>();
  };
  tbb::parallel_invoke([&] { compress(0, a.box, b.box); }, [&] { compress(1, b.box, a.box); });
  const auto t1 = std::chrono::steady_clock::now();
  tbb::parallel_invoke([&] { solve(nd.child[0], nd.Y[0]); }, [&] { solve(nd.child[1], nd.Y[1]); });
  const Eigen::Index k0 = nd.V[0].rows(), k1 = nd.V[1].rows();
  Eigen::MatrixXcd K = Eigen::MatrixXcd::Identity(k0 + k1, k0 + k1);
  if (k0 > 0 && k1 > 0) {
    // in float (sums over n_b terms: relative rounding ~1e-6 ≪ the blocks' 1e-4), then kept in double
    K.topRightCorner(k0, k1) = (nd.V[0] * nd.Y[1]).cast<std::complex<double>>();
    K.bottomLeftCorner(k1, k0) = (nd.V[1] * nd.Y[0]).cast<std::complex<double>>();
  }
  if (k0 + k1 > 0) nd.K.compute(K);
  nd.capped = (ok[0] ? 0 : 1) + (ok[1] ? 0 : 1);
  nd.seconds_compress = std::chrono::duration<double>(t1 - t0).count();
  nd.seconds_factor = seconds_since(t1);
}

void HodlrLU::solve(int k, Eigen::Ref<Eigen::MatrixXcf> B) const {
  const Node& nd = nodes_[k];
  if (nd.child[0] < 0) {
    const Eigen::MatrixXcf x = nd.leaf.solve(B);
    B = x;
    return;
  }
  const int na = nodes_[nd.child[0]].box.size(), nb = nodes_[nd.child[1]].box.size();
  auto Ba = B.topRows(na);
  auto Bb = B.bottomRows(nb);
  tbb::parallel_invoke([&] { solve(nd.child[0], Ba); }, [&] { solve(nd.child[1], Bb); });
  const Eigen::Index k0 = nd.V[0].rows(), k1 = nd.V[1].rows();
  if (k0 + k1 == 0) return;
  Eigen::MatrixXcd T(k0 + k1, B.cols());
  T.topRows(k0) = (nd.V[0] * Bb).cast<std::complex<double>>();  // acts on x_b
  T.bottomRows(k1) = (nd.V[1] * Ba).cast<std::complex<double>>();
  const Eigen::MatrixXcf S = nd.K.solve(T).cast<std::complex<float>>();
  Ba.noalias() -= nd.Y[0] * S.topRows(k0);
  Bb.noalias() -= nd.Y[1] * S.bottomRows(k1);
}

void HodlrLU::apply(const Eigen::MatrixXcd& in, Eigen::MatrixXcd& out) const {
  Eigen::MatrixXcf x(in.rows(), in.cols());
  for (std::size_t p = 0; p < perm_.size(); ++p) x.row(static_cast<Eigen::Index>(p)) = in.row(perm_[p]).cast<std::complex<float>>();
  solve(0, x);
  out.resize(in.rows(), in.cols());
  for (std::size_t p = 0; p < perm_.size(); ++p) out.row(perm_[p]) = x.row(static_cast<Eigen::Index>(p)).cast<std::complex<double>>();
}

void HodlrLU::apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const {
  Eigen::MatrixXcd x;
  apply(Eigen::MatrixXcd(in), x);
  out = x.col(0);
}

}  // namespace plumage::bem
