// The Eq. 2 currents of the approximate solver (paper §4.1: J̃ = n̂ × η0H, M = −n̂ × E from the
// local reflection under each top node), as current amplitudes for the far field (radiation.hpp).
#pragma once

#include <Eigen/Dense>

#include <array>
#include <span>

#include "plumage/cross_section.hpp"
#include "plumage/far_field.hpp"
#include "plumage/local_reflection.hpp"

namespace plumage::detail {

// Nodes whose local incidence is within 1e-3 rad of grazing, or beyond, carry no current
// (back-facing; the reference code's threshold). There is no shadowing between nodes.
inline constexpr double kGrazingCutoff = 1e-3;

// What the currents need of one prepared top surface (the solver's PreparedTop): interior
// nodes 1..N−2 with their normals, window w(x_m), d_m and regularity factor; with reflection
// sub-sampling (samples K > 1) the fine interior vertices' normals and the segment lengths.
struct CurrentNodes {
  std::span<const Vec2> normals;
  std::span<const double> window;
  std::span<const double> node_length;
  std::span<const double> regularity;
  std::span<const double> segment_length;
  int samples = 1;
  std::span<const Vec2> sample_normals;
};

// Current amplitudes at every node for one incident direction ω_i (w_i, as in solve()), both
// polarizations: columns [pol][J̃x J̃y J̃z Mx My Mz], times the window and the regularity,
// without the incident phase (the kernel carries it); and the incident power Φ_i (Eq. 9).
// `jones` holds one matrix per node, or per sub-sample when the reflection is sub-sampled: then
// a node's currents are the tent-weighted mean of its lit sub-samples' currents (each with its
// own normal and basis — Jones matrices in different local bases cannot be averaged).
//
// With 24 columns, columns 12–23 receive the lossless reference: the reflected wave at every
// point keeps its polarization and phase but carries all the incident power (|a_s|² + |a_p|² =
// |E_i·ŝ|² + |η0H_i·ŝ|²), without the regularity factor: the reference of the `lossless`
// normalisation. Where nothing is reflected (a polarization at its Brewster angle) it falls back
// to a perfect conductor (a_s = −E_i·ŝ, a_p = η0H_i·ŝ).
void fill_amplitudes(const CurrentNodes& top, const IncidentDirection& incident, const std::array<double, 3>& w_i,
                     std::span<const JonesReflection> jones, bool with_incident,
                     Eigen::Ref<Eigen::MatrixXcd> amplitudes, std::array<double, 2>& incident_power);

}  // namespace plumage::detail
