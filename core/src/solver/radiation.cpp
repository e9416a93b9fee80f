#include "radiation.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/simd_math.hpp"
#include "tent_kernel.hpp"

namespace plumage::detail {

namespace {

// Directions per exact-kernel block: the block (nodes × 64 complex ≈ 1.4 MB for 1350 nodes)
// stays in cache while the GEMM reads it.
constexpr std::size_t kDirectionBlock = 64;

// Rows of `sums` (directions, 6 columns per group) → the two projected outputs per group.
void project_rows(const Eigen::MatrixXcd& sums, std::span<const double> phi_o_rad, double theta_i_rad,
                  int groups, Eigen::MatrixXcd& out) {
  const double st = std::sin(theta_i_rad), ct = std::cos(theta_i_rad);
  out.resize(sums.rows(), 2 * groups);
  for (Eigen::Index j = 0; j < sums.rows(); ++j) {
    const double sp = std::sin(phi_o_rad[static_cast<std::size_t>(j)]);
    const double cp = std::cos(phi_o_rad[static_cast<std::size_t>(j)]);
    const double e1[3] = {cp, 0.0, -sp};
    const double e2[3] = {st * sp, ct, st * cp};
    for (int g = 0; g < groups; ++g) {
      const Eigen::Index c = 6 * g;
      const Complex e1j = e1[0] * sums(j, c) + e1[2] * sums(j, c + 2);
      const Complex e2j = e2[0] * sums(j, c) + e2[1] * sums(j, c + 1) + e2[2] * sums(j, c + 2);
      const Complex e1m = e1[0] * sums(j, c + 3) + e1[2] * sums(j, c + 5);
      const Complex e2m = e2[0] * sums(j, c + 3) + e2[1] * sums(j, c + 4) + e2[2] * sums(j, c + 5);
      out(j, 2 * g) = -e1j - e2m;
      out(j, 2 * g + 1) = -e2j + e1m;
    }
  }
}

void radiate_exact(std::span<const Vec2> vertices, std::span<const double> segment_length,
                   std::span<const double> chi, double gamma0, double theta_i_rad,
                   const Eigen::MatrixXcd& amplitudes, std::span<const RadiationTargets> targets) {
  TentKernel kernel(vertices.size());
  Eigen::MatrixXcd kt, sums, projected;
  for (const RadiationTargets& t : targets) {
    const int g0 = t.first_output / 2;
    const int groups = (t.first_output + t.outputs + 1) / 2 - g0;
    const auto n_dir = static_cast<Eigen::Index>(t.phi_o_rad.size());
    t.result->resize(n_dir, t.outputs);
    for (std::size_t j0 = 0; j0 < t.phi_o_rad.size(); j0 += kDirectionBlock) {
      const std::size_t nb = std::min(kDirectionBlock, t.phi_o_rad.size() - j0);
      const auto phis = t.phi_o_rad.subspan(j0, nb);
      kernel.build(vertices, segment_length, chi, {0.0, 0.0}, gamma0, phis, kt);
      sums.noalias() = kt.transpose() * amplitudes.middleCols(6 * g0, 6 * groups);
      project_rows(sums, phis, theta_i_rad, groups, projected);
      t.result->middleRows(static_cast<Eigen::Index>(j0), static_cast<Eigen::Index>(nb)) =
          projected.middleCols(t.first_output - 2 * g0, t.outputs);
    }
  }
}

// N-point Lagrange stencil on the uniform grid φ_p = lo + p·step (N even: the target between
// the stencil's two middle points).
struct Stencil {
  int points = 6;
  std::vector<Eigen::Index> first;
  std::vector<std::array<double, kMaxStencilPoints>> weight;
  std::vector<double> sin_phi, cos_phi;
};

Stencil make_stencil(std::span<const double> phi_o_rad, double lo, double step, int points) {
  Stencil s;
  s.points = points;
  const int half = points / 2;
  for (const double phi : phi_o_rad) {
    const double t = (phi - lo) / step;
    const double base = std::floor(t) - (half - 1);
    const double f = t - base;  // in [half − 1, half): position among nodes 0 … points − 1
    std::array<double, kMaxStencilPoints> w{};
    for (int a = 0; a < points; ++a) {
      double num = 1.0, den = 1.0;
      for (int b = 0; b < points; ++b) {
        if (b == a) continue;
        num *= f - b;
        den *= a - b;
      }
      w[a] = num / den;
    }
    s.first.push_back(static_cast<Eigen::Index>(base));
    s.weight.push_back(w);
    s.sin_phi.push_back(std::sin(phi));
    s.cos_phi.push_back(std::cos(phi));
  }
  return s;
}

// Chunks of the polyline: node ranges and their centres; the sampling grid over (−π/2, π/2).
struct ChunkLayout {
  struct Chunk {
    std::size_t first, count;
    Vec2 centre;
  };
  std::vector<Chunk> chunks;
  std::size_t max_count = 0, samples = 0;
  double lo = 0.0, step = 0.0;
  std::vector<double> grid;
};

ChunkLayout chunk_layout(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
                         const ChunkingOptions& options) {
  ChunkLayout layout;
  const std::size_t nodes = vertices.size() - 2;
  double total = 0.0;
  for (const double h : segment_length) total += h;
  const double mean_h = total / static_cast<double>(segment_length.size());
  const auto per_chunk = static_cast<std::size_t>(
      std::max(8.0, std::round(2.0 * options.chunk_phase / std::max(gamma0 * mean_h, 1e-12))));
  // Chunk sizes as equal as possible and palindromic, so that a mirrored barbule is cut into
  // the mirrored chunks.
  std::size_t count = (nodes + per_chunk - 1) / per_chunk;
  if (count % 2 == 0 && nodes % 2 == 1) ++count;
  std::vector<std::size_t> sizes(count, nodes / count);
  std::size_t extra = nodes % count;
  if (extra % 2 == 1) ++sizes[count / 2], --extra;  // count is odd here
  for (std::size_t k = 0; k < extra / 2; ++k) ++sizes[k], ++sizes[count - 1 - k];
  double band = 0.0;
  for (std::size_t k = 0, m0 = 0; k < count; m0 += sizes[k], ++k) {
    ChunkLayout::Chunk c{m0, sizes[k], {}};
    // Tent supports of nodes m0 … m0+count−1 span vertices m0 … m0+count+1.
    double x_lo = vertices[m0].x, x_hi = x_lo, z_lo = vertices[m0].z, z_hi = z_lo;
    for (std::size_t k = m0; k <= m0 + c.count + 1; ++k) {
      x_lo = std::min(x_lo, vertices[k].x), x_hi = std::max(x_hi, vertices[k].x);
      z_lo = std::min(z_lo, vertices[k].z), z_hi = std::max(z_hi, vertices[k].z);
    }
    c.centre = {0.5 * (x_lo + x_hi), 0.5 * (z_lo + z_hi)};
    double radius = 0.0;
    for (std::size_t k = m0; k <= m0 + c.count + 1; ++k) radius = std::max(radius, norm(vertices[k] - c.centre));
    // Jacobi–Anger: |J_n(x)| for n ≥ x + 7 x^{1/3} + 8 is below ~1e-10 of the peak; the
    // projection on ê1, ê2 adds two more orders.
    const double x = gamma0 * radius;
    band = std::max(band, x + 7.0 * std::cbrt(x) + 10.0);
    layout.chunks.push_back(c);
    layout.max_count = std::max(layout.max_count, c.count);
  }
  // A whole number of steps across (−π/2, π/2), so that the grid is symmetric about 0 and a
  // mirrored barbule sees the mirrored grid; half a stencil of padding beyond each end.
  const double intervals = std::ceil(options.oversampling * band);
  const double pad = 0.5 * options.stencil_points;
  layout.step = kPi / intervals;
  layout.lo = -0.5 * kPi - pad * layout.step;
  layout.samples = static_cast<std::size_t>(intervals) + static_cast<std::size_t>(options.stencil_points) + 1;
  layout.grid.resize(layout.samples);
  for (std::size_t p = 0; p < layout.samples; ++p) {
    layout.grid[p] = layout.step * (static_cast<double>(p) - pad - 0.5 * intervals);
  }
  return layout;
}

}  // namespace

struct Radiator::Plan {
  std::span<const Vec2> vertices;
  std::span<const double> segment_length;
  double gamma0 = 0.0, theta_i_rad = 0.0;
  std::vector<std::span<const double>> target_phi;
  bool chunked = false;
  ChunkLayout layout;
  std::vector<Stencil> stencils;                      // per target set
  std::vector<OutgoingPhases> outgoing;               // per chunk, on the sampling grid
  std::vector<std::array<double, 3>> e1, e2;          // polarization directions at the grid points
  // e^{−iγ0 ρ̂_j·r_c} per chunk and target set, directions padded to a multiple of 4.
  std::vector<std::vector<std::vector<double>>> phase_re, phase_im;
  // The same per target set, direction-major: [direction][chunk] (re, im), as the interpolation reads them.
  std::vector<std::vector<double>> phase_by_direction;
  FactoredTentKernel kernel;
  bool single_precision = false;                       // ChunkingOptions::single_precision_gemm
  Eigen::MatrixXd kernel_split, product;               // [Re K; Im K] (2P × nodes), its product
  std::vector<Eigen::MatrixXd> amplitude_split;        // per azimuth: [Re A | Im A]
  Eigen::MatrixXf kernel_split_f, product_f;           // the same in float
  std::vector<Eigen::MatrixXf> amplitude_split_f;
  // Per target set: every chunk's projected samples, [chunk][grid point][azimuth][output] (re, im),
  // in float (they carry the float GEMM's rounding already); the interpolated far field,
  // [direction][azimuth][output] (re, im), summed over the chunks in double.
  std::vector<std::vector<float>> rows;
  std::vector<std::vector<double>> accumulated;
  std::vector<float> chunk_acc;
  std::vector<double> acc;
};

namespace {
// One spare plan per thread: its buffers (a few MB for a production barbule) are reused by the
// next solve() instead of being mapped and faulted in again.
thread_local std::unique_ptr<Radiator::Plan> spare_plan;
}  // namespace

Radiator::Radiator(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
                   double theta_i_rad, std::vector<std::span<const double>> target_phi_o_rad,
                   const ChunkingOptions& options)
    : plan_(spare_plan ? std::move(spare_plan) : std::make_unique<Plan>()) {
  if (vertices.size() < 3) throw Error("radiate: a polyline needs at least 3 vertices");
  Plan& p = *plan_;
  p.vertices = vertices;
  p.segment_length = segment_length;
  p.gamma0 = gamma0;
  p.theta_i_rad = theta_i_rad;
  p.target_phi = std::move(target_phi_o_rad);
  bool on_cone = true;
  for (const auto& phis : p.target_phi) {
    for (const double phi : phis) on_cone = on_cone && std::abs(phi) <= 0.5 * kPi;
  }
  p.chunked = options.chunked && on_cone;
  p.single_precision = options.single_precision_gemm;
  if (!p.chunked) return;
  p.layout = chunk_layout(vertices, segment_length, gamma0, options);
  const std::size_t sets = p.target_phi.size(), chunks = p.layout.chunks.size();
  p.stencils.resize(sets);
  if (options.stencil_points < 4 || options.stencil_points > kMaxStencilPoints || options.stencil_points % 2 != 0)
    throw Error("radiate: stencil_points must be even, in [4, " + std::to_string(kMaxStencilPoints) + "]");
  for (std::size_t s = 0; s < sets; ++s)
    p.stencils[s] = make_stencil(p.target_phi[s], p.layout.lo, p.layout.step, options.stencil_points);
  const double st = std::sin(theta_i_rad), ct = std::cos(theta_i_rad);
  p.e1.clear(), p.e2.clear();
  for (const double phi : p.layout.grid) {
    const double sp = std::sin(phi), cp = std::cos(phi);
    p.e1.push_back({cp, 0.0, -sp});
    p.e2.push_back({st * sp, ct, st * cp});
  }
  p.outgoing.resize(chunks);
  p.phase_re.resize(chunks);
  p.phase_im.resize(chunks);
  std::vector<double> angle;
  for (std::size_t ci = 0; ci < chunks; ++ci) {
    const auto& c = p.layout.chunks[ci];
    p.outgoing[ci].build(vertices.subspan(c.first, c.count + 2), c.centre, gamma0, p.layout.grid);
    p.phase_re[ci].resize(sets);
    p.phase_im[ci].resize(sets);
    for (std::size_t s = 0; s < sets; ++s) {
      const Stencil& st = p.stencils[s];
      const std::size_t n_dir = p.target_phi[s].size();
      std::vector<double>& pr = p.phase_re[ci][s];
      std::vector<double>& pi = p.phase_im[ci][s];
      angle.assign(n_dir + 4, 0.0);
      pr.resize(n_dir + 4);
      pi.resize(n_dir + 4);
      for (std::size_t j = 0; j < n_dir; ++j) {
        angle[j] = -gamma0 * (st.sin_phi[j] * c.centre.x + st.cos_phi[j] * c.centre.z);
      }
      for (std::size_t j = 0; j < n_dir; j += 4) {
        simd::v4d sn, cs;
        simd::sincos(simd::v4d{angle[j], angle[j + 1], angle[j + 2], angle[j + 3]}, sn, cs);
        for (int l = 0; l < 4; ++l) pr[j + l] = cs[l], pi[j + l] = sn[l];
      }
    }
  }
  p.phase_by_direction.resize(sets);
  for (std::size_t s = 0; s < sets; ++s) {
    const std::size_t n_dir = p.target_phi[s].size();
    std::vector<double>& by = p.phase_by_direction[s];
    by.resize(n_dir * chunks * 2);
    for (std::size_t j = 0; j < n_dir; ++j) {
      for (std::size_t ci = 0; ci < chunks; ++ci) {
        by[2 * (j * chunks + ci)] = p.phase_re[ci][s][j];
        by[2 * (j * chunks + ci) + 1] = p.phase_im[ci][s][j];
      }
    }
  }
}

double Radiator::estimate_bytes(std::span<const Vec2> vertices, std::span<const double> segment_length, double gamma0,
                                std::span<const std::size_t> target_sizes, bool on_cone, const ChunkingOptions& options,
                                std::size_t n_phi, std::size_t columns) {
  const double verts = static_cast<double>(vertices.size()), c = static_cast<double>(columns);
  double directions = 0.0;
  for (const std::size_t n : target_sizes) directions += static_cast<double>(n);
  const double outputs = c / 3.0;  // two outputs per group of six columns
  double bytes = static_cast<double>(n_phi) * directions * outputs * 16.0;  // results
  if (!options.chunked || !on_cone || vertices.size() < 3) {
    // the exact sum: one kernel block of kDirectionBlock directions and its products at a time
    const double block = static_cast<double>(kDirectionBlock);
    return bytes + verts * block * 16.0 * 2.0 + block * c * 16.0 * 2.0 + verts * 8.0 * 12.0;
  }
  const ChunkLayout layout = chunk_layout(vertices, segment_length, gamma0, options);
  const double samples = static_cast<double>(layout.samples), chunks = static_cast<double>(layout.chunks.size());
  bytes += (verts + 2.0 * chunks) * samples * 16.0;                      // outgoing phases per chunk
  bytes += chunks * (directions + 4.0 * static_cast<double>(target_sizes.size())) * 16.0;  // chunk phases
  bytes += 2.0 * samples * static_cast<double>(layout.max_count + 2) * 8.0 * 2.0;  // kernel_split, product
  bytes += static_cast<double>(n_phi) * (verts - 2.0) * 2.0 * c * 8.0;  // amplitude_split
  bytes += static_cast<double>(n_phi) * (chunks * samples * 4.0 + directions * 8.0) * 2.0 * outputs;  // rows, accumulated
  bytes += static_cast<double>(layout.max_count + 2) * 8.0 * 13.0;      // the kernel's per-node buffers
  return bytes;
}

namespace {
// Project the six sums of each group on ê1, ê2 (radiation.hpp) at every grid point of a chunk's
// product [Re K; Im K]·[Re A | Im A] (azimuth a), into the rows of each target set that wants
// those outputs. The sums are formed in double whatever the product's precision.
template <class Matrix>
void project_samples(const Matrix& product, const std::vector<std::array<double, 3>>& e1s,
                     const std::vector<std::array<double, 3>>& e2s, int groups, std::size_t a, std::size_t n_phi,
                     std::size_t chunk, std::span<const RadiationTargets> layout, std::vector<std::vector<float>>& rows) {
  const Eigen::Index P = product.rows() / 2, columns = product.cols() / 2;
  const std::size_t sets = layout.size();
  for (Eigen::Index j = 0; j < P; ++j) {
    const auto& e1 = e1s[static_cast<std::size_t>(j)];
    const auto& e2 = e2s[static_cast<std::size_t>(j)];
    auto sum = [&](Eigen::Index col) {
      const double rr = product(j, col), ii = product(P + j, columns + col);
      const double ri = product(j, columns + col), ir = product(P + j, col);
      return Complex(rr - ii, ri + ir);
    };
    for (int g = 0; g < groups; ++g) {
      const Eigen::Index b = 6 * g;
      const Complex s0 = sum(b), s1 = sum(b + 1), s2 = sum(b + 2), s3 = sum(b + 3), s4 = sum(b + 4), s5 = sum(b + 5);
      const Complex e1j = e1[0] * s0 + e1[2] * s2;
      const Complex e2j = e2[0] * s0 + e2[1] * s1 + e2[2] * s2;
      const Complex e1m = e1[0] * s3 + e1[2] * s5;
      const Complex e2m = e2[0] * s3 + e2[1] * s4 + e2[2] * s5;
      const Complex o[2] = {-e1j - e2m, -e2j + e1m};
      for (int h = 0; h < 2; ++h) {
        const int q = 2 * g + h;
        for (std::size_t s = 0; s < sets; ++s) {
          const int k = q - layout[s].first_output;
          if (k < 0 || k >= layout[s].outputs) continue;
          const std::size_t outputs = static_cast<std::size_t>(layout[s].outputs);
          const std::size_t at =
              2 * (((chunk * static_cast<std::size_t>(P) + static_cast<std::size_t>(j)) * n_phi + a) * outputs +
                   static_cast<std::size_t>(k));
          rows[s][at] = static_cast<float>(o[h].real());
          rows[s][at + 1] = static_cast<float>(o[h].imag());
        }
      }
    }
  }
}

// W > 0: the width known at compile time (one azimuth: 8 floats per grid point), so that the
// short loops are single vector operations.
template <std::size_t W>
void interpolate_chunks_impl(Radiator::Plan& p, std::size_t s, std::size_t runtime_width) {
  const std::size_t width = W > 0 ? W : runtime_width;
  const Stencil& st = p.stencils[s];
  const std::size_t n_dir = p.target_phi[s].size(), chunks = p.layout.chunks.size(), samples = p.layout.samples;
  p.chunk_acc.resize(width);
  p.acc.resize(width);
  float* __restrict tmp = p.chunk_acc.data();
  double* __restrict acc = p.acc.data();
  const float* rows = p.rows[s].data();
  for (std::size_t j = 0; j < n_dir; ++j) {
    const auto& w = st.weight[j];
    const double* phase = p.phase_by_direction[s].data() + 2 * j * chunks;
    for (std::size_t k = 0; k < width; ++k) acc[k] = 0.0;
    for (std::size_t ci = 0; ci < chunks; ++ci) {
      const float* __restrict y = rows + (ci * samples + static_cast<std::size_t>(st.first[j])) * width;
      for (std::size_t k = 0; k < width; ++k) tmp[k] = 0.0f;
      for (int a = 0; a < st.points; ++a) {
        const float* __restrict ya = y + static_cast<std::size_t>(a) * width;
        const auto wa = static_cast<float>(w[a]);
        for (std::size_t k = 0; k < width; ++k) tmp[k] += wa * ya[k];
      }
      const double pr = phase[2 * ci], pi = phase[2 * ci + 1];
      for (std::size_t k = 0; k < width; k += 2) {
        const double re = tmp[k], im = tmp[k + 1];
        acc[k] += pr * re - pi * im;
        acc[k + 1] += pr * im + pi * re;
      }
    }
    std::copy(acc, acc + width, p.accumulated[s].data() + j * width);
  }
}

// Every chunk's samples of target set s interpolated to the set's directions (the stencils are
// the same for all chunks: one grid) and summed with the chunks' phases e^{−iγ0 ρ̂_j·r_c}, one
// direction at a time (its sum stays in cache; `accumulated` is written once). `width` floats per
// grid point: [azimuth][output] (re, im).
void interpolate_chunks(Radiator::Plan& p, std::size_t s, std::size_t width) {
  if (width == 8) return interpolate_chunks_impl<8>(p, s, width);
  interpolate_chunks_impl<0>(p, s, width);
}

// accumulated[s] ([direction][azimuth][output] (re, im)) → results[a · sets + s].
void copy_results(const std::vector<std::vector<double>>& accumulated, std::span<const RadiationTargets> layout,
                  std::size_t n_phi, std::vector<Eigen::MatrixXcd>& results) {
  const std::size_t sets = layout.size();
  for (std::size_t a = 0; a < n_phi; ++a) {
    for (std::size_t s = 0; s < sets; ++s) {
      const std::size_t n_dir = layout[s].phi_o_rad.size(), outputs = static_cast<std::size_t>(layout[s].outputs);
      Eigen::MatrixXcd& r = results[a * sets + s];
      r.resize(static_cast<Eigen::Index>(n_dir), static_cast<Eigen::Index>(outputs));
      for (std::size_t j = 0; j < n_dir; ++j) {
        const double* v = accumulated[s].data() + 2 * ((j * n_phi + a) * outputs);
        for (std::size_t q = 0; q < outputs; ++q) {
          r(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(q)) = Complex(v[2 * q], v[2 * q + 1]);
        }
      }
    }
  }
}
}  // namespace

Radiator::~Radiator() {
  if (plan_) spare_plan = std::move(plan_);
}

void Radiator::radiate_all(std::span<const std::vector<double>> chi, std::span<const Eigen::MatrixXcd> amplitudes,
                           std::span<const RadiationTargets> layout, std::vector<Eigen::MatrixXcd>& results) {
  Plan& p = *plan_;
  const std::size_t n_phi = chi.size(), sets = layout.size();
  if (amplitudes.size() != n_phi || sets != p.target_phi.size()) throw Error("radiate: targets differ from the plan's");
  for (std::size_t s = 0; s < sets; ++s) {
    const RadiationTargets& t = layout[s];
    if (t.phi_o_rad.data() != p.target_phi[s].data() || t.phi_o_rad.size() != p.target_phi[s].size())
      throw Error("radiate: targets differ from the plan's");
    for (const Eigen::MatrixXcd& a : amplitudes) {
      if (t.outputs < 1 || t.outputs > 16 || t.first_output < 0 || t.first_output + t.outputs > 2 * a.cols() / 6) {
        throw Error("radiate: target outputs out of range");
      }
    }
  }
  results.resize(n_phi * sets);
  if (!p.chunked) {
    for (std::size_t a = 0; a < n_phi; ++a) {
      std::vector<RadiationTargets> targets(layout.begin(), layout.end());
      for (std::size_t s = 0; s < sets; ++s) targets[s].result = &results[a * sets + s];
      radiate_exact(p.vertices, p.segment_length, chi[a], p.gamma0, p.theta_i_rad, amplitudes[a], targets);
    }
    return;
  }
  const auto columns = amplitudes.front().cols();
  const int groups = static_cast<int>(columns / 6);
  const std::size_t samples = p.layout.samples;
  p.amplitude_split.resize(n_phi);
  p.amplitude_split_f.resize(n_phi);
  for (std::size_t a = 0; a < n_phi; ++a) {
    if (amplitudes[a].cols() != columns) throw Error("radiate: azimuths differ in current columns");
    if (p.single_precision) {
      p.amplitude_split_f[a].resize(amplitudes[a].rows(), 2 * columns);
      p.amplitude_split_f[a].leftCols(columns) = amplitudes[a].real().cast<float>();
      p.amplitude_split_f[a].rightCols(columns) = amplitudes[a].imag().cast<float>();
    } else {
      p.amplitude_split[a].resize(amplitudes[a].rows(), 2 * columns);
      p.amplitude_split[a].leftCols(columns) = amplitudes[a].real();
      p.amplitude_split[a].rightCols(columns) = amplitudes[a].imag();
    }
  }
  p.rows.resize(sets);
  p.accumulated.resize(sets);
  for (std::size_t s = 0; s < sets; ++s) {
    // Every entry of rows is written before it is read, every entry of accumulated once: no clearing.
    const std::size_t width = n_phi * 2 * static_cast<std::size_t>(layout[s].outputs);
    p.rows[s].resize(p.layout.chunks.size() * samples * width);
    p.accumulated[s].resize(layout[s].phi_o_rad.size() * width);
  }
  for (std::size_t ci = 0; ci < p.layout.chunks.size(); ++ci) {
    const auto& c = p.layout.chunks[ci];
    const std::size_t v0 = c.first, nv = c.count + 2;
    for (std::size_t a = 0; a < n_phi; ++a) {
      // Real arithmetic: [Re K; Im K]·[Re A | Im A] holds the four real products of K·A.
      if (p.single_precision) {
        p.kernel.build(p.outgoing[ci], p.segment_length.subspan(v0, nv - 1),
                       std::span<const double>(chi[a]).subspan(v0, nv), p.kernel_split_f);
        p.product_f.noalias() = p.kernel_split_f * p.amplitude_split_f[a].middleRows(
                                                       static_cast<Eigen::Index>(c.first), static_cast<Eigen::Index>(c.count));
        project_samples(p.product_f, p.e1, p.e2, groups, a, n_phi, ci, layout, p.rows);
      } else {
        p.kernel.build(p.outgoing[ci], p.segment_length.subspan(v0, nv - 1),
                       std::span<const double>(chi[a]).subspan(v0, nv), p.kernel_split);
        p.product.noalias() = p.kernel_split * p.amplitude_split[a].middleRows(static_cast<Eigen::Index>(c.first),
                                                                             static_cast<Eigen::Index>(c.count));
        project_samples(p.product, p.e1, p.e2, groups, a, n_phi, ci, layout, p.rows);
      }
    }
  }
  for (std::size_t s = 0; s < sets; ++s) interpolate_chunks(p, s, n_phi * 2 * static_cast<std::size_t>(layout[s].outputs));
  copy_results(p.accumulated, layout, n_phi, results);
}

}  // namespace plumage::detail
