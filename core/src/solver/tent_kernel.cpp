#include "tent_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/simd_math.hpp"
#include "tent_integrals.hpp"

namespace plumage::detail {

TentKernel::TentKernel(std::size_t max_vertices) {
  const std::size_t v = max_vertices + 8;
  for (auto* b : {&psi_, &er_, &ei_, &ar_, &ai_, &br_, &bi_, &u_, &h_}) b->assign(v, 0.0);
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
    // Segment phase increments u and the tent weights A(u), B(u).
    for (std::size_t k = 0; k < segs + 4; ++k) u_[k] = psi[k + 1] - psi[k];
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
    double* out = reinterpret_cast<double*>(kt.data() + static_cast<Eigen::Index>(j * nodes));
    for (std::size_t m = 1; m <= nodes; ++m) {
      const double pr = er_[m - 1] * br_[m - 1] - ei_[m - 1] * bi_[m - 1];
      const double pi = er_[m - 1] * bi_[m - 1] + ei_[m - 1] * br_[m - 1];
      const double nr = er_[m] * ar_[m] - ei_[m] * ai_[m];
      const double ni = er_[m] * ai_[m] + ei_[m] * ar_[m];
      out[2 * (m - 1)] = h_[m - 1] * pr + h_[m] * nr;
      out[2 * (m - 1) + 1] = h_[m - 1] * pi + h_[m] * ni;
    }
  }
}

}  // namespace plumage::detail
