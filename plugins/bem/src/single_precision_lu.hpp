// Dense LU in single precision as a GMRES preconditioner (method hmatrix, preconditioner
// dense_single; NOTES.md §5, "mallard rod lattice").
//
// Why: on lattices of many small regions (the mallard's melanin rods) the near-field LU that fits in
// memory is no preconditioner at all (GMRES stagnated at residual 0.30), while the system is small
// enough (~35 000 unknowns) that the whole operator fits as N² complex<float> (8 B each, 10 GB at
// 35 400). The factors of a single-precision copy of Z are an almost exact inverse: the preconditioned
// operator is I + O(cond(Z)·1e-7), so GMRES in double with the H-matrix mat-vec (the accurate
// operator) needs a handful of iterations and the solution keeps double accuracy — mixed-precision
// iterative refinement, with GMRES as the refinement loop.
//
// The factorisation is a right-looking blocked LU with partial pivoting (recursive panels, then the
// trailing update in fixed column tiles run by oneTBB, each tile one single-threaded Eigen GEMM), so
// the factors are bit-identical for any thread count. Eigen's own PartialPivLU parallelises only
// with OpenMP, which the project does not use.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <vector>

namespace plumage::bem {

class SinglePrecisionLU {
 public:
  // Factorises A in place (A is moved in and holds L\U afterwards). `panel` is the block width;
  // `progress`, if set, is called after each panel with the fraction of the flops done.
  explicit SinglePrecisionLU(Eigen::MatrixXcf&& A, int panel = 256,
                             const std::function<void(double)>& progress = {});
  // out = A⁻¹ in, computed in single precision (the preconditioner's job: no refinement here).
  void apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const;
  int size() const { return static_cast<int>(lu_.rows()); }
  double memory_gb() const { return double(lu_.size()) * sizeof(std::complex<float>) / 1e9; }
  // Row interchanges as LAPACK's ipiv (0-based): row k was swapped with row pivots()[k], in order.
  const std::vector<int>& pivots() const { return piv_; }
  const Eigen::MatrixXcf& factors() const { return lu_; }

 private:
  Eigen::MatrixXcf lu_;
  std::vector<int> piv_;
};

}  // namespace plumage::bem
