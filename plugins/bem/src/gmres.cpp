#include "gmres.hpp"

#include <cmath>
#include <unordered_set>

#include "assembly.hpp"
#include "pair_integrals.hpp"

namespace plumage::bem {

GmresResult gmres(const Op& A, const Op& M, const Eigen::VectorXcd& b, Eigen::VectorXcd& x, double tol, int m,
                  int max_iterations, const std::function<void(int, double)>& progress) {
  using V = Eigen::VectorXcd;
  GmresResult res;
  const double bnorm = b.norm();
  if (bnorm == 0.0) {
    x.setZero();
    res.converged = true;
    return res;
  }
  V r(b.size()), w(b.size()), z(b.size());
  std::vector<V> Vb(m + 1);
  Eigen::MatrixXcd H = Eigen::MatrixXcd::Zero(m + 1, m);
  std::vector<std::complex<double>> cs(m), sn(m), g(m + 1);
  A(x, w);
  r = b - w;
  double rnorm = r.norm();
  while (res.iterations < max_iterations) {
    if (rnorm <= tol * bnorm) break;
    Vb[0] = r / rnorm;
    std::fill(g.begin(), g.end(), 0.0);
    g[0] = rnorm;
    int k = 0;
    for (; k < m && res.iterations < max_iterations; ++k) {
      M(Vb[k], z);
      A(z, w);
      for (int j = 0; j <= k; ++j) {  // modified Gram–Schmidt
        H(j, k) = Vb[j].dot(w);
        w -= H(j, k) * Vb[j];
      }
      H(k + 1, k) = w.norm();
      Vb[k + 1] = w / H(k + 1, k).real();
      for (int j = 0; j < k; ++j) {  // previous Givens rotations
        const auto t = cs[j] * H(j, k) + sn[j] * H(j + 1, k);
        H(j + 1, k) = -std::conj(sn[j]) * H(j, k) + std::conj(cs[j]) * H(j + 1, k);
        H(j, k) = t;
      }
      const double a = std::abs(H(k, k)), bb = std::abs(H(k + 1, k));
      const double d = std::hypot(a, bb);
      cs[k] = a == 0.0 ? std::complex<double>(0.0) : std::complex<double>(a / d);
      sn[k] = a == 0.0 ? std::complex<double>(1.0) : (H(k, k) / a) * std::conj(H(k + 1, k)) / d;
      H(k, k) = cs[k] * H(k, k) + sn[k] * H(k + 1, k);
      H(k + 1, k) = 0.0;
      g[k + 1] = -std::conj(sn[k]) * g[k];
      g[k] = cs[k] * g[k];
      ++res.iterations;
      if (progress) progress(res.iterations, std::abs(g[k + 1]) / bnorm);
      if (std::abs(g[k + 1]) <= tol * bnorm) {
        ++k;
        break;
      }
    }
    // y = H⁻¹ g (upper triangular), x += Σ Z_j y_j
    std::vector<std::complex<double>> y(k);
    for (int i = k - 1; i >= 0; --i) {
      auto s = g[i];
      for (int j = i + 1; j < k; ++j) s -= H(i, j) * y[j];
      y[i] = s / H(i, i);
    }
    w.setZero();
    for (int j = 0; j < k; ++j) w += y[j] * Vb[j];
    M(w, z);  // right preconditioning: x += M⁻¹ V y
    x += z;
    A(x, w);
    r = b - w;
    rnorm = r.norm();
  }
  res.relative_residual = rnorm / bnorm;
  res.converged = res.relative_residual <= tol * 1.0000001;
  return res;
}

NearFieldLU::NearFieldLU(const Mesh& mesh, const Eigen::MatrixXcd& Z, double factor) {
  const auto n = static_cast<long>(Z.rows());
  std::unordered_set<long> seen;
  std::vector<Eigen::Triplet<std::complex<double>>> t;
  const int ns = static_cast<int>(mesh.segments.size());
  for (int a = 0; a < ns; ++a) {
    const Segment& A = mesh.segments[a];
    for (int b = 0; b < ns; ++b) {
      const Segment& B = mesh.segments[b];
      if (a != b && segment_distance(A, B) > factor * std::max(A.h, B.h)) continue;
      for (int r = 0; r < 8; ++r) {
        const long i = global_index(mesh, A, r);
        for (int c = 0; c < 8; ++c) {
          const long j = global_index(mesh, B, c);
          if (seen.insert(i * n + j).second) t.emplace_back(i, j, Z(i, j));
        }
      }
    }
  }
  Eigen::SparseMatrix<std::complex<double>> S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  nnz_ = S.nonZeros();
  lu_.analyzePattern(S);
  lu_.factorize(S);
}

NearFieldLU::NearFieldLU(const Eigen::SparseMatrix<std::complex<double>>& S) {
  nnz_ = S.nonZeros();
  lu_.analyzePattern(S);
  lu_.factorize(S);
}

void NearFieldLU::apply(const Eigen::VectorXcd& in, Eigen::VectorXcd& out) const { out = lu_.solve(in); }

}  // namespace plumage::bem
