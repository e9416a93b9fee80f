#include "radiation_tree.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/simd_math.hpp"

namespace plumage::detail {

namespace {

// Jacobi–Anger: |J_n(x)| for n ≥ x + 7 x^{1/3} + 8 is below ~1e-10 of the peak; the projection
// on ê1, ê2 adds two more orders.
double band_limit(double x) { return x + 7.0 * std::cbrt(x) + 10.0; }

// Centre (of the bounding box) and radius of vertices [v0, v1].
std::pair<Vec2, double> enclosing(std::span<const Vec2> vertices, std::size_t v0, std::size_t v1) {
  double x_lo = vertices[v0].x, x_hi = x_lo, z_lo = vertices[v0].z, z_hi = z_lo;
  for (std::size_t k = v0; k <= v1; ++k) {
    x_lo = std::min(x_lo, vertices[k].x), x_hi = std::max(x_hi, vertices[k].x);
    z_lo = std::min(z_lo, vertices[k].z), z_hi = std::max(z_hi, vertices[k].z);
  }
  const Vec2 centre{0.5 * (x_lo + x_hi), 0.5 * (z_lo + z_hi)};
  double radius = 0.0;
  for (std::size_t k = v0; k <= v1; ++k) radius = std::max(radius, norm(vertices[k] - centre));
  return {centre, radius};
}

// Chunk sizes as equal as possible and palindromic, so that a mirrored barbule is cut into the
// mirrored chunks.
std::vector<std::size_t> chunk_sizes(std::size_t nodes, std::size_t per_chunk) {
  std::size_t count = (nodes + per_chunk - 1) / per_chunk;
  if (count % 2 == 0 && nodes % 2 == 1) ++count;
  std::vector<std::size_t> sizes(count, nodes / count);
  std::size_t extra = nodes % count;
  if (extra % 2 == 1) ++sizes[count / 2], --extra;  // count is odd here
  for (std::size_t k = 0; k < extra / 2; ++k) ++sizes[k], ++sizes[count - 1 - k];
  return sizes;
}

SampleGrid sample_grid(std::size_t intervals, std::size_t pad) {
  SampleGrid g;
  g.intervals = intervals;
  g.pad = pad;
  g.step = kPi / static_cast<double>(intervals);
  g.lo = -0.5 * kPi - static_cast<double>(pad) * g.step;
  g.samples = intervals + 2 * pad + 1;
  g.phi.resize(g.samples);
  for (std::size_t p = 0; p < g.samples; ++p) {
    g.phi[p] = g.step * (static_cast<double>(p) - static_cast<double>(pad) - 0.5 * static_cast<double>(intervals));
  }
  return g;
}

struct Builder {
  std::span<const Vec2> vertices;
  double gamma0;
  const ChunkingOptions& options;
  FarFieldTree& tree;
  std::vector<std::size_t> intervals;  // per grid

  // Node over chunks [a, b): a chunk, or two halves, or three parts (k, n − 2k, k) for odd n:
  // symmetric under reversal of the chunk order.
  std::size_t build(std::size_t a, std::size_t b) {
    const std::size_t n = b - a;
    if (n == 1) return a;
    std::vector<std::size_t> bounds{a};
    if (n % 2 == 0) {
      bounds.push_back(a + n / 2);
    } else {
      const std::size_t k = (n + 1) / 3;
      bounds.push_back(a + k);
      bounds.push_back(b - k);
    }
    bounds.push_back(b);
    FarFieldTree::Node node;
    for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
      FarFieldTree::Transfer t;
      t.child = build(bounds[i], bounds[i + 1]);
      node.children.push_back(std::move(t));
    }
    const auto& first = tree.chunks[a];
    const auto& last = tree.chunks[b - 1];
    const auto [centre, radius] = enclosing(vertices, first.first, last.first + last.count + 1);
    node.centre = centre;
    node.grid = intervals.size();
    intervals.push_back(static_cast<std::size_t>(std::ceil(options.merge_oversampling * band_limit(gamma0 * radius))));
    tree.nodes.push_back(std::move(node));
    return tree.nodes.size() - 1;
  }
};

}  // namespace

Stencil make_stencil(std::span<const double> phi_o_rad, const SampleGrid& grid, int points, bool with_trig) {
  Stencil s;
  s.points = points;
  const int half = points / 2;
  std::array<double, kMaxStencilPoints> inverse_denominator{};
  for (int a = 0; a < points; ++a) {
    double den = 1.0;
    for (int b = 0; b < points; ++b) den *= b == a ? 1.0 : a - b;
    inverse_denominator[static_cast<std::size_t>(a)] = 1.0 / den;
  }
  s.first.reserve(phi_o_rad.size()), s.weight.reserve(phi_o_rad.size());
  s.sin_phi.reserve(phi_o_rad.size()), s.cos_phi.reserve(phi_o_rad.size());
  for (const double phi : phi_o_rad) {
    const double t = (phi - grid.lo) / grid.step;
    // The stencil centred on the target (f in [half − 1, half): position among nodes 0 … points − 1),
    // shifted inwards where it would leave the grid (the chunks' grid, see far_field_tree).
    const double base = std::clamp(std::floor(t) - (half - 1), 0.0, static_cast<double>(grid.samples) - points);
    const double f = t - base;
    // w_a = Π_{b≠a} (f − b) / Π_{b≠a} (a − b): the numerators from prefix and suffix products.
    std::array<double, kMaxStencilPoints> w{}, right{};
    right[static_cast<std::size_t>(points - 1)] = 1.0;
    for (int a = points - 1; a > 0; --a) {
      right[static_cast<std::size_t>(a - 1)] = right[static_cast<std::size_t>(a)] * (f - a);
    }
    double left = 1.0;
    for (int a = 0; a < points; ++a) {
      const auto i = static_cast<std::size_t>(a);
      w[i] = left * right[i] * inverse_denominator[i];
      left *= f - a;
    }
    s.first.push_back(static_cast<Eigen::Index>(base));
    s.weight.push_back(w);
    if (!with_trig) continue;
    s.sin_phi.push_back(std::sin(phi));
    s.cos_phi.push_back(std::cos(phi));
  }
  return s;
}

FarFieldTree far_field_tree(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
                            const ChunkingOptions& options, bool with_transfers) {
  FarFieldTree tree;
  const std::size_t nodes = vertices.size() - 2;
  double total = 0.0;
  for (const double h : segment_length) total += h;
  const double mean_h = total / static_cast<double>(segment_length.size());
  const auto per_chunk = static_cast<std::size_t>(
      std::max(8.0, std::round(2.0 * options.chunk_phase / std::max(gamma0 * mean_h, 1e-12))));
  double leaf_band = 0.0;
  std::size_t m0 = 0;
  for (const std::size_t size : chunk_sizes(nodes, per_chunk)) {
    // Tent supports of nodes m0 … m0 + size − 1 span vertices m0 … m0 + size + 1.
    const auto [centre, radius] = enclosing(vertices, m0, m0 + size + 1);
    tree.chunks.push_back({m0, size, centre});
    tree.nodes.push_back({centre, 0, {}});
    tree.max_count = std::max(tree.max_count, size);
    leaf_band = std::max(leaf_band, band_limit(gamma0 * radius));
    m0 += size;
  }
  Builder builder{vertices, gamma0, options, tree,
                  {static_cast<std::size_t>(std::ceil(options.oversampling * leaf_band))}};
  builder.build(0, tree.chunks.size());
  // The stencils reading the chunks' grid (to their parents, or a single chunk to the targets)
  // have stencil_points, those reading an internal node's grid merge_stencil_points.
  const std::size_t grids = builder.intervals.size();
  tree.grid_points.assign(grids, options.merge_stencil_points);
  tree.grid_points[0] = options.stencil_points;
  // Padding, from the root down: the root's stencils reach the targets in [−π/2, π/2], a child's
  // the parent's outermost grid point (π/2 + pad_P·step_P) and half a stencil beyond it. The
  // chunks share the largest padding any of them needs.
  auto half = [&](std::size_t g) { return static_cast<std::size_t>(tree.grid_points[g] / 2); };
  std::vector<std::size_t> pad(grids, 0);
  pad[tree.root().grid] = half(tree.root().grid);
  for (std::size_t n = tree.nodes.size(); n-- > tree.chunks.size();) {
    const auto& node = tree.nodes[n];
    const double reach = static_cast<double>(pad[node.grid]) / static_cast<double>(builder.intervals[node.grid]);
    for (const auto& t : node.children) {
      const std::size_t g = tree.nodes[t.child].grid;
      const auto needed =
          half(g) + static_cast<std::size_t>(std::ceil(reach * static_cast<double>(builder.intervals[g]) - 1e-9));
      pad[g] = std::max(pad[g], needed);
    }
  }
  // The chunks' grid (its samples are the kernels' and GEMMs' rows) keeps the padding of the
  // targets' stencils alone: a parent's points beyond ±(π/2 + 5 chunk steps), which serve only
  // the last ~2° of targets next to ±π/2, are read by stencils shifted inwards (make_stencil
  // clamps). Measured: relative L2 vs the exact sum unchanged to 3 digits on the production
  // units, error of the root's samples within 1.5 rad < |φ| ≤ π/2 1.6e-7 (test_radiation_tree.cpp),
  // 7 % fewer chunk samples (issue 26).
  pad[0] = std::min(pad[0], half(0));
  for (std::size_t g = 0; g < grids; ++g) tree.grids.push_back(sample_grid(builder.intervals[g], pad[g]));
  if (!with_transfers) return tree;
  std::vector<double> sin_phi, cos_phi, angle;
  for (std::size_t n = tree.chunks.size(); n < tree.nodes.size(); ++n) {
    FarFieldTree::Node& node = tree.nodes[n];
    const SampleGrid& grid = tree.grids[node.grid];
    const std::size_t padded = (grid.samples + 3) / 4 * 4;
    sin_phi.resize(padded), cos_phi.resize(padded), angle.assign(padded, 0.0);
    for (std::size_t p = 0; p < grid.samples; ++p) sin_phi[p] = std::sin(grid.phi[p]), cos_phi[p] = std::cos(grid.phi[p]);
    for (auto& t : node.children) {
      const FarFieldTree::Node& child = tree.nodes[t.child];
      const int points = tree.grid_points[child.grid];
      const Stencil s = make_stencil(grid.phi, tree.grids[child.grid], points, false);
      const Vec2 d = child.centre - node.centre;
      for (std::size_t p = 0; p < grid.samples; ++p) angle[p] = -gamma0 * (sin_phi[p] * d.x + cos_phi[p] * d.z);
      t.first.resize(grid.samples);
      t.weight.resize(grid.samples * static_cast<std::size_t>(points));
      t.phase.resize(2 * grid.samples);
      for (std::size_t p = 0; p < grid.samples; ++p) {
        t.first[p] = static_cast<std::int32_t>(s.first[p]);
        if (s.first[p] < 0 || s.first[p] + points > static_cast<Eigen::Index>(tree.grids[child.grid].samples))
          throw Error("radiate: a merge stencil leaves its child's grid (padding)");
        for (int a = 0; a < points; ++a)
          t.weight[p * static_cast<std::size_t>(points) + static_cast<std::size_t>(a)] =
              static_cast<float>(s.weight[p][static_cast<std::size_t>(a)]);
      }
      for (std::size_t p = 0; p < grid.samples; p += 4) {
        simd::v4d sn, cs;
        simd::sincos(simd::v4d{angle[p], angle[p + 1], angle[p + 2], angle[p + 3]}, sn, cs);
        for (std::size_t l = 0; l < 4 && p + l < grid.samples; ++l) {
          t.phase[2 * (p + l)] = static_cast<float>(cs[l]);
          t.phase[2 * (p + l) + 1] = static_cast<float>(sn[l]);
        }
      }
    }
  }
  return tree;
}

namespace {

// parent[p] (+)= phase_p · Σ_a w_pa child[first_p + a] over `width` floats ((re, im) pairs).
// W > 0: the width known at compile time.
template <std::size_t W>
void transfer(const FarFieldTree::Transfer& t, int points, const float* __restrict child, float* __restrict parent,
              std::size_t samples, std::size_t runtime_width, bool first_child, float* __restrict tmp) {
  const std::size_t width = W > 0 ? W : runtime_width;
  for (std::size_t p = 0; p < samples; ++p) {
    const float* __restrict y = child + static_cast<std::size_t>(t.first[p]) * width;
    const float* w = t.weight.data() + p * static_cast<std::size_t>(points);
    for (std::size_t k = 0; k < width; ++k) tmp[k] = w[0] * y[k];
    for (int a = 1; a < points; ++a) {
      const float* __restrict ya = y + static_cast<std::size_t>(a) * width;
      const float wa = w[a];
      for (std::size_t k = 0; k < width; ++k) tmp[k] = std::fma(wa, ya[k], tmp[k]);
    }
    const float pr = t.phase[2 * p], pi = t.phase[2 * p + 1];
    float* __restrict out = parent + p * width;
    // Explicit fused products: the same roundings in every lane whatever the width and the
    // compiler's contraction choices (one azimuth at a time gives the bits of all at once).
    if (first_child) {
      for (std::size_t k = 0; k < width; k += 2) {
        out[k] = std::fma(pr, tmp[k], -(pi * tmp[k + 1]));
        out[k + 1] = std::fma(pr, tmp[k + 1], pi * tmp[k]);
      }
    } else {
      for (std::size_t k = 0; k < width; k += 2) {
        out[k] += std::fma(pr, tmp[k], -(pi * tmp[k + 1]));
        out[k + 1] += std::fma(pr, tmp[k + 1], pi * tmp[k]);
      }
    }
  }
}

}  // namespace

void aggregate(const FarFieldTree& tree, const float* leaf_samples, std::size_t width,
               std::vector<std::vector<float>>& node_samples) {
  const std::size_t chunks = tree.chunks.size(), leaf_samples_per_chunk = tree.grids[0].samples;
  node_samples.resize(tree.nodes.size() - chunks);
  std::vector<float> tmp(width);
  for (std::size_t n = chunks; n < tree.nodes.size(); ++n) {
    const FarFieldTree::Node& node = tree.nodes[n];
    const std::size_t samples = tree.grids[node.grid].samples;
    std::vector<float>& out = node_samples[n - chunks];
    out.resize(samples * width);  // every entry written by the first child
    for (std::size_t c = 0; c < node.children.size(); ++c) {
      const FarFieldTree::Transfer& t = node.children[c];
      const float* child = t.child < chunks ? leaf_samples + t.child * leaf_samples_per_chunk * width
                                            : node_samples[t.child - chunks].data();
      const int points = tree.grid_points[tree.nodes[t.child].grid];
      if (width == 16) {
        transfer<16>(t, points, child, out.data(), samples, width, c == 0, tmp.data());
      } else {
        transfer<0>(t, points, child, out.data(), samples, width, c == 0, tmp.data());
      }
    }
  }
}

}  // namespace plumage::detail
