// Hierarchical-matrix form of the PMCHWT operator (issue 6 Deliver 2; NOTES.md §5):
//   Z = N + Σ_d Σ_{admissible (σ,τ) of domain d} P_σᵀ B_στ P_τ
// N is the exact sparse near field (all segment pairs of inadmissible leaf blocks, integrated and
// symmetrised exactly as assemble_dense does); P the local-to-global map of the 8 local unknowns
// per segment (assembly.hpp). An admissible block B (clusters of segments farther apart than
// max(diam)/η and than 2.02 h, so that all its pairs use the smooth 4×4 Gauss rule) is not
// stored entry by entry: its three kernel matrices I = ∫∫NNG, X = ∫∫NN G'R̂_x, Z = ∫∫NN G'R̂_z
// (2|σ| × 2|τ|, tents) are compressed by adaptive cross approximation with partial pivoting (ACA),
// and the 8×8 Galerkin structure of §6.4 (tangents, normals, tent derivatives, σ signs, ε) is
// applied on the fly in the mat-vec — the same algebra as local_block, with P = n̂_A·(X, Z) and
// Q = n̂_B·(X, Z). The domains are compressed separately (own γ_d). The mat-vec is parallel (oneTBB)
// over blocks with a fixed summation order, so it does not depend on the thread count.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "assembly.hpp"
#include "cluster.hpp"
#include "mesh.hpp"

namespace plumage::bem {

struct HMatrixOptions {
  double aca_tolerance = 1e-6;  // relative Frobenius error per admissible block
  double eta = 1.0;             // admissibility max(diam) ≤ η dist
  int leaf_size = 24;           // segments per leaf cluster (NOTES.md §5: iterations vs near-field size)
  // Preconditioner pattern: near-field entries of segment pairs closer than factor·max(h);
  // 0 (default): the whole near field. Measured on a 0.3 µm hummingbird segment (20 ppw, 8 556
  // unknowns, tolerance 1e-6): whole near field 66 / 77 iterations, factor 10: 183 / 209, factor 4:
  // > 1500 (NOTES.md §5).
  double preconditioner_factor = 0.0;
  // near_field: SparseLU of (part of) the near field (above). dense_single: the whole operator
  // expanded to complex<float> and factorised (single_precision_lu.hpp) — 8 N² bytes, for rod
  // lattices where no near field that fits in memory preconditions (NOTES.md §5); no near-field
  // copy is kept then.
  // hodlr: hierarchical LU of the whole operator with weak admissibility (hodlr.hpp), no near-field
  // copy either.
  enum class Preconditioner { near_field, dense_single, hodlr };
  Preconditioner preconditioner = Preconditioner::near_field;
};

struct HMatrixStats {
  long admissible_blocks = 0, dense_blocks = 0, near_pairs = 0;
  long lowrank_entries = 0;  // complex numbers stored in U, V (and dense fallbacks)
  long near_nonzeros = 0, preconditioner_nonzeros = 0;
  int max_rank = 0;
  double mean_rank = 0;
  double near_seconds = 0, aca_seconds = 0;
  double memory_gb() const;
};

// The 8×8 local block of domain `dom` for test segment A, basis segment B (σ signs applied).
Local8 local_pair(const Segment& A, const Segment& B, const PairIntegrals& in, int dom, const Medium& m, double k0,
                  double beta);

class HMatrix {
 public:
  // `progress_step`: the step name under which the assembly reports its progress (near-field pairs
  // integrated, ACA blocks compressed; plumage/memory_budget.hpp report_step), "" for none.
  HMatrix(const Mesh& mesh, const std::vector<Medium>& media, double k0, double beta, const QuadratureOptions& q,
          const HMatrixOptions& options, std::string progress_step = {});
  int size() const { return n_; }
  // y = Z x
  void apply(const Eigen::VectorXcd& x, Eigen::VectorXcd& y) const;
  // Y = Z X for every column: one pass over the near field and the compressed blocks for all of them
  // (the right-hand sides of one (λ, θ_i) solved together, bem_solver.cpp).
  void apply(const Eigen::MatrixXcd& X, Eigen::MatrixXcd& Y) const;
  const Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor>& near() const { return near_; }
  // The preconditioner's part of the near field (column major, for SparseLU).
  Eigen::SparseMatrix<std::complex<double>> take_preconditioner_matrix() { return std::move(pre_); }
  const HMatrixStats& stats() const { return stats_; }
  // The whole operator as a dense complex<float> matrix: the near field plus every admissible
  // block expanded (its kernels U V, then the Galerkin algebra of local_block per segment pair).
  // Summed in a fixed order: the same bits on any thread count.
  Eigen::MatrixXcf to_dense_single(const Mesh& mesh, const std::vector<Medium>& media) const;

 private:
  friend class HMatrixEntries;  // rows and columns of Z for the HODLR preconditioner (hmatrix_entries.hpp)
  struct LowRank {
    int r0 = 0, nr = 0, c0 = 0, nc = 0;  // segment ranges (cluster order)
    Eigen::MatrixXcd U[3], V[3];         // kernels I, X, Z: U 2nr × k, V k × 2nc; or U dense, V empty
  };
  struct Domain {
    std::vector<int> loc2glob;  // 8 per segment in cluster order
    std::vector<int> seg;       // mesh segment index per cluster-order position
    std::vector<double> tx, tz, nx, nz, h, sign;  // per segment in cluster order; sign = σ of the domain
    std::complex<double> eps;
    std::vector<LowRank> blocks;
  };
  double k0_ = 0, beta_ = 0;
  std::string progress_step_;
  void build_near_field(const Mesh& mesh, const std::vector<Medium>& media, const QuadratureOptions& q,
                        const HMatrixOptions& options, const std::vector<ClusterTree>& trees,
                        const std::vector<BlockPartition>& parts);
  void compress_blocks(const Mesh& mesh, const std::vector<Medium>& media, const QuadratureOptions& q,
                       const HMatrixOptions& options, const std::vector<ClusterTree>& trees,
                       const std::vector<BlockPartition>& parts);
  void apply_block(const Domain& d, const LowRank& b, const Eigen::MatrixXcd& xl, Eigen::MatrixXcd& out) const;
  int n_ = 0;
  std::vector<Domain> domains_;
  Eigen::SparseMatrix<std::complex<double>, Eigen::RowMajor> near_;
  Eigen::SparseMatrix<std::complex<double>> pre_;
  HMatrixStats stats_;
};

}  // namespace plumage::bem
