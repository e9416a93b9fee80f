#include "tent_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "plumage/simd_math.hpp"
#include "tent_integrals.hpp"

namespace plumage::detail {

TentKernel::TentKernel(std::size_t max_vertices) {
  const std::size_t v = max_vertices + 8;
  for (auto* b : {&psi_, &er_, &ei_, &ar_, &ai_, &br_, &bi_, &u_, &h_}) b->assign(v, 0.0);
}

void OutgoingPhases::build(std::span<const Vec2> vertices, Vec2 origin, double gamma0,
                           std::span<const double> phi_o_rad) {
  verts = vertices.size();
  directions = phi_o_rad.size();
  stride = (directions + 7) / 8 * 8;
  re.assign(stride * verts, 0.0);
  im.assign(stride * verts, 0.0);
  dg.assign(stride * verts, 0.0);
  std::vector<double> sx(stride, 0.0), sz(stride, 0.0), g(stride, 0.0), g_next(stride, 0.0);
  for (std::size_t j = 0; j < directions; ++j) sx[j] = gamma0 * std::sin(phi_o_rad[j]), sz[j] = gamma0 * std::cos(phi_o_rad[j]);
  for (std::size_t k = 0; k < verts; ++k) {
    const double dx = vertices[k].x - origin.x, dz = vertices[k].z - origin.z;
    for (std::size_t j = 0; j < directions; ++j) g_next[j] = -(sx[j] * dx + sz[j] * dz);
    double* r = re.data() + k * stride;
    double* i = im.data() + k * stride;
    for (std::size_t j = 0; j < stride; j += 4) {
      simd::v4d sn, cs;
      simd::sincos(simd::v4d{g_next[j], g_next[j + 1], g_next[j + 2], g_next[j + 3]}, sn, cs);
      for (int l = 0; l < 4; ++l) r[j + l] = cs[l], i[j + l] = sn[l];
    }
    if (k > 0) {
      double* d = dg.data() + (k - 1) * stride;
      for (std::size_t j = 0; j < directions; ++j) d[j] = g_next[j] - g[j];
    }
    std::swap(g, g_next);
  }
  re_f.assign(re.begin(), re.end());
  im_f.assign(im.begin(), im.end());
  dg_f.assign(dg.begin(), dg.end());
}

namespace {

// The vector loops of FactoredTentKernel::build, as functions with restrict parameters (GCC 12
// does not vectorise them with restrict-qualified locals inside the segment loop).
// e = e^{iχ}·e^{ig}
template <class T>
void unit_phase(T c, T s, const T* __restrict gr, const T* __restrict gi, T* __restrict er, T* __restrict ei,
                std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) {
    er[j] = c * gr[j] - s * gi[j];
    ei[j] = c * gi[j] + s * gr[j];
  }
}

// out = add + e·conj(w) (complex, split)
template <class T>
void multiply_conj_add(const T* __restrict add_re, const T* __restrict add_im, const T* __restrict er,
                       const T* __restrict ei, const T* __restrict wr, const T* __restrict wi, T* __restrict out_re,
                       T* __restrict out_im, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) {
    out_re[j] = add_re[j] + (er[j] * wr[j] + ei[j] * wi[j]);
    out_im[j] = add_im[j] + (ei[j] * wr[j] - er[j] * wi[j]);
  }
}

// out = e·w (complex, split)
template <class T>
void multiply(const T* __restrict er, const T* __restrict ei, const T* __restrict wr, const T* __restrict wi,
              T* __restrict out_re, T* __restrict out_im, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) {
    out_re[j] = er[j] * wr[j] - ei[j] * wi[j];
    out_im[j] = er[j] * wi[j] + ei[j] * wr[j];
  }
}

// A node's column of the split kernel: Re then Im.
void store_column(const double* re, const double* im, std::size_t n, double* col) {
  std::memcpy(col, re, n * sizeof(double));
  std::memcpy(col + n, im, n * sizeof(double));
}

using v8f = float __attribute__((vector_size(32)));

// tent_weight_b_series in 8 float lanes: the same series, cut after u^11 (the next term,
// 13·u^12/14!, is below 1.5e-10 for |u| ≤ 1, far under float rounding).
inline void tent_weight_b_series_f(v8f u, v8f& b_re, v8f& b_im) {
  const v8f u2 = u * u;
  v8f pr = v8f{} + static_cast<float>(k_br[5]), pi = v8f{} + static_cast<float>(k_bi[5]);
  for (int m = 4; m >= 0; --m) {
    pr = pr * u2 + static_cast<float>(k_br[m]);
    pi = pi * u2 + static_cast<float>(k_bi[m]);
  }
  b_re = pr;
  b_im = u * pi;
}

}  // namespace

// e^{iχ_k} at every vertex (in_re_, in_im_).
void FactoredTentKernel::incident_phases(std::span<const double> chi, std::size_t verts) {
  in_re_.resize(verts + 4), in_im_.resize(verts + 4), padded_.resize(verts + 4);
  for (std::size_t k = 0; k < verts + 4; ++k) padded_[k] = chi[std::min(k, verts - 1)];
  for (std::size_t k = 0; k < verts; k += 4) {
    simd::v4d sn, cs;
    simd::sincos(simd::v4d{padded_[k], padded_[k + 1], padded_[k + 2], padded_[k + 3]}, sn, cs);
    std::memcpy(in_re_.data() + k, &cs, sizeof cs);
    std::memcpy(in_im_.data() + k, &sn, sizeof sn);
  }
}

// Segment k (vertices k, k + 1, length h, phase increment u) adds h·e^{iψ_k}·A(u) to node k and
// h·e^{iψ_k}·B(u) to node k + 1 (tent_integrals.hpp). With A(u) = e^{iu}·conj(B(u)) and
// e^{iψ_k}·e^{iu} = e^{iψ_{k+1}} (ψ is linear along the segment), node k's part is
// e^{iψ_{k+1}}·conj(h·B(u)): one series per entry instead of two (issue 26; the identity is
// exact, the two phases agree to rounding, ~|ψ|·1e-16).
template <class Matrix>
void FactoredTentKernel::build_into(const OutgoingPhases& outgoing, std::span<const double> segment_length,
                                    std::span<const double> chi, Matrix& split) {
  const std::size_t verts = outgoing.verts, segs = verts - 1, nodes = verts - 2;
  const std::size_t n = outgoing.stride, p_dir = outgoing.directions;
  for (auto* b : {&ar_, &ai_, &br_, &bi_, &er_, &ei_, &carry_re_, &carry_im_, &node_re_, &node_im_}) b->resize(n);
  split.resize(static_cast<Eigen::Index>(2 * p_dir), static_cast<Eigen::Index>(nodes));
  incident_phases(chi, verts);
  double* br = br_.data();
  double* bi = bi_.data();
  double* cur_re = er_.data();  // e^{iψ_k}
  double* cur_im = ei_.data();
  double* nxt_re = ar_.data();  // e^{iψ_{k+1}}
  double* nxt_im = ai_.data();
  double* cr = carry_re_.data();
  double* ci = carry_im_.data();
  double* nr = node_re_.data();
  double* ni = node_im_.data();
  unit_phase(in_re_[0], in_im_[0], outgoing.re.data(), outgoing.im.data(), cur_re, cur_im, n);
  // Padding lanes (j ≥ P) compute harmless values.
  for (std::size_t k = 0; k < segs; ++k) {
    const double dchi = chi[k + 1] - chi[k], h = segment_length[k];
    const double* dg = outgoing.dg.data() + k * n;
    unit_phase(in_re_[k + 1], in_im_[k + 1], outgoing.re.data() + (k + 1) * n, outgoing.im.data() + (k + 1) * n,
               nxt_re, nxt_im, n);
    simd::v4d largest = simd::splat(0.0);
    for (std::size_t j = 0; j < n; j += 4) {
      simd::v4d u;
      std::memcpy(&u, dg + j, sizeof u);
      u += dchi;
      const simd::v4d magnitude = u < 0.0 ? -u : u;
      largest = magnitude > largest ? magnitude : largest;
      simd::v4d b_re, b_im;
      tent_weight_b_series(u, b_re, b_im);
      b_re *= h;
      b_im *= h;
      std::memcpy(br + j, &b_re, sizeof b_re);
      std::memcpy(bi + j, &b_im, sizeof b_im);
    }
    if (std::max(std::max(largest[0], largest[1]), std::max(largest[2], largest[3])) > kTaylorRange) {
      // Coarse sampling or very short λ: closed form where the series would not converge.
      for (std::size_t j = 0; j < p_dir; ++j) {
        const double u = dchi + dg[j];
        if (std::abs(u) <= kTaylorRange) continue;
        std::complex<double> a, b;
        tent_weights_closed(u, a, b);
        br[j] = h * b.real(), bi[j] = h * b.imag();
      }
    }
    if (k >= 1) {
      // Node k's column: the B part of segment k − 1 (carry) plus the A part of segment k.
      multiply_conj_add(cr, ci, nxt_re, nxt_im, br, bi, nr, ni, n);
      auto* col = split.data() + static_cast<Eigen::Index>((k - 1) * 2 * p_dir);
      store_column(nr, ni, p_dir, col);
    }
    multiply(cur_re, cur_im, br, bi, cr, ci, n);
    std::swap(cur_re, nxt_re);
    std::swap(cur_im, nxt_im);
  }
}

void FactoredTentKernel::build(const OutgoingPhases& outgoing, std::span<const double> segment_length,
                               std::span<const double> chi, Eigen::MatrixXd& split) {
  build_into(outgoing, segment_length, chi, split);
}

// The float kernel (tent_kernel.hpp): the loops of build_into in 8 float lanes.
void FactoredTentKernel::build(const OutgoingPhases& outgoing, std::span<const double> segment_length,
                               std::span<const double> chi, Eigen::MatrixXf& split) {
  const std::size_t verts = outgoing.verts, segs = verts - 1, nodes = verts - 2;
  const std::size_t n = outgoing.stride, p_dir = outgoing.directions;  // n: a multiple of 8
  for (auto& b : f_) b.resize(n);
  split.resize(static_cast<Eigen::Index>(2 * p_dir), static_cast<Eigen::Index>(nodes));
  incident_phases(chi, verts);
  float* br = f_[0].data();
  float* bi = f_[1].data();
  float* cur_re = f_[2].data();
  float* cur_im = f_[3].data();
  float* nxt_re = f_[4].data();
  float* nxt_im = f_[5].data();
  float* cr = f_[6].data();
  float* ci = f_[7].data();
  float* nr = f_[8].data();
  float* ni = f_[9].data();
  unit_phase(static_cast<float>(in_re_[0]), static_cast<float>(in_im_[0]), outgoing.re_f.data(), outgoing.im_f.data(),
             cur_re, cur_im, n);
  for (std::size_t k = 0; k < segs; ++k) {
    const double dchi = chi[k + 1] - chi[k], h = segment_length[k];
    const float dchi_f = static_cast<float>(dchi), h_f = static_cast<float>(h);
    const float* dg = outgoing.dg_f.data() + k * n;
    unit_phase(static_cast<float>(in_re_[k + 1]), static_cast<float>(in_im_[k + 1]),
               outgoing.re_f.data() + (k + 1) * n, outgoing.im_f.data() + (k + 1) * n, nxt_re, nxt_im, n);
    v8f largest = v8f{} + 0.0f;
    for (std::size_t j = 0; j < n; j += 8) {
      v8f u;
      std::memcpy(&u, dg + j, sizeof u);
      u += dchi_f;
      const v8f magnitude = u < 0.0f ? -u : u;
      largest = magnitude > largest ? magnitude : largest;
      v8f b_re, b_im;
      tent_weight_b_series_f(u, b_re, b_im);
      b_re *= h_f;
      b_im *= h_f;
      std::memcpy(br + j, &b_re, sizeof b_re);
      std::memcpy(bi + j, &b_im, sizeof b_im);
    }
    float top = 0.0f;
    for (int l = 0; l < 8; ++l) top = std::max(top, largest[l]);
    if (top > static_cast<float>(kTaylorRange)) {
      const double* dg_d = outgoing.dg.data() + k * n;
      for (std::size_t j = 0; j < p_dir; ++j) {
        const double u = dchi + dg_d[j];
        if (std::abs(u) <= kTaylorRange) continue;
        std::complex<double> a, b;
        tent_weights_closed(u, a, b);
        br[j] = static_cast<float>(h * b.real()), bi[j] = static_cast<float>(h * b.imag());
      }
    }
    if (k >= 1) {
      multiply_conj_add(cr, ci, nxt_re, nxt_im, br, bi, nr, ni, n);
      float* col = split.data() + static_cast<Eigen::Index>((k - 1) * 2 * p_dir);
      std::memcpy(col, nr, p_dir * sizeof(float));
      std::memcpy(col + p_dir, ni, p_dir * sizeof(float));
    }
    multiply(cur_re, cur_im, br, bi, cr, ci, n);
    std::swap(cur_re, nxt_re);
    std::swap(cur_im, nxt_im);
  }
}

void TentKernel::accumulate(std::size_t segs, double* out) {
  const std::size_t nodes = segs - 1;
  double largest = 0.0;
  for (std::size_t k = 0; k < segs; k += 4) {
    simd::v4d a_re, a_im, b_re, b_im;
    const simd::v4d u{u_[k], u_[k + 1], u_[k + 2], u_[k + 3]};
    tent_weights_series(u, a_re, a_im, b_re, b_im);
    for (int l = 0; l < 4; ++l) {
      ar_[k + l] = a_re[l], ai_[k + l] = a_im[l], br_[k + l] = b_re[l], bi_[k + l] = b_im[l];
      if (k + l < segs) largest = std::max(largest, std::abs(u[l]));
    }
  }
  if (largest > kTaylorRange) {  // coarse sampling or very short λ: closed form
    for (std::size_t k = 0; k < segs; ++k) {
      if (std::abs(u_[k]) <= kTaylorRange) continue;
      std::complex<double> a, b;
      tent_weights_closed(u_[k], a, b);
      ar_[k] = a.real(), ai_[k] = a.imag(), br_[k] = b.real(), bi_[k] = b.imag();
    }
  }
  // Node m (vertex m) collects h·e^{iψ}·B of segment m−1 and h·e^{iψ}·A of segment m.
  for (std::size_t m = 1; m <= nodes; ++m) {
    const double pr = er_[m - 1] * br_[m - 1] - ei_[m - 1] * bi_[m - 1];
    const double pi = er_[m - 1] * bi_[m - 1] + ei_[m - 1] * br_[m - 1];
    const double nr = er_[m] * ar_[m] - ei_[m] * ai_[m];
    const double ni = er_[m] * ai_[m] + ei_[m] * ar_[m];
    out[2 * (m - 1)] = h_[m - 1] * pr + h_[m] * nr;
    out[2 * (m - 1) + 1] = h_[m - 1] * pi + h_[m] * ni;
  }
}

// Written as plain loops over structure-of-arrays buffers so that they vectorise; complex
// products are spelled out in real arithmetic (std::complex's operator* calls __muldc3 for
// Inf/NaN recovery).
void TentKernel::build(std::span<const Vec2> vertices, std::span<const double> segment_length,
                       std::span<const double> chi, Vec2 origin, double gamma0,
                       std::span<const double> phi_o_rad, Eigen::MatrixXcd& kt) {
  const std::size_t verts = vertices.size();
  const std::size_t segs = verts - 1;
  const std::size_t nodes = verts - 2;
  if (verts + 8 > psi_.size()) {
    for (auto* b : {&psi_, &er_, &ei_, &ar_, &ai_, &br_, &bi_, &u_, &h_}) b->assign(verts + 8, 0.0);
  }
  std::fill(h_.begin(), h_.end(), 0.0);
  for (std::size_t k = 0; k < segs; ++k) h_[k] = segment_length[k];
  kt.resize(static_cast<Eigen::Index>(nodes), static_cast<Eigen::Index>(phi_o_rad.size()));
  const Vec2* v = vertices.data();
  for (std::size_t j = 0; j < phi_o_rad.size(); ++j) {
    const double sx = gamma0 * std::sin(phi_o_rad[j]), sz = gamma0 * std::cos(phi_o_rad[j]);
    double* psi = psi_.data();
    for (std::size_t k = 0; k < verts; ++k) {
      psi[k] = chi[k] - (sx * (v[k].x - origin.x) + sz * (v[k].z - origin.z));
    }
    for (std::size_t k = verts; k < verts + 4; ++k) psi[k] = psi[verts - 1];
    for (std::size_t k = 0; k < verts; k += 4) {
      simd::v4d s, c;
      simd::sincos(simd::v4d{psi[k], psi[k + 1], psi[k + 2], psi[k + 3]}, s, c);
      for (int l = 0; l < 4; ++l) er_[k + l] = c[l], ei_[k + l] = s[l];
    }
    // Segment phase increments u and the tent weights A(u), B(u), then the node sums.
    for (std::size_t k = 0; k < segs + 4; ++k) u_[k] = psi[k + 1] - psi[k];
    accumulate(segs, reinterpret_cast<double*>(kt.data() + static_cast<Eigen::Index>(j * nodes)));
  }
}

}  // namespace plumage::detail
