// The chunks of a polyline and the tree that merges their far fields (radiation.hpp, issue 26).
//
// A node's far field relative to its centre r_n, F_n(φ), is band-limited in φ (Jacobi–Anger):
// no Fourier component e^{ikφ} beyond band(x) = x + 7 x^{1/3} + 10, x = γ0 R_n (R_n the radius
// of its vertices about r_n). It is held on its own uniform grid over (−π/2, π/2) at
// `oversampling` × band(x) points per π. A parent's field is the sum of its children's shifted
// to its centre,
//   F_P(φ) = Σ_c F_c(φ) e^{−iγ0 ρ̂(φ)·(r_c − r_P)},
// evaluated at the parent's grid points: each child interpolated there (N-point Lagrange on the
// child's grid) and multiplied by the shift phase, exact at the point. The product's band is at
// most γ0 (R_c + |r_c − r_P|) ≤ γ0 R_P, within the parent's grid. The leaves are the chunks (one
// grid for all of them); every internal node merges two or three neighbours, so that the tree
// (and every grid, symmetric about 0) is the mirror image of itself: a mirrored barbule is merged
// in the mirrored order.
#pragma once

#include <Eigen/Dense>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "chunking_options.hpp"
#include "plumage/cross_section.hpp"

namespace plumage::detail {

// φ_p = lo + p·step, p = 0 … samples − 1: a whole number of steps (`intervals`) across
// (−π/2, π/2), symmetric about 0, and `pad` steps beyond each end (room for the stencils of the
// targets and of the parent's grid, itself padded).
struct SampleGrid {
  double lo = 0.0, step = 0.0;
  std::size_t intervals = 0, pad = 0, samples = 0;
  std::vector<double> phi;
};

// N-point Lagrange stencil (N even: the target between the stencil's two middle points) of
// each target on a grid; sin φ, cos φ of the targets too if `with_trig`.
struct Stencil {
  int points = 6;
  std::vector<Eigen::Index> first;
  std::vector<std::array<double, kMaxStencilPoints>> weight;
  std::vector<double> sin_phi, cos_phi;
};

Stencil make_stencil(std::span<const double> phi_o_rad, const SampleGrid& grid, int points, bool with_trig = true);

struct FarFieldTree {
  struct Chunk {
    std::size_t first, count;  // nodes first … first + count − 1 (vertices first … first + count + 1)
    Vec2 centre;
  };
  // A child's samples → its parent's grid: per parent grid point the child's first stencil
  // point, the weights [point · stencil_points + a] and e^{−iγ0 ρ̂·(r_c − r_P)} (re, im).
  struct Transfer {
    std::size_t child = 0;
    std::vector<std::int32_t> first;
    std::vector<float> weight, phase;
  };
  struct Node {
    Vec2 centre;
    std::size_t grid = 0;  // index into grids
    std::vector<Transfer> children;
  };
  std::vector<Chunk> chunks;
  std::size_t max_count = 0;
  std::vector<SampleGrid> grids;  // grids[0]: the chunks' grid; then one per internal node
  std::vector<Node> nodes;        // 0 … chunks − 1 the chunks; then the internal nodes, children first
  std::vector<int> grid_points;   // Lagrange points of the stencils that read each grid

  const Node& root() const { return nodes.back(); }
  int root_points() const { return grid_points[root().grid]; }
  std::size_t root_index() const { return nodes.size() - 1; }
};

// The chunks, the tree and every grid; the transfers only if `with_transfers` (estimate_bytes
// needs the sizes alone).
FarFieldTree far_field_tree(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
                            const ChunkingOptions& options, bool with_transfers);

// Every internal node's samples from its children's, children first. `leaf_samples`:
// [chunk][grid point][width floats]; node_samples[n − chunks]: [grid point][width floats],
// (re, im) pairs, for internal node n.
void aggregate(const FarFieldTree& tree, const float* leaf_samples, std::size_t width,
               std::vector<std::vector<float>>& node_samples);

}  // namespace plumage::detail
