// Adaptive cross approximation (ACA, partial pivoting) of the admissible blocks of the hierarchical
// matrix (hmatrix.hpp; NOTES.md §5). Not the 8×8 Galerkin blocks are compressed but the three smooth
// kernel matrices of a block, per unit length of both segments (tents i of the test segment A, j of
// the basis segment B):
//   I_ij = ∫∫ N_i N_j G,   X_ij = ∫∫ N_i N_j G' R̂_x,   Z_ij = ∫∫ N_i N_j G' R̂_z
// (the 4×4 Gauss branch of pair_integrals, which every pair of an admissible block uses).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "mesh.hpp"
#include "pair_integrals.hpp"

namespace plumage::bem {

// The kernels I, X, Z (k = 0, 1, 2) of the block of test segments order[r0, r0 + nr) and basis
// segments order[c0, c0 + nc) of one domain (transverse wavenumber gamma, `points` Gauss points per
// segment), each to relative Frobenius error eps: U[k] (2nr × rank) times V[k] (rank × 2nc), or
// U[k] the whole block and V[k] empty where the rank would not save memory.
void compress_far_kernels(const Mesh& mesh, const std::vector<int>& order, cplx gamma, int points, int r0, int nr,
                          int c0, int nc, double eps, Eigen::MatrixXcd (&U)[3], Eigen::MatrixXcd (&V)[3]);

}  // namespace plumage::bem
