// Restarted GMRES(m) with right preconditioning for complex systems (issue 6 Deliver 2), and the
// near-field sparse-LU preconditioner. The mat-vec is an Op: the dense matrix (method gmres) or the
// hierarchical matrix (method hmatrix, hmatrix.hpp; NOTES.md §5).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <functional>
#include <vector>

#include "mesh.hpp"

namespace plumage::bem {

using Op = std::function<void(const Eigen::VectorXcd& in, Eigen::VectorXcd& out)>;

struct GmresResult {
  int iterations = 0;
  double relative_residual = 0.0;
  bool converged = false;
};

// Solves A x = b to ‖b − A x‖ ≤ tol ‖b‖ (x holds the initial guess on entry). Stores the
// restart + 1 Krylov vectors only (the preconditioner is applied once more to their combination).
// `progress`, if set, is called after every iteration with (iterations so far, relative residual).
GmresResult gmres(const Op& A, const Op& precondition, const Eigen::VectorXcd& b, Eigen::VectorXcd& x, double tol,
                  int restart, int max_iterations,
                  const std::function<void(int, double)>& progress = {});

using BlockOp = std::function<void(const Eigen::MatrixXcd& in, Eigen::MatrixXcd& out)>;

// The columns of A X = B by the restarted GMRES above — each column its own Krylov space, stopping
// test, restarts and iteration count — run in lockstep: every step applies the preconditioner and
// then the operator once to the current vectors of all unconverged columns together (one pass over
// the compressed matrices for all of them, NOTES.md §5 "Right-hand sides together"). X holds the
// initial guesses on entry. Flexible GMRES (Saad 1993): the preconditioned vectors z_j = M v_j are
// kept and x += Z y, so a preconditioner applied in single precision (hodlr, dense_single: linear
// only to ~1e-7) does not limit the attainable residual; 2 restart + 1 vectors per column.
// `progress(column, iterations, residual)`.
std::vector<GmresResult> gmres_lockstep(const BlockOp& A, const BlockOp& precondition, const Eigen::MatrixXcd& B,
                                        Eigen::MatrixXcd& X, double tol, int restart, int max_iterations,
                                        const std::function<void(int, int, double)>& progress = {});

// Near-field preconditioner: the entries of Z coupling segments closer than `factor`·max(h)
// (the locally singular part of the operator), as a sparse matrix factorised by SparseLU.
class NearFieldLU {
 public:
  NearFieldLU(const Mesh& mesh, const Eigen::MatrixXcd& Z, double factor);
  // From a near-field matrix already in sparse form (the H-matrix's exact near field).
  explicit NearFieldLU(const Eigen::SparseMatrix<std::complex<double>>& S);
  void apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const;
  long nonzeros() const { return nnz_; }

 private:
  Eigen::SparseLU<Eigen::SparseMatrix<std::complex<double>>> lu_;
  long nnz_ = 0;
};

}  // namespace plumage::bem
