// Rows and columns of the H-matrix operator Z = N + Σ blocks (hmatrix.hpp), restricted to a window
// of a permuted index order: the entry oracle of the HODLR preconditioner (hodlr.hpp; NOTES.md §5
// "Preconditioner hodlr"). An entry is exactly what HMatrix::apply multiplies by: the near field's value, or an
// ACA block's kernels U V expanded through the Galerkin algebra of local_pair (as to_dense_single
// does for the whole matrix). A row of a window of width w costs O(w + blocks on the row's
// segments), not O(N): blocks and segments are skipped when they lie outside the window's box.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

#include "hmatrix.hpp"
#include "hodlr.hpp"

namespace plumage::bem {

// Position of every unknown (the vertex of its tent), in the global order: the points of the
// HODLR bisection.
std::vector<Vec2> unknown_positions(const Mesh& mesh);

class HMatrixEntries {
 public:
  // `perm[p]` = global unknown at position p of the HODLR order (hodlr.hpp).
  HMatrixEntries(const HMatrix& H, const Mesh& mesh, const std::vector<Medium>& media, const std::vector<int>& perm);
  // out[q − w.begin] = Z(perm[p], perm[q]) for q in [w.begin, w.end)
  void row(int p, const IndexBox& w, Eigen::VectorXcd& out) const;
  // out[q − w.begin] = Z(perm[q], perm[p])
  void column(int p, const IndexBox& w, Eigen::VectorXcd& out) const;
  double memory_gb() const;

 private:
  struct Slot {
    int dom, s, l;  // domain, cluster-order segment position, local index (0..7)
  };
  struct Box {
    double xmin, xmax, zmin, zmax;
  };
  bool segment_in(int dom, int s, const IndexBox& w) const;
  void far_part(int p, const IndexBox& w, bool transpose, Eigen::VectorXcd& out) const;
  const HMatrix& H_;
  const Mesh& mesh_;
  const std::vector<Medium>& media_;
  std::vector<int> perm_, ipos_;
  std::vector<std::vector<Slot>> slots_;                  // per global unknown
  std::vector<std::vector<std::vector<int>>> row_blocks_;  // [dom][s]: blocks whose rows hold s
  std::vector<std::vector<std::vector<int>>> col_blocks_;  // [dom][s]: blocks whose columns hold s
  std::vector<std::vector<Box>> row_box_, col_box_;       // [dom][block]: segment boxes of its rows / columns
};

}  // namespace plumage::bem
