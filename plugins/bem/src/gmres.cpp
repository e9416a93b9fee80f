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

namespace {

// The state of one column of gmres_lockstep: its Arnoldi cycle (the same arithmetic as gmres()).
struct LockstepColumn {
  std::vector<Eigen::VectorXcd> V;  // Krylov basis of the current cycle
  std::vector<Eigen::VectorXcd> Zp;  // z_j = M v_j as applied (flexible GMRES)
  Eigen::MatrixXcd H;
  std::vector<std::complex<double>> cs, sn, g;
  int k = 0;
  double bnorm = 0;
  bool active = false;  // in a cycle
  GmresResult res;
};

// Starts a cycle from the residual r, or ends the column (converged or out of iterations).
void start_cycle(LockstepColumn& c, const Eigen::VectorXcd& r, double tol, int m, int max_iterations) {
  const double rnorm = r.norm();
  c.res.relative_residual = rnorm / c.bnorm;
  if (rnorm <= tol * c.bnorm || c.res.iterations >= max_iterations) {
    c.active = false;
    c.res.converged = c.res.relative_residual <= tol * 1.0000001;
    std::vector<Eigen::VectorXcd>().swap(c.V);
    std::vector<Eigen::VectorXcd>().swap(c.Zp);
    return;
  }
  c.V.assign(1, r / rnorm);
  c.Zp.clear();
  c.H = Eigen::MatrixXcd::Zero(m + 1, m);
  c.cs.assign(m, 0.0), c.sn.assign(m, 0.0), c.g.assign(m + 1, 0.0);
  c.g[0] = rnorm;
  c.k = 0;
  c.active = true;
}

// Arnoldi step with w = A M v_k (modified Gram–Schmidt, Givens rotations; as gmres()). Returns true
// when the cycle ends (converged, restart length or iteration limit reached).
bool arnoldi_step(LockstepColumn& c, Eigen::VectorXcd w, double tol, int m, int max_iterations) {
  const int k = c.k;
  auto& H = c.H;
  for (int j = 0; j <= k; ++j) {
    H(j, k) = c.V[j].dot(w);
    w -= H(j, k) * c.V[j];
  }
  H(k + 1, k) = w.norm();
  c.V.push_back(w / H(k + 1, k).real());
  for (int j = 0; j < k; ++j) {
    const auto t = c.cs[j] * H(j, k) + c.sn[j] * H(j + 1, k);
    H(j + 1, k) = -std::conj(c.sn[j]) * H(j, k) + std::conj(c.cs[j]) * H(j + 1, k);
    H(j, k) = t;
  }
  const double a = std::abs(H(k, k)), bb = std::abs(H(k + 1, k));
  const double d = std::hypot(a, bb);
  c.cs[k] = a == 0.0 ? std::complex<double>(0.0) : std::complex<double>(a / d);
  c.sn[k] = a == 0.0 ? std::complex<double>(1.0) : (H(k, k) / a) * std::conj(H(k + 1, k)) / d;
  H(k, k) = c.cs[k] * H(k, k) + c.sn[k] * H(k + 1, k);
  H(k + 1, k) = 0.0;
  c.g[k + 1] = -std::conj(c.sn[k]) * c.g[k];
  c.g[k] = c.cs[k] * c.g[k];
  ++c.res.iterations;
  ++c.k;
  return std::abs(c.g[k + 1]) <= tol * c.bnorm || c.k == m || c.res.iterations >= max_iterations;
}

// Σ y_j z_j with y = H⁻¹ g (upper triangular) of the ended cycle.
Eigen::VectorXcd cycle_combination(const LockstepColumn& c) {
  std::vector<std::complex<double>> y(c.k);
  for (int i = c.k - 1; i >= 0; --i) {
    auto s = c.g[i];
    for (int j = i + 1; j < c.k; ++j) s -= c.H(i, j) * y[j];
    y[i] = s / c.H(i, i);
  }
  Eigen::VectorXcd w = Eigen::VectorXcd::Zero(c.V[0].size());
  for (int j = 0; j < c.k; ++j) w += y[j] * c.Zp[j];
  return w;
}

}  // namespace

std::vector<GmresResult> gmres_lockstep(const BlockOp& A, const BlockOp& M, const Eigen::MatrixXcd& B,
                                        Eigen::MatrixXcd& X, double tol, int m, int max_iterations,
                                        const std::function<void(int, int, double)>& progress) {
  const int nc = static_cast<int>(B.cols());
  std::vector<LockstepColumn> cols(nc);
  Eigen::MatrixXcd W, Z;
  A(X, W);
  for (int j = 0; j < nc; ++j) {
    cols[j].bnorm = B.col(j).norm();
    if (cols[j].bnorm == 0.0) {
      X.col(j).setZero();
      cols[j].res.converged = true;
      continue;
    }
    start_cycle(cols[j], B.col(j) - W.col(j), tol, m, max_iterations);
  }
  for (;;) {
    std::vector<int> active;
    for (int j = 0; j < nc; ++j)
      if (cols[j].active) active.push_back(j);
    if (active.empty()) break;
    Eigen::MatrixXcd Vk(B.rows(), static_cast<Eigen::Index>(active.size()));
    for (std::size_t t = 0; t < active.size(); ++t) Vk.col(t) = cols[active[t]].V[cols[active[t]].k];
    M(Vk, Z);
    A(Z, W);
    std::vector<int> ended;
    for (std::size_t t = 0; t < active.size(); ++t) {
      LockstepColumn& c = cols[active[t]];
      c.Zp.push_back(Z.col(t));
      const bool end = arnoldi_step(c, W.col(t), tol, m, max_iterations);
      if (progress) progress(active[t], c.res.iterations, std::abs(c.g[c.k]) / c.bnorm);
      if (end) ended.push_back(active[t]);
    }
    if (ended.empty()) continue;
    // x += Z y (the preconditioned vectors as applied), then the true residual of the ended columns
    Eigen::MatrixXcd Xe(B.rows(), static_cast<Eigen::Index>(ended.size()));
    for (std::size_t t = 0; t < ended.size(); ++t) {
      X.col(ended[t]) += cycle_combination(cols[ended[t]]);
      Xe.col(t) = X.col(ended[t]);
    }
    A(Xe, W);
    for (std::size_t t = 0; t < ended.size(); ++t) {
      start_cycle(cols[ended[t]], B.col(ended[t]) - W.col(t), tol, m, max_iterations);
    }
  }
  std::vector<GmresResult> out;
  for (const LockstepColumn& c : cols) out.push_back(c.res);
  return out;
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
