// Galerkin double integrals over a (test, basis) segment pair for one domain (spec §6.4–6.5):
//   I_ij = ∫∫ N_i N_j G,   P_ij = ∫∫ N_i N_j G'(R) R̂·n̂_A,   Q_ij = ∫∫ N_i N_j G'(R) R̂·n̂_B,
// G = (i/4) H0^(1)(γR), G' = dG/dR, R̂ = (ρ − ρ')/R, ρ on the test segment A, ρ' on B.
#pragma once

#include <array>
#include <complex>

#include "mesh.hpp"
#include "numerics/hankel.hpp"
#include "quadrature.hpp"

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

// Tensor Gauss rule over a well-separated pair (no singularity): calls
// visit(Na, Nb, d, R, G, dG, w) at every node pair with the tent values Na[2], Nb[2], d = ρ − ρ',
// R = |d|, G and G' = dG/dR, and w the product of the reference-rule weights (per unit length of
// both segments; multiply by h_A h_B for the integral). Shared by the Galerkin far pairs and the
// hierarchical matrix's per-length kernels, so the two agree node for node.
template <class Visit>
void for_each_far_node(const Segment& A, const Segment& B, cplx gamma, int points, Visit&& visit) {
  static const cplx kI{0.0, 1.0};
  const Rule& g = gauss_legendre(points);
  const int n = static_cast<int>(g.x.size());
  for (int a = 0; a < n; ++a) {
    const Vec2 p = A.p0 + (g.x[a] * A.h) * A.t;
    const double Na[2] = {1.0 - g.x[a], g.x[a]};
    for (int b = 0; b < n; ++b) {
      const Vec2 s = B.p0 + (g.x[b] * B.h) * B.t;
      const double Nb[2] = {1.0 - g.x[b], g.x[b]};
      const Vec2 d = p - s;
      const double R = norm(d);
      const H01 h = hankel1_01(gamma * R);
      const cplx G = 0.25 * kI * h.h0;
      const cplx dG = -0.25 * kI * gamma * h.h1;
      visit(Na, Nb, d, R, G, dG, g.w[a] * g.w[b]);
    }
  }
}

PairIntegrals pair_integrals(const Segment& A, const Segment& B, cplx gamma, bool same,
                             const QuadratureOptions& q);

// Smallest distance between two segments.
double segment_distance(const Segment& A, const Segment& B);

}  // namespace plumage::bem
