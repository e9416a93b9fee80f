// Galerkin blocks of spec §6.4 per segment pair and domain; see assembly.hpp.
#include "assembly.hpp"

#include <tbb/parallel_for.h>

namespace plumage::bem {

namespace {
const cplx kI{0.0, 1.0};
}

std::vector<Medium> media(const Geometry& geometry, double lambda_nm, double beta) {
  const double k0 = 2.0 * std::numbers::pi / lambda_nm;
  std::vector<Medium> out;
  for (const Material& m : geometry.domain_material) {
    const cplx n = m.index(lambda_nm);
    Medium md;
    md.eps = n * n;
    md.gamma = std::sqrt(k0 * k0 * md.eps - beta * beta);  // principal branch: Im ≥ 0 for Im ε ≥ 0
    if (md.gamma.imag() < 0.0) md.gamma = -md.gamma;
    out.push_back(md);
  }
  return out;
}

int global_index(const Mesh& mesh, const Segment& S, int l) {
  const int node = l & 1;
  switch (l >> 1) {
    case 0: return mesh.jt(node ? S.v1 : S.v0);
    case 1: return mesh.jz(S.zdof[node]);
    case 2: return mesh.mt(node ? S.v1 : S.v0);
    default: return mesh.mz(S.zdof[node]);
  }
}

void local_block(const Segment& A, const Segment& B, const PairIntegrals& in, const Medium& m, double k0,
                 double beta, double sign, Local8& out) {
  const double d[2] = {-1.0, 1.0};  // N_i' = d_i / h
  cplx S = 0.0, col[2] = {0.0, 0.0}, row[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      S += in.I[i][j];
      col[j] += in.I[i][j];
      row[i] += in.I[i][j];
    }
  }
  const double tt = dot(A.t, B.t), tn = dot(A.t, B.n);
  // L[a, b] blocks (§6.4 with ωμ0 → k0 a, 1/(ωε) → b/k0)
  auto L = [&](cplx a, cplx b, int r0, int c0) {
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const cplx Ltt = kI * k0 * a * tt * in.I[i][j] - (kI * b / k0) * (d[i] * d[j] / (A.h * B.h)) * S;
        const cplx Ltz = (beta * b / k0) * (d[i] / A.h) * col[j];
        const cplx Lzt = -(beta * b / k0) * (d[j] / B.h) * row[i];
        const cplx Lzz = kI * (k0 * a - b * beta * beta / k0) * in.I[i][j];
        out[r0 + i][c0 + j] += sign * Ltt;
        out[r0 + i][c0 + 2 + j] += sign * Ltz;
        out[r0 + 2 + i][c0 + j] += sign * Lzt;
        out[r0 + 2 + i][c0 + 2 + j] += sign * Lzz;
      }
    }
  };
  // K blocks: tt = iβ (t̂_A·n̂_B) I, tz = P, zt = −Q, zz = 0; `ks` = +1 (H rows) or −1 (E rows)
  auto K = [&](double ks, int r0, int c0) {
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        out[r0 + i][c0 + j] += (sign * ks) * (kI * beta * tn * in.I[i][j]);
        out[r0 + i][c0 + 2 + j] += (sign * ks) * in.P[i][j];
        out[r0 + 2 + i][c0 + j] += (sign * ks) * (-in.Q[i][j]);
      }
    }
  };
  L(1.0, 1.0 / m.eps, 0, 0);  // E rows, J̃ columns
  K(-1.0, 0, 4);              // E rows, M columns
  K(+1.0, 4, 0);              // H rows, J̃ columns
  L(m.eps, 1.0, 4, 4);        // H rows, M columns
}

Eigen::MatrixXcd assemble_dense(const Mesh& mesh, const std::vector<Medium>& md, double k0, double beta,
                                const QuadratureOptions& q) {
  const int n = mesh.unknowns();
  Eigen::MatrixXcd Z = Eigen::MatrixXcd::Zero(n, n);
  auto scatter = [&](const Segment& A, const Segment& B, const PairIntegrals& in, int dom) {
    const double sa = A.a == dom ? 1.0 : -1.0, sb = B.a == dom ? 1.0 : -1.0;
    Local8 loc{};
    local_block(A, B, in, md[dom], k0, beta, sa * sb, loc);
    int ra[8], cb[8];
    for (int l = 0; l < 8; ++l) ra[l] = global_index(mesh, A, l), cb[l] = global_index(mesh, B, l);
    for (int r = 0; r < 8; ++r) {
      for (int c = 0; c < 8; ++c) Z(ra[r], cb[c]) += loc[r][c];
    }
  };
  // Pair integrals of a block of rows in parallel (oneTBB), then scattered in a fixed order, so the
  // matrix does not depend on the thread count.
  constexpr std::size_t kRows = 64;
  for (int dom = 0; dom < mesh.a_count; ++dom) {
    const auto& segs = mesh.domain_segments[dom];
    const std::size_t n = segs.size();
    std::vector<std::vector<PairIntegrals>> buf(kRows);
    for (std::size_t x0 = 0; x0 < n; x0 += kRows) {
      const std::size_t x1 = std::min(n, x0 + kRows);
      tbb::parallel_for(x0, x1, [&](std::size_t x) {
        auto& row = buf[x - x0];
        row.resize(n - x);
        const Segment& A = mesh.segments[segs[x]];
        for (std::size_t y = x; y < n; ++y) {
          row[y - x] = pair_integrals(A, mesh.segments[segs[y]], md[dom].gamma, x == y, q);
        }
      });
      for (std::size_t x = x0; x < x1; ++x) {
        const Segment& A = mesh.segments[segs[x]];
        for (std::size_t y = x; y < n; ++y) {
          const Segment& B = mesh.segments[segs[y]];
          const PairIntegrals& in = buf[x - x0][y - x];
          scatter(A, B, in, dom);
          if (x == y) continue;
          // (B, A) from the same integrals: I' = Iᵀ, P' = −Qᵀ, Q' = −Pᵀ (R̂ changes sign)
          PairIntegrals tr;
          for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < 2; ++j) {
              tr.I[j][i] = in.I[i][j];
              tr.P[j][i] = -in.Q[i][j];
              tr.Q[j][i] = -in.P[i][j];
            }
          }
          scatter(B, A, tr, dom);
        }
      }
    }
  }
  return Z;
}

}  // namespace plumage::bem
