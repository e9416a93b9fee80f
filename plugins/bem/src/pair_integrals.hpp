// Galerkin double integrals over a (test, basis) segment pair for one domain (spec §6.4–6.5):
//   I_ij = ∫∫ N_i N_j G,   P_ij = ∫∫ N_i N_j G'(R) R̂·n̂_A,   Q_ij = ∫∫ N_i N_j G'(R) R̂·n̂_B,
// G = (i/4) H0^(1)(γR), G' = dG/dR, R̂ = (ρ − ρ')/R, ρ on the test segment A, ρ' on B.
#pragma once

#include <array>
#include <complex>

#include "mesh.hpp"

namespace plumage::bem {

using cplx = std::complex<double>;
using Block2 = std::array<std::array<cplx, 2>, 2>;

struct PairIntegrals {
  Block2 I{}, P{}, Q{};
};

struct QuadratureOptions {
  int far_points = 4;        // per segment, pairs farther apart than near_factor·h
  double near_factor = 2.0;
  int near_outer = 8;        // per piece of the outer rule for near pairs
  int near_pieces = 3;       // uniform pieces for near, non-touching pairs
  int adjacent_pieces = 8;   // geometric pieces (ratio 1/4) toward a shared vertex
  int inner_regular = 6;     // Gauss points for the smooth remainder of near pairs
};

PairIntegrals pair_integrals(const Segment& A, const Segment& B, cplx gamma, bool same,
                             const QuadratureOptions& q);

// Smallest distance between two segments.
double segment_distance(const Segment& A, const Segment& B);

}  // namespace plumage::bem
