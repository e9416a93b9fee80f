#include "solver.hpp"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <map>
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

struct Modes {
  Mat W, V;
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
  const Mat I = Mat::Identity(n, n);
  m.V = q_matrix(eps * I, eps * I, kx, ky) * m.gamma.cwiseInverse().asDiagonal();
  return m;
}

Modes slice_modes(const Slice& slice, const SlicedCell& cell, const std::vector<Complex>& eps_of, const Vec& kx,
                  double ky, const SolverSettings& s) {
  if (slice.boxes.empty()) return homogeneous_modes(eps_of[1], kx, ky);
  const int M = s.harmonics, n = 2 * M + 1;
  const Mat E = toeplitz(profile_coefficients(slice, cell.period_nm, M, [&](int i) { return eps_of[i]; }), M);
  const Mat Ei = E.partialPivLu().inverse();
  const Mat A = s.li_rule
                    ? Mat(toeplitz(profile_coefficients(slice, cell.period_nm, M, [&](int i) { return 1.0 / eps_of[i]; }), M)
                              .partialPivLu()
                              .inverse())
                    : E;
  const auto Kx = kx.asDiagonal();
  const Mat I = Mat::Identity(n, n);
  Mat P(2 * n, 2 * n);
  P.topLeftCorner(n, n) = ky * (Kx * Ei);
  P.topRightCorner(n, n) = I - Kx * Ei * Kx;
  P.bottomLeftCorner(n, n) = ky * ky * Ei - I;
  P.bottomRightCorner(n, n) = -ky * (Ei * Kx);
  const Mat Q = q_matrix(E, A, kx, ky);
  Eigen::ComplexEigenSolver<Mat> eig(P * Q);
  Modes m;
  m.W = eig.eigenvectors();
  m.gamma = eig.eigenvalues().unaryExpr([](Complex g2) { return forward_root(g2); });
  m.V = Q * m.W * m.gamma.cwiseInverse().asDiagonal();
  return m;
}

// S-matrix of a slice of thickness k0·L between two zero-thickness air gaps (W0 = I, V0).
SMatrix slice_smatrix(const Modes& m, const Mat& V0, double k0L) {
  const auto Wlu = m.W.partialPivLu();
  const auto Vlu = m.V.partialPivLu();
  const Mat WiW0 = Wlu.inverse(), ViV0 = Vlu.solve(V0);
  const Mat A = WiW0 + ViV0, B = WiW0 - ViV0;
  const Vec x = (Complex(0.0, 1.0) * k0L * m.gamma).array().exp();
  const auto Alu = A.partialPivLu();
  const Mat XB = x.asDiagonal() * B;
  const Mat BAi = B * Alu.inverse();
  const Mat D = A - XB * Alu.solve(XB);
  const auto Dlu = D.partialPivLu();
  SMatrix s;
  s.s11 = Dlu.solve(XB * Alu.solve(x.asDiagonal() * A) - B);
  s.s12 = Dlu.solve(x.asDiagonal() * (A - BAi * B));
  s.s21 = s.s12;
  s.s22 = s.s11;
  return s;
}

// Redheffer star product a ⊗ b (a above b).
SMatrix star(const SMatrix& a, const SMatrix& b) {
  const int n = static_cast<int>(a.s11.rows());
  const Mat I = Mat::Identity(n, n);
  const Mat D = (I - b.s11 * a.s22).transpose().partialPivLu().solve(a.s12.transpose()).transpose();
  const Mat F = (I - a.s22 * b.s11).transpose().partialPivLu().solve(b.s21.transpose()).transpose();
  return {a.s11 + D * b.s11 * a.s21, D * b.s12, F * a.s21, b.s22 + F * a.s22 * b.s12};
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
  const Mat A = m.W + V0.partialPivLu().solve(m.V), B = m.W - V0.partialPivLu().solve(m.V);
  const auto Alu = A.partialPivLu();
  const Mat Ai = Alu.inverse();
  if (top) return {-Ai * B, 2.0 * Ai, 0.5 * (A - B * Ai * B), B * Ai};
  return {B * Ai, 0.5 * (A - B * Ai * B), 2.0 * Ai, -Ai * B};
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

}  // namespace

EntryResult solve_entry(const SlicedCell& cell, double lambda_nm, double theta, double phi, const SolverSettings& s) {
  const int M = s.harmonics, n = 2 * M + 1;
  const double k0 = wavenumber_per_nm(lambda_nm);
  // Engine frame (slicing.hpp): ω_i,e = (cosθ sinφ, −sinθ, −cosθ cosφ), incident k = −ω_i,e.
  const double st = std::sin(theta), ct = std::cos(theta), sp = std::sin(phi), cp = std::cos(phi);
  const double kx0 = -ct * sp, ky = st, kz0 = ct * cp;
  Vec kx(n);
  double kx_max = 0.0;
  for (int m = -M; m <= M; ++m) {
    kx(m + M) = kx0 + m * lambda_nm / cell.period_nm;
    kx_max = std::max(kx_max, std::abs(kx(m + M).real()));
  }
  std::vector<Complex> eps_of;
  for (const Material& mat : cell.materials) {
    const Complex idx = mat.index(lambda_nm);
    eps_of.push_back(idx * idx);
  }
  // The zero-thickness gap: any homogeneous medium; ε_gap > k_x² + k_y² keeps all its γ real and
  // away from 0 (no Wood anomaly in the reference basis).
  const Mat V0 = homogeneous_modes(1.0 + kx_max * kx_max + ky * ky, kx, ky).V;
  const Modes top = homogeneous_modes(eps_of[0], kx, ky), bottom = homogeneous_modes(eps_of[1], kx, ky);
  std::vector<SMatrix> by_type(cell.n_types);
  std::vector<bool> done(cell.n_types, false);
  auto slice_s = [&](const Slice& slice) -> const SMatrix& {
    if (!done[slice.type]) {
      by_type[slice.type] = slice_smatrix(slice_modes(slice, cell, eps_of, kx, ky, s), V0, k0 * slice.thickness_nm);
      done[slice.type] = true;
    }
    return by_type[slice.type];
  };
  // Rows repeat: the slices between two host-only slices (one row of rods, or two interleaved rows)
  // form a chunk whose S-matrix is made once per entry and reused for every equal chunk.
  std::map<std::vector<int>, SMatrix> chunks;
  SMatrix total = half_space(top, V0, true);
  for (std::size_t i = 0; i < cell.slices.size();) {
    std::size_t j = i + 1;
    if (!cell.slices[i].boxes.empty())
      while (j < cell.slices.size() && !cell.slices[j].boxes.empty()) ++j;
    std::vector<int> key;
    for (std::size_t k = i; k < j; ++k) key.push_back(cell.slices[k].type);
    auto it = chunks.find(key);
    if (it == chunks.end()) {
      std::vector<int> shifted_key;
      for (int t : key) shifted_key.push_back(cell.half_shift_type.empty() ? -1 : cell.half_shift_type[t]);
      const auto sh = chunks.find(shifted_key);
      if (sh != chunks.end()) it = chunks.emplace(std::move(key), half_period_shift(sh->second, M)).first;
    }
    if (it == chunks.end()) {
      SMatrix chunk = slice_s(cell.slices[i]);
      for (std::size_t k = i + 1; k < j; ++k) chunk = star(chunk, slice_s(cell.slices[k]));
      it = chunks.emplace(std::move(key), std::move(chunk)).first;
    }
    total = star(total, it->second);
    i = j;
  }
  total = star(total, half_space(bottom, V0, false));

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
    const Vec cr = total.s11 * c, ct_ = total.s21 * c;
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
      if (std::abs(gt.imag()) < 1e-9) r.transmitted[q] += z_flux(et, {kx(m), ky, gt}) / f_inc;
      if (m == M) {
        J[0][q] = dot(er, s_hat);
        J[1][q] = dot(cross(k_ref, er), s_hat);
      }
    }
  }
  r.jones = {J[0][0], J[0][1], J[1][0], J[1][1]};
  return r;
}

EntryResult solve_entry_extrapolated(const SlicedCell& coarse, const SlicedCell& fine, double lambda_nm, double theta,
                                     double phi, const SolverSettings& s) {
  const EntryResult a = solve_entry(coarse, lambda_nm, theta, phi, s);
  EntryResult r = solve_entry(fine, lambda_nm, theta, phi, s);
  auto x = [](Complex f, Complex c) { return (4.0 * f - c) / 3.0; };
  r.jones = {x(r.jones.ss, a.jones.ss), x(r.jones.sp, a.jones.sp), x(r.jones.ps, a.jones.ps), x(r.jones.pp, a.jones.pp)};
  return r;
}

}  // namespace plumage::rcwa
