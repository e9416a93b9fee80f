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
  std::vector<double> psi_, er_, ei_, ar_, ai_, br_, bi_, u_, h_;
};

}  // namespace plumage::detail
