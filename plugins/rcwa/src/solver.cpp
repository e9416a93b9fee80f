#include "solver.hpp"

#include "lu.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

namespace plumage::rcwa {

namespace {

using Mat = Eigen::MatrixXcd;
using Vec = Eigen::VectorXcd;

struct SMatrix {
  Mat s11, s12, s21, s22;
};

// Fourier coefficients f_m, m = −2M..2M (index m + 2M), of host + Σ (value(mat) − value(under))·box.
template <class Value>
Vec profile_coefficients(const Slice& slice, double period_nm, int M, Value value) {
  Vec c = Vec::Zero(4 * M + 1);
  c(2 * M) = value(1);
  for (const Box& b : slice.boxes) {
    const Complex delta = value(b.material) - value(b.under);
    const double f = b.width_nm / period_nm;
    for (int m = -2 * M; m <= 2 * M; ++m) {
      const double arg = kPi * m * f;
      const double sinc = m == 0 ? 1.0 : std::sin(arg) / arg;
      c(m + 2 * M) += delta * f * sinc * std::exp(Complex(0.0, -2.0 * kPi * m * b.x_center_nm / period_nm));
    }
  }
  return c;
}

Mat toeplitz(const Vec& c, int M) {
  const int n = 2 * M + 1;
  Mat t(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) t(i, j) = c(i - j + 2 * M);
  return t;
}

// Im γ ≥ 0 (forward waves decay); on the real axis Re γ ≥ 0. A γ of exactly 0 (a Wood anomaly) is
// nudged so that V = Q W Γ⁻¹ stays finite.
Complex forward_root(Complex g2) {
  Complex g = std::sqrt(g2);
  if (g.imag() < 0.0 || (g.imag() == 0.0 && g.real() < 0.0)) g = -g;
  if (std::abs(g) < 1e-12) g = Complex(1e-12, 1e-12);
  return g;
}

// The host is the gap medium of the S-matrices when all its |γ| are at least this (solve_stack).
constexpr double kHostGapMinGamma = 0.05;

// Relative gap |u − t| / max|eigenvalue| below which slice_modes solves the coupled problem.
constexpr double kDegenerateTolerance = 1e-7;

struct Modes {
  Mat W, W_inv, V;  // W_inv = W⁻¹ (homogeneous and coupled modes; slice_modes builds SlabModes directly)
  Vec gamma;
};

// Q of a slice (see solver.hpp) from [[ε]], A and the orders.
Mat q_matrix(const Mat& eps, const Mat& a, const Vec& kx, double ky) {
  const int n = static_cast<int>(kx.size());
  // K_x is diagonal: applied as a scaling (O(n²)), never as a dense product.
  Mat Q = Mat::Zero(2 * n, 2 * n);
  Q.topLeftCorner(n, n).diagonal() = -ky * kx;
  Q.topRightCorner(n, n) = -eps;
  Q.topRightCorner(n, n).diagonal() += kx.cwiseProduct(kx);
  Q.bottomLeftCorner(n, n) = a;
  Q.bottomLeftCorner(n, n).diagonal().array() -= ky * ky;
  Q.bottomRightCorner(n, n).diagonal() = ky * kx;
  return Q;
}

// Homogeneous medium: W = I, γ_m = √(ε − k_x,m² − k_y²) for both E_x and E_y.
Modes homogeneous_modes(Complex eps, const Vec& kx, double ky) {
  const int n = static_cast<int>(kx.size());
  Modes m;
  m.gamma.resize(2 * n);
  for (int i = 0; i < n; ++i) m.gamma(i) = m.gamma(i + n) = forward_root(eps - kx(i) * kx(i) - ky * ky);
  m.W = Mat::Identity(2 * n, 2 * n);
  m.W_inv = m.W;
  const Mat I = Mat::Identity(n, n);
  m.V = q_matrix(eps * I, eps * I, kx, ky) * m.gamma.cwiseInverse().asDiagonal();
  return m;
}

// The 2n × 2n mode problem of a slice from P and Q directly (the general path; also the fallback of
// slice_modes when a TE-like and a TM-like eigenvalue coincide).
Modes coupled_modes(const Mat& P, const Mat& Q) {
  Eigen::ComplexEigenSolver<Mat> eig(P * Q);
  Modes m;
  m.W = eig.eigenvectors();
  m.W_inv = Lu(m.W).inverse();
  m.gamma = eig.eigenvalues().unaryExpr([](Complex g2) { return forward_root(g2); });
  m.V = Q * m.W * m.gamma.cwiseInverse().asDiagonal();
  return m;
}

// What slice_smatrix needs of a slice's modes against the gap (W0 = I, V0): W⁻¹, V⁻¹V0 and γ.
struct SlabModes {
  Mat W_inv, ViV0;
  Vec gamma;
};

SlabModes slab_modes(const Modes& m, const Mat& V0) { return {m.W_inv, Lu(m.V).solve(V0), m.gamma}; }

// P V0 for a gap V0 whose four n × n blocks are diagonal (a homogeneous medium): column scalings of
// P's blocks (P of solver.hpp from [[ε]]⁻¹ and the orders), O(n²) instead of a product.
Mat p_times_gap(const Mat& Ei, const Vec& kx, double ky, const Mat& V0) {
  const int n = static_cast<int>(kx.size());
  const auto Kx = kx.asDiagonal();
  Mat P11 = ky * (Kx * Ei), P12 = -(Kx * Ei * Kx), P21 = (ky * ky) * Ei, P22 = -ky * (Ei * Kx);
  P12.diagonal().array() += 1.0;
  P21.diagonal().array() -= 1.0;
  const Vec v11 = V0.topLeftCorner(n, n).diagonal(), v12 = V0.topRightCorner(n, n).diagonal();
  const Vec v21 = V0.bottomLeftCorner(n, n).diagonal(), v22 = V0.bottomRightCorner(n, n).diagonal();
  Mat PV0(2 * n, 2 * n);
  PV0.topLeftCorner(n, n) = P11 * v11.asDiagonal() + P12 * v21.asDiagonal();
  PV0.topRightCorner(n, n) = P11 * v12.asDiagonal() + P12 * v22.asDiagonal();
  PV0.bottomLeftCorner(n, n) = P21 * v11.asDiagonal() + P22 * v21.asDiagonal();
  PV0.bottomRightCorner(n, n) = P21 * v12.asDiagonal() + P22 * v22.asDiagonal();
  return PV0;
}

// A y-invariant slice: PQ = [[T − k_y², 0], [C, U − k_y²]] with T = (I − K_x ε⁻¹ K_x) A (TM-like,
// E_x), U = [[ε]] − K_x² (TE-like, E_y), C = k_y (K_x − ε⁻¹ K_x A) (expand P Q of solver.hpp; the
// k_y terms of the diagonal blocks cancel). So the conical modes come from two n × n eigenproblems
// (the planar TM and TE ones, γ² shifted by −k_y²) instead of one 2n × 2n: U's modes are (0; w_u),
// T's are (w_t; y) with (U − t) y = −C w_t, solved in U's eigenbasis (4x fewer flops than the
// coupled solve; the same γ and fields up to the modes' normalisation, NOTES.md §5).
// [[ε]], [[ε]]⁻¹ and A depend on λ only: they come from the WavelengthSetup.
SlabModes slice_modes(const WavelengthSetup::TypeMatrices& tm, const Vec& kx, double ky, const Mat& V0,
                      const SolverSettings& s) {
  const int n = 2 * s.harmonics + 1;
  const Mat &E = tm.eps, &Ei = tm.eps_inv, &A = tm.a;
  const auto Kx = kx.asDiagonal();
  auto coupled = [&] {
    const Mat I = Mat::Identity(n, n);
    Mat P(2 * n, 2 * n);
    P.topLeftCorner(n, n) = ky * (Kx * Ei);
    P.topRightCorner(n, n) = I - Kx * Ei * Kx;
    P.bottomLeftCorner(n, n) = ky * ky * Ei - I;
    P.bottomRightCorner(n, n) = -ky * (Ei * Kx);
    return slab_modes(coupled_modes(P, q_matrix(E, A, kx, ky)), V0);
  };
  if (s.coupled_eigenproblem) return coupled();
  const Mat KxA = Kx * A;
  const Mat T = A - Kx * (Ei * KxA);
  Mat U = E;
  U.diagonal() -= kx.cwiseProduct(kx);
  const Eigen::ComplexEigenSolver<Mat> eig_t(T), eig_u(U);
  const Vec& t = eig_t.eigenvalues();
  const Vec& u = eig_u.eigenvalues();
  const Mat &Wt = eig_t.eigenvectors(), &Wu = eig_u.eigenvectors();
  const Lu Wu_lu(Wu);
  SlabModes m;
  m.W_inv = Mat::Zero(2 * n, 2 * n);
  m.W_inv.topLeftCorner(n, n) = Lu(Wt).inverse();
  m.W_inv.bottomRightCorner(n, n) = Wu_lu.inverse();
  if (ky != 0.0) {
    // Near-coincident t and u (a nearly homogeneous slice) make (U − t)⁻¹ ill-conditioned: solve
    // the coupled problem there instead.
    double scale = 1.0;
    for (int j = 0; j < n; ++j) scale = std::max({scale, std::abs(t(j)), std::abs(u(j))});
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        if (std::abs(u(j) - t(k)) < kDegenerateTolerance * scale) return coupled();
    // W = [[Wt, 0], [Wc, Wu]] with Wc = −Wu G is block lower triangular: W⁻¹'s lower-left block is
    // −Wu⁻¹ Wc Wt⁻¹ = G Wt⁻¹ (no 2n × 2n LU).
    Mat G = Wu_lu.solve(ky * (Kx * Wt - Ei * (KxA * Wt)));
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) G(j, k) /= u(j) - t(k);
    m.W_inv.bottomLeftCorner(n, n) = G * m.W_inv.topLeftCorner(n, n);
  }
  m.gamma.resize(2 * n);
  for (int j = 0; j < n; ++j) {
    m.gamma(j) = forward_root(t(j) - ky * ky);
    m.gamma(n + j) = forward_root(u(j) - ky * ky);
  }
  // V = Q W Γ⁻¹, and P Q W = W Γ² gives V = P⁻¹ W Γ, so V⁻¹V0 = Γ⁻¹ W⁻¹ (P V0): no V and no 2n × 2n
  // LU; W⁻¹ block lower triangular (three n × 2n products).
  const Mat PV0 = p_times_gap(Ei, kx, ky, V0);
  m.ViV0.resize(2 * n, 2 * n);
  m.ViV0.topRows(n) = m.W_inv.topLeftCorner(n, n) * PV0.topRows(n);
  m.ViV0.bottomRows(n) = m.W_inv.bottomRightCorner(n, n) * PV0.bottomRows(n);
  if (ky != 0.0) m.ViV0.bottomRows(n).noalias() += m.W_inv.bottomLeftCorner(n, n) * PV0.topRows(n);
  m.ViV0 = m.gamma.cwiseInverse().asDiagonal() * m.ViV0;
  return m;
}

// S-matrix of a slice of thickness k0·L between two zero-thickness gaps (W0 = I, V0). Rumpf's
// symmetric form has s11 = s22 = D⁻¹(X B A⁻¹ X A − B), s12 = s21 = D⁻¹ X (A − B A⁻¹ B) with
// A = W⁻¹ + V⁻¹V0, B = W⁻¹ − V⁻¹V0, X = diag(e^{iγk0L}), D = A − X B A⁻¹ X B. D factors as
// (A + XB) A⁻¹ (A − XB) = (A − XB) A⁻¹ (A + XB), so the even and odd parts of the slab are
// s11 + s12 = (A − XB)⁻¹ (XA − B) and s11 − s12 = −(A + XB)⁻¹ (XA + B): two LUs, no A⁻¹.
SMatrix slice_smatrix(const SlabModes& m, double k0L) {
  const Mat& ViV0 = m.ViV0;
  const Vec x = (Complex(0.0, 1.0) * k0L * m.gamma).array().exp();
  const Vec one_minus_x = Vec::Ones(x.size()) - x, one_plus_x = Vec::Ones(x.size()) + x;
  // A − XB = (I − X) W⁻¹ + (I + X) V⁻¹V0 =: a + b, XA − B = b − a; A + XB = c + d, XA + B = c − d.
  const Mat a = one_minus_x.asDiagonal() * m.W_inv, b = one_plus_x.asDiagonal() * ViV0;
  const Mat c = one_plus_x.asDiagonal() * m.W_inv, d = one_minus_x.asDiagonal() * ViV0;
  const Mat even = Lu(a + b).solve(b - a), odd = Lu(c + d).solve(d - c);
  SMatrix s;
  s.s11 = 0.5 * (even + odd);
  s.s12 = 0.5 * (even - odd);
  s.s21 = s.s12;
  s.s22 = s.s11;
  return s;
}

// Redheffer star product a ⊗ b (a above b).
SMatrix star(const SMatrix& a, const SMatrix& b) {
  const int n = static_cast<int>(a.s11.rows());
  const Mat I = Mat::Identity(n, n);
  const Mat D = Lu(I - b.s11 * a.s22).solve_right(a.s12);
  const Mat F = Lu(I - a.s22 * b.s11).solve_right(b.s21);
  return {a.s11 + D * b.s11 * a.s21, D * b.s12, F * a.s21, b.s22 + F * a.s22 * b.s12};
}

// a ⊗ swap(a), swap(a) = (a22, a21, a12, a11): a stack followed by the same slices in reverse
// order. Every slice's S-matrix is direction-symmetric (s11 = s22, s12 = s21), and
// swap(a ⊗ b) = swap(b) ⊗ swap(a), so swap(a) is the reversed stack. Both inverses of star()
// become the same (I − a22²)⁻¹ and the result is direction-symmetric: one LU instead of two.
SMatrix mirror_star(const SMatrix& a) {
  Mat I_minus = -(a.s22 * a.s22);
  I_minus.diagonal().array() += 1.0;
  const Mat D = Lu(std::move(I_minus)).solve_right(a.s12);
  SMatrix s;
  s.s12 = D * a.s21;
  s.s11 = a.s11 + (D * a.s22) * a.s21;
  s.s21 = s.s12;
  s.s22 = s.s11;
  return s;
}

// The S-matrix of the same layers shifted by half a period: D S D with D = diag((−1)^m) on the
// E_x and E_y blocks (ε_m → (−1)^m ε_m makes P, Q → D P D, D Q D, so W → D W, V → D V).
SMatrix half_period_shift(const SMatrix& s, int M) {
  const int n = 2 * M + 1;
  Vec d(2 * n);
  for (int a = 0; a < 2 * n; ++a) d(a) = ((a % n) - M) % 2 == 0 ? 1.0 : -1.0;
  auto flip = [&](const Mat& m) { return Mat(d.asDiagonal() * m * d.asDiagonal()); };
  return {flip(s.s11), flip(s.s12), flip(s.s21), flip(s.s22)};
}

// Half-space above (incident side, `top`) or below: its modes against the air gap.
SMatrix half_space(const Modes& m, const Mat& V0, bool top) {
  const Mat V0iV = Lu(V0).solve(m.V);
  const Mat A = m.W + V0iV, B = m.W - V0iV;
  const Mat Ai = Lu(A).inverse();
  if (top) return {-Ai * B, 2.0 * Ai, 0.5 * (A - B * Ai * B), B * Ai};
  return {B * Ai, 0.5 * (A - B * Ai * B), 2.0 * Ai, -Ai * B};
}


// Reflection matrix of the layers `s` over a stack of reflection R, both seen from the gap above:
// R' = s11 + s12 R (I − s22 R)⁻¹ s21, the s11 block of the star product s ⊗ (R, ·, ·, ·).
Mat reflect_over(const SMatrix& s, const Mat& R) {
  Mat I_minus = -(s.s22 * R);
  I_minus.diagonal().array() += 1.0;
  return s.s11 + (s.s12 * R) * Lu(std::move(I_minus)).solve(s.s21);
}

// The stack as units, top to bottom: runs of slices between two host-only slices (a row of rods,
// or interleaved rows) that occur more than once, counting a run shifted by half a period as the
// same, are "repeated" chunks whose S-matrix is built once (by star products) and reused; every
// other slice is its own unit (its S-matrix is reused by slice type).
struct StackUnit {
  std::size_t begin = 0, end = 0;  // slices [begin, end)
  bool repeated = false;
  std::size_t first_equal = 0;     // the first unit of identical geometry (holds the S-matrix)
  long half_shift_of = -1;         // a unit whose geometry, shifted by half a period, is this one
};

std::vector<StackUnit> stack_units(const SlicedCell& cell) {
  struct Run {
    std::size_t begin, end;
    std::vector<int> key, shifted;
  };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < cell.slices.size();) {
    std::size_t j = i + 1;
    if (!cell.slices[i].boxes.empty())
      while (j < cell.slices.size() && !cell.slices[j].boxes.empty()) ++j;
    Run r{i, j, {}, {}};
    for (std::size_t k = i; k < j; ++k) {
      r.key.push_back(cell.slices[k].type);
      r.shifted.push_back(cell.half_shift_type.empty() ? -1 : cell.half_shift_type[cell.slices[k].type]);
    }
    runs.push_back(std::move(r));
    i = j;
  }
  std::vector<StackUnit> units;
  std::vector<long> unit_of_run(runs.size(), -1);
  for (std::size_t a = 0; a < runs.size(); ++a) {
    const Run& r = runs[a];
    std::size_t copies = 0;
    for (const Run& o : runs) copies += (o.key == r.key || o.key == r.shifted) ? 1 : 0;
    if (r.end - r.begin < 2 || copies < 2) {
      for (std::size_t k = r.begin; k < r.end; ++k) units.push_back({k, k + 1, false, units.size(), -1});
      continue;
    }
    StackUnit u{r.begin, r.end, true, units.size(), -1};
    for (std::size_t b = 0; b < a; ++b) {
      if (unit_of_run[b] < 0) continue;
      if (runs[b].key == r.key) u.first_equal = units[unit_of_run[b]].first_equal;
      else if (runs[b].key == r.shifted && u.half_shift_of < 0) u.half_shift_of = static_cast<long>(units[unit_of_run[b]].first_equal);
    }
    unit_of_run[a] = static_cast<long>(units.size());
    units.push_back(u);
  }
  // Both partners of a half-period pair may take the other's S-matrix (the reflection recursion
  // runs bottom-up, so the lower one is usually built first).
  for (const StackUnit& u : units)
    if (u.half_shift_of >= 0)
      for (StackUnit& v : units)
        if (v.repeated && v.first_equal == static_cast<std::size_t>(u.half_shift_of) && v.half_shift_of < 0)
          v.half_shift_of = static_cast<long>(u.first_equal);
  return units;
}

}  // namespace

namespace {

using Vec3 = std::array<Complex, 3>;

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Complex dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// z-flux Re(E × H*)_z of a plane wave with normalised k (η0H = k × E).
double z_flux(const Vec3& e, const Vec3& k) {
  const Vec3 h = cross(k, e);
  return (e[0] * std::conj(h[1]) - e[1] * std::conj(h[0])).real();
}

// The plane wave of order i with transverse (E_x, E_y) and k_z = kz (sign = direction).
Vec3 wave_field(Complex ex, Complex ey, Complex kx, double ky, Complex kz) {
  return {ex, ey, -(kx * ex + ky * ey) / kz};
}

// The S-matrix of a repeated chunk (slices [begin, end)) by star products. A chunk whose slice types
// read the same backwards (a row of rods symmetric about its centre) is H ⊗ swap(H) for its upper
// half H (mirror_star), H ⊗ s_mid ⊗ swap(H) for an odd count: half the star products.
template <class SliceS>
SMatrix chunk_smatrix(const SlicedCell& cell, std::size_t begin, std::size_t end, SliceS slice_s) {
  const std::size_t len = end - begin;
  bool palindrome = len >= 2;
  for (std::size_t k = 0; k < len / 2 && palindrome; ++k)
    palindrome = cell.slices[begin + k].type == cell.slices[end - 1 - k].type;
  const std::size_t upper_end = palindrome ? begin + len / 2 : end;
  SMatrix chunk = slice_s(cell.slices[begin]);
  for (std::size_t k = begin + 1; k < upper_end; ++k) chunk = star(chunk, slice_s(cell.slices[k]));
  if (!palindrome) return chunk;
  if (len % 2 == 0) return mirror_star(chunk);
  const SMatrix with_mid = star(chunk, slice_s(cell.slices[upper_end]));
  return star(with_mid, SMatrix{chunk.s22, chunk.s21, chunk.s12, chunk.s11});
}

}  // namespace

WavelengthSetup prepare_wavelength(const SlicedCell& cell, double lambda_nm, const SolverSettings& s) {
  WavelengthSetup w;
  w.cell = &cell;
  w.lambda_nm = lambda_nm;
  w.settings = s;
  for (const Material& mat : cell.materials) {
    const Complex idx = mat.index(lambda_nm);
    w.eps_of.push_back(idx * idx);
  }
  const int M = s.harmonics;
  w.types.resize(static_cast<std::size_t>(cell.n_types));
  std::vector<bool> seen(static_cast<std::size_t>(cell.n_types), false);
  for (const Slice& slice : cell.slices) {
    if (seen[slice.type] || slice.boxes.empty()) continue;
    seen[slice.type] = true;
    WavelengthSetup::TypeMatrices& t = w.types[slice.type];
    t.eps = toeplitz(profile_coefficients(slice, cell.period_nm, M, [&](int i) { return w.eps_of[i]; }), M);
    t.eps_inv = Lu(t.eps).inverse();
    t.a = s.li_rule
              ? Lu(toeplitz(profile_coefficients(slice, cell.period_nm, M, [&](int i) { return 1.0 / w.eps_of[i]; }), M))
                    .inverse()
              : t.eps;
  }
  return w;
}

namespace {

struct StackSolution {
  Mat r, t;            // reflection (and, with settings.transmission, transmission) between the half-spaces
  Modes top, bottom;   // the half-spaces' modes
};

StackSolution solve_stack(const WavelengthSetup& w, const Vec& kx, double ky, double kx_max) {
  const SlicedCell& cell = *w.cell;
  const SolverSettings& s = w.settings;
  const int M = s.harmonics, n = 2 * M + 1;
  const double k0 = wavenumber_per_nm(w.lambda_nm);
  StackSolution out{{}, {}, homogeneous_modes(w.eps_of[0], kx, ky), homogeneous_modes(w.eps_of[1], kx, ky)};
  // The zero-thickness gap: any homogeneous medium. The host itself when none of its orders is near
  // grazing: host-only slices are then pure phase delays (s11 = s22 = 0, s12 = s21 = X) and the
  // substrate reflects nothing, so such a unit costs R' = X R X instead of an S-matrix and an LU.
  // Next to a Rayleigh anomaly of the host (some |γ| < kHostGapMinGamma, V0 ∝ Γ⁻¹ large) the gap is
  // ε_gap = 1 + max k_x² + k_y² instead, whose γ are all real and away from 0.
  const bool host_gap = out.bottom.gamma.cwiseAbs().minCoeff() >= kHostGapMinGamma;
  const Mat V0 = host_gap ? out.bottom.V : homogeneous_modes(1.0 + kx_max * kx_max + ky * ky, kx, ky).V;
  auto host_phase = [&](double thickness_nm) {
    return Vec((Complex(0.0, 1.0) * k0 * thickness_nm * out.bottom.gamma).array().exp());
  };
  // The per-type and per-chunk S-matrices (~30 KB each) live on between the entries of a thread: freed
  // at every entry, they made glibc trim the heap top and fault the pages in again (~80 page
  // faults per entry, ~8 % of the CPU as system time; NOTES.md §5).
  thread_local std::vector<SMatrix> by_type, chunk_s;
  by_type.resize(static_cast<std::size_t>(cell.n_types));
  std::vector<bool> done(cell.n_types, false);
  auto slice_s = [&](const Slice& slice) -> const SMatrix& {
    if (!done[slice.type]) {
      // A slice shifted by half a period of one already solved: D S D (half_period_shift).
      const int twin = cell.half_shift_type.empty() ? -1 : cell.half_shift_type[slice.type];
      const double k0L = k0 * slice.thickness_nm;
      if (twin >= 0 && done[twin]) {
        by_type[slice.type] = half_period_shift(by_type[twin], M);
      } else if (slice.boxes.empty() && host_gap) {
        const Mat X = host_phase(slice.thickness_nm).asDiagonal();
        by_type[slice.type] = {Mat::Zero(2 * n, 2 * n), X, X, Mat::Zero(2 * n, 2 * n)};
      } else {
        by_type[slice.type] = slice_smatrix(slice.boxes.empty() ? slab_modes(homogeneous_modes(w.eps_of[1], kx, ky), V0)
                                                                : slice_modes(w.types[slice.type], kx, ky, V0, s),
                                            k0L);
      }
      done[slice.type] = true;
    }
    return by_type[slice.type];
  };
  const std::vector<StackUnit> units = stack_units(cell);
  chunk_s.resize(units.size());  // the S-matrix of each repeated chunk, built once
  std::vector<bool> chunk_done(units.size(), false);
  auto unit_s = [&](std::size_t u) -> const SMatrix& {
    const StackUnit& unit = units[u];
    if (!unit.repeated) return slice_s(cell.slices[unit.begin]);
    const std::size_t first = unit.first_equal;
    if (!chunk_done[first]) {
      chunk_s[first] = unit.half_shift_of >= 0 && chunk_done[unit.half_shift_of]
                           ? half_period_shift(chunk_s[unit.half_shift_of], M)
                           : chunk_smatrix(cell, unit.begin, unit.end, slice_s);
      chunk_done[first] = true;
    }
    return chunk_s[first];
  };
  const Mat I = Mat::Identity(2 * n, 2 * n), O = Mat::Zero(2 * n, 2 * n);
  const SMatrix top_s = half_space(out.top, V0, true);
  const SMatrix bottom_s = host_gap ? SMatrix{O, I, I, O} : half_space(out.bottom, V0, false);
  if (s.transmission) {
    SMatrix total = top_s;
    for (std::size_t u = 0; u < units.size(); ++u) total = star(total, unit_s(u));
    total = star(total, bottom_s);
    out.r = std::move(total.s11);
    out.t = std::move(total.s21);
  } else {
    // Only the reflection is needed: recurse R upward from the substrate (one LU and three products
    // per unit instead of a star product's two LUs and eight products).
    Mat R = bottom_s.s11;
    for (std::size_t u = units.size(); u-- > 0;) {
      const StackUnit& unit = units[u];
      if (host_gap && !unit.repeated && cell.slices[unit.begin].boxes.empty()) {
        const Vec x = host_phase(cell.slices[unit.begin].thickness_nm);
        R = x.asDiagonal() * R * x.asDiagonal();
      } else {
        R = reflect_over(unit_s(u), R);
      }
    }
    out.r = reflect_over(top_s, R);
  }
  return out;
}

}  // namespace

EntryResult solve_entry(const WavelengthSetup& w, double theta, double phi) {
  const SlicedCell& cell = *w.cell;
  const SolverSettings& s = w.settings;
  const int M = s.harmonics, n = 2 * M + 1;
  const double lambda_nm = w.lambda_nm;
  // Engine frame (slicing.hpp): ω_i,e = (cosθ sinφ, −sinθ, −cosθ cosφ), incident k = −ω_i,e.
  const double st = std::sin(theta), ct = std::cos(theta), sp = std::sin(phi), cp = std::cos(phi);
  const double kx0 = -ct * sp, ky = st, kz0 = ct * cp;
  Vec kx(n);
  double kx_max = 0.0;
  for (int m = -M; m <= M; ++m) {
    kx(m + M) = kx0 + m * lambda_nm / cell.period_nm;
    kx_max = std::max(kx_max, std::abs(kx(m + M).real()));
  }
  const StackSolution stack = solve_stack(w, kx, ky, kx_max);
  const Modes &top = stack.top, &bottom = stack.bottom;

  // ŝ = ω_i,e × n̂_e, n̂_e = (0, 0, −1); R ŷ = −ŷ at exactly normal incidence (crystal_mapping.cpp).
  double sx = st, sy = ct * sp;
  const double len = std::hypot(sx, sy);
  if (len < 1e-4) sx = 0.0, sy = -1.0;
  else sx /= len, sy /= len;
  const Vec3 s_hat = {sx, sy, 0.0};
  const Vec3 k_inc = {kx0, ky, kz0};
  const Vec3 k_ref = {kx0, ky, -kz0};
  // Incident s: E = ŝ; incident p: η0H = ŝ, E = ŝ × k̂ — so B = I and J = C (crystal_mapping.cpp).
  const Vec3 e_inc[2] = {s_hat, cross(s_hat, k_inc)};
  EntryResult r;
  Complex J[2][2];
  for (int q = 0; q < 2; ++q) {
    Vec c = Vec::Zero(2 * n);
    c(M) = e_inc[q][0];
    c(n + M) = e_inc[q][1];
    const double f_inc = z_flux(e_inc[q], k_inc);
    const Vec cr = stack.r * c;
    const Vec ct_ = s.transmission ? Vec(stack.t * c) : Vec::Zero(2 * n);
    for (int m = 0; m < n; ++m) {
      const Complex gr = top.gamma(m), gt = bottom.gamma(m);
      const Vec3 er = wave_field(cr(m), cr(n + m), kx(m), ky, -gr);
      const double fr = gr.imag() < 1e-9 ? -z_flux(er, {kx(m), ky, -gr}) / f_inc : 0.0;
      r.reflected[q] += fr;
      if (m != M && gr.imag() < 1e-9 && gr.real() > 1e-9) {
        r.other_orders[q] += fr;
        r.has_other_orders = true;
      }
      const Vec3 et = wave_field(ct_(m), ct_(n + m), kx(m), ky, gt);
      if (s.transmission && std::abs(gt.imag()) < 1e-9) r.transmitted[q] += z_flux(et, {kx(m), ky, gt}) / f_inc;
      if (m == M) {
        J[0][q] = dot(er, s_hat);
        J[1][q] = dot(cross(k_ref, er), s_hat);
      }
    }
  }
  r.jones = {J[0][0], J[0][1], J[1][0], J[1][1]};
  return r;
}

EntryResult solve_entry(const SlicedCell& cell, double lambda_nm, double theta, double phi, const SolverSettings& s) {
  return solve_entry(prepare_wavelength(cell, lambda_nm, s), theta, phi);
}

EntryResult solve_entry_extrapolated(const WavelengthSetup& coarse, const WavelengthSetup& fine, double theta,
                                     double phi) {
  const EntryResult a = solve_entry(coarse, theta, phi);
  EntryResult r = solve_entry(fine, theta, phi);
  auto x = [](Complex f, Complex c) { return (4.0 * f - c) / 3.0; };
  r.jones = {x(r.jones.ss, a.jones.ss), x(r.jones.sp, a.jones.sp), x(r.jones.ps, a.jones.ps), x(r.jones.pp, a.jones.pp)};
  return r;
}

EntryResult solve_entry_extrapolated(const SlicedCell& coarse, const SlicedCell& fine, double lambda_nm, double theta,
                                     double phi, const SolverSettings& s) {
  return solve_entry_extrapolated(prepare_wavelength(coarse, lambda_nm, s), prepare_wavelength(fine, lambda_nm, s),
                                  theta, phi);
}

}  // namespace plumage::rcwa
