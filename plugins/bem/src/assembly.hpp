// Dense multi-region PMCHWT matrix (spec §6.3–6.4) in the scaled form J̃ = η0 J, H-equations × η0:
//   E rows: Σ_r σ_{r,i} Σ_j σ_{r,j} [ L_r J̃_j − K_r M_j ],   L_r = L[a = 1, b = 1/ε_r]
//   H rows: Σ_r σ_{r,i} Σ_j σ_{r,j} [ K_r J̃_j + L'_r M_j ],  L'_r = L[a = ε_r, b = 1]
// with L[a, b] X = i k0 a ∫ G X + (i b/k0) ∇ ∫ G ∇'_s·X (ωμ0/η0 = k0, 1/(ωε_r η0) = 1/(k0 ε_r)).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "mesh.hpp"
#include "pair_integrals.hpp"

namespace plumage::bem {

struct Medium {
  cplx eps;    // ε_r = n²
  cplx gamma;  // sqrt(k_r² − β²), Im ≥ 0
};

std::vector<Medium> media(const Geometry& geometry, double lambda_nm, double beta);

// Adds domain `d`'s operator for the segment pair (A test, B basis) with signs σ_A σ_B into the
// 8×8 local block indexed [E_t0 E_t1 E_z0 E_z1 H_t0 H_t1 H_z0 H_z1] × [J_t0 J_t1 J_z0 J_z1 M_t0 M_t1 M_z0 M_z1].
using Local8 = std::array<std::array<cplx, 8>, 8>;
void local_block(const Segment& A, const Segment& B, const PairIntegrals& in, const Medium& m, double k0,
                 double beta, double sign, Local8& out);

// Global row/column index of local index l (0..7) of segment S.
int global_index(const Mesh& mesh, const Segment& S, int l);

Eigen::MatrixXcd assemble_dense(const Mesh& mesh, const std::vector<Medium>& media, double k0, double beta,
                                const QuadratureOptions& q);

}  // namespace plumage::bem
