// Far field of tent-interpolated surface currents on the top polyline (paper Eq. 7, spec §4.1),
// projected on the two polarization directions of each outgoing direction.
//
// The currents come as groups of six columns (J̃x J̃y J̃z Mx My Mz, J̃ = η0 J) per node; group g
// yields two outputs per direction, the components of
//   𝓔/pref = ô × S_M − (I − ôô) S_J
// along ê1 = (cos φ, 0, −sin φ) and ê2 = ô × ê1 = (sin θ_i sin φ, cos θ_i, sin θ_i cos φ), where
// ô = (cos θ_i sin φ, −sin θ_i, cos θ_i cos φ) is the outgoing direction on the specular cone and
// S_J, S_M the radiation integrals:  o1 = −ê1·S_J − ê2·S_M,  o2 = −ê2·S_J + ê1·S_M.
//
// Two evaluations:
//  * exact    every (node, direction) kernel entry (tent_kernel.hpp) and one GEMM; cost
//             ∝ nodes × directions.
//  * chunked  the polyline is cut into chunks of a few µm (γ0·R_c ≈ chunk_phase, R_c a chunk's
//             radius). Relative to its centre r_c, a chunk's far field F_c(φ) is band-limited in
//             φ: by the Jacobi–Anger expansion it has no Fourier component e^{inφ} above
//             |n| ≈ γ0 R_c beyond a decay margin. It is computed exactly (kernel × currents, one
//             GEMM per chunk, projected on ê1, ê2) on a uniform grid over (−π/2, π/2) at a few
//             times that rate (ChunkingOptions: 1.6). The chunks' fields are then merged up a
//             tree (radiation_tree.hpp, issue 26): neighbouring chunks in twos or threes, then
//             those nodes, up to one root over the whole polyline; a parent's samples, on its own
//             finer grid (band limit of its radius, merge_oversampling 3.0), are its children's
//             interpolated there (10-point Lagrange) times the shift e^{−iγ0 ρ̂·(r_c − r_P)}.
//             Only the root is interpolated to the requested directions and multiplied by
//             e^{−iγ0 ρ̂·r_root}. Cost ∝ nodes × (samples per chunk) for the kernels and GEMMs,
//             (levels × samples + directions) × stencil for the interpolation (before: chunks ×
//             directions × stencil); agreement with the exact sum is measured in the tests
//             (≤ 1e-5 relative L2; 1.4e-6 to 1.9e-6 on the production bench units).
#pragma once

#include <Eigen/Dense>

#include <memory>
#include <span>
#include <vector>

#include "chunking_options.hpp"
#include "plumage/cross_section.hpp"

namespace plumage::detail {

// One set of outgoing azimuths and the outputs wanted there.
struct RadiationTargets {
  std::span<const double> phi_o_rad;
  int first_output = 0;  // outputs 2g, 2g + 1 belong to column group g
  int outputs = 0;
  Eigen::MatrixXcd* result = nullptr;  // resized to (directions × outputs) and overwritten
};

// The far field of many incident azimuths of one (polyline, γ0, θ_i, target azimuths): what does
// not depend on the incident phase χ — the chunks, the merge tree and its grids, the merge and
// target stencils with their shift phases, the root's phases e^{−iγ0 ρ̂_j·r_root} at the targets
// and the outgoing kernel phases (OutgoingPhases) — is set up once; radiate_all() then costs one
// complex product per kernel entry instead of a sincos. Chunked evaluation needs every target
// azimuth in [−π/2, π/2]; otherwise the exact sum is used.
class Radiator {
 public:
  Radiator(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
           double theta_i_rad, std::vector<std::span<const double>> target_phi_o_rad,
           const ChunkingOptions& options);
  ~Radiator();
  Radiator(const Radiator&) = delete;
  Radiator& operator=(const Radiator&) = delete;

  // Every incident azimuth a at once: chi[a], amplitudes[a] ((vertices − 2) × (6·groups));
  // layout[s].phi_o_rad must be the azimuths given to the constructor as set s (its `result`
  // pointers unused); results[a · layout.size() + s] receives set s of azimuth a. The merge
  // and the interpolation to the targets run over all azimuths (and all the sets' outputs)
  // together: one stencil and phase per grid point or direction for all of them.
  void radiate_all(std::span<const std::vector<double>> chi, std::span<const Eigen::MatrixXcd> amplitudes,
                   std::span<const RadiationTargets> layout, std::vector<Eigen::MatrixXcd>& results);

  // Upper bound of the bytes a Radiator of these arguments and radiate_all() over `n_phi`
  // azimuths of `columns` current columns hold (plan, chunk tables, kernel, split amplitudes,
  // accumulators, results), from the same chunk layout, without building anything.
  static double estimate_bytes(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
                               std::span<const std::size_t> target_sizes, bool on_cone, const ChunkingOptions& options,
                               std::size_t n_phi, std::size_t columns);

  struct Plan;  // radiation.cpp

 private:
  std::unique_ptr<Plan> plan_;
};

}  // namespace plumage::detail
