// Peak memory of one BEM solve at (λ, θ_i), estimated from the mesh before anything is assembled
// (issue 23 Deliver 2, plumage/memory_budget.hpp). build_system refuses a system over the budget
// with MemoryBudgetError (exit status 2) naming the estimate and the options that lower it;
// BemSolver::estimate_memory gives `plumage check` the same number.
//
// The parts (bytes), with N unknowns, R right-hand sides (2 per incident azimuth), P far-field
// directions:
//   dense/gmres: the matrix 16 N^2; gmres adds the near-field LU and the Krylov basis.
//   hmatrix:     the exact near field (counted: the near pairs of the block partition, ~34 stored
//                entries of 20 bytes each, measured 27-33) twice (mat-vec copy and the
//                preconditioner's), the ACA blocks (rank <= 16 per kernel), the sparse LU's fill-in
//                (a model fitted to the measured peaks of NOTES.md / docs/benchmarks.md: 8 x 16 bytes
//                per near entry at 14 000 unknowns, growing as N^0.4) and the Krylov basis;
//                dense_single replaces the sparse LU by 8 N^2 bytes.
//   all:         right-hand sides, solutions and warm-start products 3 x 16 N R, the far-field
//                operator 48 N P and its product's workspace 16 N P, and 64 bytes per unknown of
//                mesh and bookkeeping.
// The estimate is one solve's; the pipeline multiplies it by the solves it runs at a time and
// adds what the process already holds (core/src/pipeline/solve_memory.hpp).
// docs/benchmarks.md "Memory estimates" compares it with measured peaks (an upper bound within ~2x).
#pragma once

#include "bem_options.hpp"
#include "mesh.hpp"
#include "plumage/memory_budget.hpp"

namespace plumage::bem {

MemoryEstimate estimate_system_memory(const Mesh& mesh, double lambda_nm, const BemOptions& options, int rhs,
                                      int far_directions);

// Sizes of the H-matrix's block partition (cluster trees only: no integral is computed).
struct HMatrixSizes {
  long near_pairs = 0;         // segment pairs of the inadmissible leaf blocks
  long admissible_blocks = 0;  // low-rank blocks
  double lowrank_rows = 0;     // sum over admissible blocks of 2 (|sigma| + |tau|)
};
HMatrixSizes hmatrix_sizes(const Mesh& mesh, const QuadratureOptions& q, const HMatrixOptions& options);

}  // namespace plumage::bem
