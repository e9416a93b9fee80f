// Kernel of the 2.5D radiation integrals over a polyline carrying tent-interpolated currents:
//   K[m, φ] = ∫ Λ_m(l) e^{i(χ(l) − γ0 ρ̂(φ)·(ρ(l) − o))} dl,   ρ̂(φ) = (sin φ, cos φ),
// for every interior vertex m of a vertex range and every outgoing azimuth φ (paper Eq. 7 with
// the incident phase χ = k_i·ρ inside the integral). Exact for the tent Λ_m and for the phase,
// which is linear along each straight segment (tent_integrals.hpp), so no quadrature error.
#pragma once

#include <Eigen/Dense>

#include <span>
#include <vector>

#include "plumage/cross_section.hpp"

namespace plumage::detail {

// The outgoing half of the kernel's phase for one polyline, phase origin and set of azimuths:
// g_k(φ) = −γ0 ρ̂(φ)·(ρ_k − o), stored as e^{i g_k} and the segment increments g_{k+1} − g_k.
// It does not depend on the incident azimuth, so one table serves every φ_i of a (λ, θ_i):
// ψ_k = χ_k + g_k, e^{iψ_k} = e^{iχ_k} e^{ig_k}, u_k = (χ_{k+1} − χ_k) + (g_{k+1} − g_k).
// Vertex-major (the directions of a vertex contiguous), so that the kernel is built with long
// vector loops over the directions.
struct OutgoingPhases {
  std::size_t verts = 0, stride = 0, directions = 0;
  std::vector<double> re, im, dg;  // [vertex · stride + direction] (dg: segment), zero-padded
  std::vector<float> re_f, im_f, dg_f;  // the same rounded to float (the float kernel's)

  void build(std::span<const Vec2> vertices, Vec2 origin, double gamma0, std::span<const double> phi_o_rad);
};

// The transposed kernel from an OutgoingPhases table and the incident phase χ (over the table's
// vertex range), split into real and imaginary parts for real GEMMs: `split` is (2·directions) ×
// nodes, rows 0 … P − 1 Re K[m, φ_j], rows P … 2P − 1 Im K[m, φ_j]. One complex product per
// entry instead of a sincos. Equal to TentKernel::build's kt (transposed) to rounding.
// A float `split` (the single-precision GEMM of radiation.hpp) is computed in float throughout
// (8 lanes): phases e^{iχ}, e^{ig} and increments u rounded to float, the same B series; the
// entries then carry a few float roundings (~2e-7 relative) instead of one (issue 26, error in
// docs/benchmarks.md "simulate"). The closed form (|u| > 1) is evaluated in double.
class FactoredTentKernel {
 public:
  void build(const OutgoingPhases& outgoing, std::span<const double> segment_length,
             std::span<const double> chi, Eigen::MatrixXd& split);
  void build(const OutgoingPhases& outgoing, std::span<const double> segment_length,
             std::span<const double> chi, Eigen::MatrixXf& split);

 private:
  void incident_phases(std::span<const double> chi, std::size_t verts);
  template <class Matrix>
  void build_into(const OutgoingPhases& outgoing, std::span<const double> segment_length,
                  std::span<const double> chi, Matrix& split);

  std::vector<double> ar_, ai_, br_, bi_, er_, ei_, carry_re_, carry_im_, node_re_, node_im_, in_re_, in_im_, padded_;
  std::vector<float> f_[10];  // the float kernel's buffers
};

class TentKernel {
 public:
  // The scratch buffers fit polylines of up to `max_vertices` vertices.
  explicit TentKernel(std::size_t max_vertices);

  // kt (nodes × directions), nodes = vertices.size() − 2 (the interior vertices, in order);
  // `segment_length[k]` = |v_{k+1} − v_k| and `chi[k]` the incident phase at vertex k, both over
  // the same range as `vertices`; `origin` is the phase reference o.
  void build(std::span<const Vec2> vertices, std::span<const double> segment_length,
             std::span<const double> chi, Vec2 origin, double gamma0,
             std::span<const double> phi_o_rad, Eigen::MatrixXcd& kt);

 private:
  // Node sums from er_/ei_ (e^{iψ}) and u_ (segment phase increments) into column j of kt.
  void accumulate(std::size_t segs, double* out);

  std::vector<double> psi_, er_, ei_, ar_, ai_, br_, bi_, u_, h_;
};

}  // namespace plumage::detail
