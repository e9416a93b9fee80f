// Hierarchical LU of the whole PMCHWT operator with weak admissibility (HODLR; issue 28 Deliver 1,
// NOTES.md §5 "Preconditioner hodlr"), the preconditioner `hodlr` of method hmatrix.
//
// The unknowns are ordered by a geometric bisection of their positions (vertex of their tent) into
// a binary tree; every off-diagonal block of a node, Z(a, b) and Z(b, a) for its children a, b, is
// stored as a low-rank product U V, built by adaptive cross approximation with partial pivoting from
// rows and columns of the operator (hmatrix_entries.hpp) and recompressed by QR + SVD to the
// relative Frobenius accuracy `tolerance`; leaves are dense. The inverse is applied by the
// Sherman–Morrison–Woodbury recursion: with D = diag(A_a, A_b), A = D + U_o V_o and
//   A⁻¹ = D⁻¹ − (D⁻¹ U_o) K⁻¹ V_o D⁻¹,  K = I + V_o D⁻¹ U_o  (small: rank(a, b) + rank(b, a)),
// D⁻¹ U_o stored per node (computed bottom-up with the children's inverses). Storage ≈ 2 N r per
// level plus N × leaf; a solve costs O(N (leaf + Σ ranks)). Why weak admissibility suffices here:
// the barbule's interfaces are curves in the plane, the bisection cuts them at few points, and the
// interaction across a cut is of low rank at preconditioner accuracy (measured ranks in NOTES.md).
// Everything (tree, ACA pivots, recursion) is deterministic and independent of the thread count.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "plumage/cross_section.hpp"

namespace plumage::bem {

// A window of consecutive positions of the HODLR order with the bounding box of their points.
struct IndexBox {
  int begin = 0, end = 0;
  double xmin = 0, xmax = 0, zmin = 0, zmax = 0;
  int size() const { return end - begin; }
};

struct HodlrOptions {
  // relative Frobenius accuracy of each off-diagonal block: 1e-4 measured (NOTES.md §5: 5-6 iterations on
  // the slab with rods where 1e-2 needs 77 and the near-field LU 36; 2-4 at 10-30 ppw on the 0.3 um segment)
  double tolerance = 1e-4;
  int leaf_size = 256;      // unknowns per dense leaf
  int max_rank = 400;       // cap per off-diagonal block (bounds the memory, see memory_bound_bytes)
};

// Upper bound of the factor's storage for n unknowns (before anything is allocated): leaves
// 8 n leaf, and per level V and D⁻¹U of rank ≤ max_rank for both off-diagonal blocks (complex<float>),
// plus the ACA's transient double-precision columns of the two blocks being compressed.
double hodlr_memory_bound_bytes(double n, const HodlrOptions& options);

struct HodlrStats {
  int levels = 0, max_rank = 0, capped_blocks = 0;
  double mean_rank = 0, seconds_compress = 0, seconds_factor = 0;
  double memory_gb = 0;
};

class HodlrLU {
 public:
  // out[q − w.begin] = A(p, q) / A(q, p) for q in the window (positions of the HODLR order).
  using Entries = std::function<void(int p, const IndexBox& w, Eigen::VectorXcd& out)>;
  // The order: perm()[position] = index of the point (unknown).
  HodlrLU(const std::vector<Vec2>& points, const HodlrOptions& options);
  const std::vector<int>& perm() const { return perm_; }
  // Compresses and factorises; `progress(done, total)` after each level (may be empty).
  void factorise(const Entries& row, const Entries& column, const std::function<void(int, int)>& progress = {});
  // out = A⁻¹ in (in the original index order).
  void apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const;
  // OUT = A⁻¹ IN for every column: one pass over the factor for all of them.
  void apply(const Eigen::MatrixXcd& in, Eigen::MatrixXcd& out) const;
  const HodlrStats& stats() const { return stats_; }

 private:
  struct Node {
    IndexBox box;
    int child[2] = {-1, -1};
    int level = 0;
    Eigen::MatrixXcf V[2];  // V[0]: of Z(a, b) (rank × n_b); V[1]: of Z(b, a) (rank × n_a)
    Eigen::MatrixXcf Y[2];  // Y[0] = A_a⁻¹ U(a, b) (n_a × rank); Y[1] = A_b⁻¹ U(b, a)
    Eigen::PartialPivLU<Eigen::MatrixXcf> leaf;  // leaf: its block
    Eigen::PartialPivLU<Eigen::MatrixXcd> K;     // inner: the Woodbury core
    double seconds_compress = 0, seconds_factor = 0;  // per node: nodes of a level run in parallel
    int capped = 0;
  };
  int build(std::vector<int>& idx, const std::vector<Vec2>& points, int begin, int end, int level);
  void factor_node(int k, const Entries& row, const Entries& column);
  void solve(int k, Eigen::Ref<Eigen::MatrixXcf> B) const;  // B (rows of node k) ← A_k⁻¹ B
  HodlrOptions options_;
  std::vector<int> perm_;
  std::vector<Node> nodes_;
  HodlrStats stats_;
  long rank_sum_ = 0, rank_count_ = 0;
};

// ACA with partial pivoting of the block rows × cols (positions) of A to relative Frobenius error
// eps, at most max_rank terms, recompressed by QR + SVD: A(rows, cols) ≈ U V. Returns false if the
// cap was reached before the tolerance.
bool aca_block(const HodlrLU::Entries& row, const HodlrLU::Entries& column, const IndexBox& rows, const IndexBox& cols,
               double eps, int max_rank, Eigen::MatrixXcd& U, Eigen::MatrixXcd& V);

}  // namespace plumage::bem
