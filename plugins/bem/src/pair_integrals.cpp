// Segment-pair integrals: Gauss for separated pairs; for self, adjacent and near pairs the
// static log and 1/R parts are integrated analytically over the source segment (singular.cpp)
// and the smooth remainder G_reg, G'_reg by Gauss (spec §6.5).
#include "pair_integrals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "numerics/hankel.hpp"
#include "quadrature.hpp"
#include "singular.hpp"

namespace plumage::bem {

namespace {

constexpr double kInv2Pi = 0.5 / std::numbers::pi;
const cplx kI{0.0, 1.0};

double point_segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return norm(p - (a + t * d));
}

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

// Outer pieces [lo, hi] ⊂ [0, 1] of the test segment A for a near, non-touching pair: the uniform
// pieces, each bisected until it lies at least half its length away from the source segment B
// (then the inner integral, analytic on the piece, is integrated by `per_piece`-point Gauss to
// ~1e-9: Bernstein-ellipse parameter ≥ 2 + √3). Regular meshes keep the uniform pieces; the
// refinement acts where B runs within ~1 nm of a 10-30 nm segment (the hummingbird generator's thin
// air gaps and sub-nm edges, NOTES.md §5), which the uniform rule integrated only to ~1e-2.
void refine_pieces(const Segment& A, const Segment& B, double lo, double hi, int depth,
                   std::vector<std::pair<double, double>>& out) {
  Segment piece = A;
  piece.p0 = A.p0 + (lo * A.h) * A.t;
  piece.p1 = A.p0 + (hi * A.h) * A.t;
  piece.h = (hi - lo) * A.h;
  if (depth >= 40 || segment_distance(piece, B) >= 0.5 * piece.h) {
    out.push_back({lo, hi});
    return;
  }
  const double mid = 0.5 * (lo + hi);
  refine_pieces(A, B, lo, mid, depth + 1, out);
  refine_pieces(A, B, mid, hi, depth + 1, out);
}

}  // namespace

double segment_distance(const Segment& A, const Segment& B) {
  if (segments_cross(A.p0, A.p1, B.p0, B.p1)) return 0.0;
  return std::min({point_segment_distance(A.p0, B.p0, B.p1), point_segment_distance(A.p1, B.p0, B.p1),
                   point_segment_distance(B.p0, A.p0, A.p1), point_segment_distance(B.p1, A.p0, A.p1)});
}

PairIntegrals pair_integrals(const Segment& A, const Segment& B, cplx gamma, bool same,
                             const QuadratureOptions& q) {
  PairIntegrals out;
  const double hmax = std::max(A.h, B.h);
  const double dist = same ? 0.0 : segment_distance(A, B);
  if (!same && dist > q.near_factor * hmax) {
    for_each_far_node(A, B, gamma, q.far_points,
                      [&](const double* Na, const double* Nb, const Vec2& d, double R, cplx G, cplx dG, double w_unit) {
                        const double w = w_unit * A.h * B.h;
                        const double ra = dot(d, A.n) / R, rb = dot(d, B.n) / R;
                        for (int i = 0; i < 2; ++i) {
                          for (int j = 0; j < 2; ++j) {
                            const double wn = w * Na[i] * Nb[j];
                            out.I[i][j] += wn * G;
                            out.P[i][j] += (wn * ra) * dG;
                            out.Q[i][j] += (wn * rb) * dG;
                          }
                        }
                      });
    return out;
  }

  // Near pair. Outer rule on A: graded toward the shared vertex for adjacent pairs.
  int shared_end = -1;  // 0: A.v0 is shared, 1: A.v1
  if (!same) {
    if (A.v0 == B.v0 || A.v0 == B.v1) shared_end = 0;
    else if (A.v1 == B.v0 || A.v1 == B.v1) shared_end = 1;
  }
  Rule outer;
  if (shared_end >= 0) {
    // Geometric pieces toward the shared vertex; a piece away from the vertex that B still comes
    // close to (a cusp: B folding back along A) is bisected as in refine_pieces.
    const Rule& g = gauss_legendre(q.near_outer);
    std::vector<std::pair<double, double>> pieces;
    double hi = 1.0;
    for (int p = 0; p < q.adjacent_pieces; ++p) {
      const double lo = p + 1 == q.adjacent_pieces ? 0.0 : hi * 0.25;
      if (lo == 0.0) pieces.push_back({lo, hi});
      else if (shared_end == 0) refine_pieces(A, B, lo, hi, 0, pieces);
      else refine_pieces(A, B, 1.0 - hi, 1.0 - lo, 0, pieces);
      if (shared_end == 1 && lo == 0.0) pieces.back() = {1.0 - hi, 1.0};
      hi = lo;
    }
    for (const auto& [lo, hi2] : pieces) {
      for (std::size_t k = 0; k < g.x.size(); ++k) {
        // toward the shared vertex the nodes must be in the graded order of graded_rule
        const double u = shared_end == 0 ? lo + (hi2 - lo) * g.x[k] : hi2 - (hi2 - lo) * g.x[k];
        outer.x.push_back(u);
        outer.w.push_back((hi2 - lo) * g.w[k]);
      }
    }
  } else {
    const Rule& g = gauss_legendre(q.near_outer);
    std::vector<std::pair<double, double>> pieces;
    for (int piece = 0; piece < q.near_pieces; ++piece) {
      const double lo = static_cast<double>(piece) / q.near_pieces, hi = static_cast<double>(piece + 1) / q.near_pieces;
      if (same) pieces.push_back({lo, hi});
      else refine_pieces(A, B, lo, hi, 0, pieces);
    }
    for (const auto& [lo, hi] : pieces) {
      for (std::size_t k = 0; k < g.x.size(); ++k) {
        outer.x.push_back(lo + (hi - lo) * g.x[k]);
        outer.w.push_back((hi - lo) * g.w[k]);
      }
    }
  }
  const Rule& gi = gauss_legendre(q.inner_regular);
  if (same) {
    // static part in closed form: ∫∫ N_i N_j (−ln|u − u'|/(2π))
    const auto L = self_log_integral(A.h);
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) out.I[i][j] += -kInv2Pi * L[i][j];
    }
  }
  for (std::size_t a = 0; a < outer.x.size(); ++a) {
    const Vec2 p = A.p0 + (outer.x[a] * A.h) * A.t;
    const double Na[2] = {1.0 - outer.x[a], outer.x[a]};
    const double wa = outer.w[a] * A.h;
    cplx g_in[2] = {0.0, 0.0};
    cplx d_in_a[2] = {0.0, 0.0}, d_in_b[2] = {0.0, 0.0};
    if (!same) {
      const StaticInner st = static_inner(p, B.p0, B.t, B.h);
      for (int j = 0; j < 2; ++j) {
        g_in[j] += -kInv2Pi * st.log[j];
        d_in_a[j] += -kInv2Pi * dot(st.vec[j], A.n);
        d_in_b[j] += -kInv2Pi * dot(st.vec[j], B.n);
      }
    }
    for (std::size_t b = 0; b < gi.x.size(); ++b) {
      const Vec2 s = B.p0 + (gi.x[b] * B.h) * B.t;
      const double Nb[2] = {1.0 - gi.x[b], gi.x[b]};
      const Vec2 d = p - s;
      const double R = norm(d);
      const GreenReg gr = green2d_reg_both(gamma, R);
      const double wb = gi.w[b] * B.h;
      const double ra = R > 0 ? dot(d, A.n) / R : 0.0, rb = R > 0 ? dot(d, B.n) / R : 0.0;
      for (int j = 0; j < 2; ++j) {
        g_in[j] += (wb * Nb[j]) * gr.g;
        if (!same) {
          d_in_a[j] += (wb * Nb[j] * ra) * gr.dg;
          d_in_b[j] += (wb * Nb[j] * rb) * gr.dg;
        }
      }
    }
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        out.I[i][j] += (wa * Na[i]) * g_in[j];
        out.P[i][j] += (wa * Na[i]) * d_in_a[j];
        out.Q[i][j] += (wa * Na[i]) * d_in_b[j];
      }
    }
  }
  return out;
}

}  // namespace plumage::bem
