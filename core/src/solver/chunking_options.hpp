// How the approximate solver evaluates its far field (radiation.hpp).
#pragma once

namespace plumage::detail {

inline constexpr int kMaxStencilPoints = 12;

struct ChunkingOptions {
  bool chunked = true;        // false: every (node, direction) kernel entry
  double chunk_phase = 18.0;  // target γ0·R_c of a chunk (R_c its radius)
  // Sampling grid step = π/(oversampling · band limit), Lagrange points of the interpolation to
  // the targets. Issue 26 (docs/benchmarks.md "simulate"): 1.6 with 10 points is 1.6x fewer
  // samples (kernel entries, GEMM rows) than the former 3.0 with 6, and ~2x closer to the exact sum.
  double oversampling = 1.6;
  int stencil_points = 10;  // even, 4 … kMaxStencilPoints
  // The grids of the merge tree's internal nodes (radiation_tree.hpp) and the stencils that read
  // them (node → parent, root → targets; the chunks' grid is read with stencil_points). A node's
  // band margin 7x^{1/3} + 10 is a smaller share of its band than a chunk's, so the same accuracy
  // needs more samples per band limit: 1.6x gives 4.8e-5 vs the exact sum, 3.0x 1.9e-6 (issue 26,
  // docs/benchmarks.md "simulate").
  double merge_oversampling = 3.0;
  int merge_stencil_points = 10;
  // The chunk GEMM (kernel × current columns) in single precision: the kernel built in float
  // (tent_kernel.hpp), the currents rounded to float once, products summed in float over a
  // chunk's ~100 nodes (issue 26: error budget and speed in docs/benchmarks.md "simulate"). The
  // chunks' projected samples are stored in float either way, and merged up the tree in float
  // (float rounding ~1e-7 per level against the 1e-5 budget; the tree test bounds it); the
  // root's interpolation to the targets sums in float, its phase and the results are double.
  bool single_precision_gemm = true;
};

}  // namespace plumage::detail
