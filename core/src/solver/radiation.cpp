#include "radiation.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/conventions.hpp"
#include "plumage/error.hpp"
#include "plumage/simd_math.hpp"
#include "radiation_tree.hpp"
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

}  // namespace

// ê1 = (cos φ, 0, −sin φ), ê2 = (sin θ_i sin φ, cos θ_i, sin θ_i cos φ) per grid point, by component.
struct Polarizations {
  std::vector<double> e1x, e1z, e2x, e2y, e2z;
};

struct Radiator::Plan {
  std::span<const Vec2> vertices;
  std::span<const double> segment_length;
  double gamma0 = 0.0, theta_i_rad = 0.0;
  std::vector<std::span<const double>> target_phi;
  bool chunked = false;
  FarFieldTree tree;                                  // chunks, merge tree, grids (radiation_tree.hpp)
  std::vector<Stencil> stencils;                      // per target set, on the root's grid
  std::vector<OutgoingPhases> outgoing;               // per chunk, on the chunks' grid
  Polarizations polarization;                         // ê1, ê2 at the chunks' grid points
  std::vector<float> projected;                        // one group's projected samples
  // e^{−iγ0 ρ̂_j·r_root} per target set and direction (re, im).
  std::vector<std::vector<double>> root_phase;
  FactoredTentKernel kernel;
  bool single_precision = false;                       // ChunkingOptions::single_precision_gemm
  Eigen::MatrixXd kernel_split, product;               // [Re K; Im K] (2P × nodes), its product
  Eigen::MatrixXd amplitude_split;                     // one chunk's rows of one azimuth: [Re A | Im A]
  Eigen::MatrixXf kernel_split_f, product_f;           // the same in float
  Eigen::MatrixXf amplitude_split_f;
  // Every chunk's projected samples, [chunk][grid point][azimuth][output] (re, im), outputs
  // first_output … first_output + outputs − 1 of the union of the target sets, in float (they
  // carry the float GEMM's rounding already); the internal nodes' samples, [grid point][azimuth]
  // [output] (re, im).
  std::vector<float> rows;
  std::vector<std::vector<float>> node_samples;
  std::vector<float> chunk_acc;
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
  for (const int points : {options.stencil_points, options.merge_stencil_points}) {
    if (points < 4 || points > kMaxStencilPoints || points % 2 != 0)
      throw Error("radiate: stencil_points must be even, in [4, " + std::to_string(kMaxStencilPoints) + "]");
  }
  p.tree = far_field_tree(vertices, segment_length, gamma0, options, true);
  const std::size_t sets = p.target_phi.size(), chunks = p.tree.chunks.size();
  const SampleGrid& leaf = p.tree.grids.front();
  const Vec2 root = p.tree.root().centre;
  p.stencils.resize(sets);
  p.root_phase.resize(sets);
  std::vector<double> angle;
  for (std::size_t s = 0; s < sets; ++s) {
    p.stencils[s] = make_stencil(p.target_phi[s], p.tree.grids[p.tree.root().grid], p.tree.root_points());
    const Stencil& st = p.stencils[s];
    const std::size_t n_dir = p.target_phi[s].size();
    angle.assign(n_dir + 4, 0.0);
    for (std::size_t j = 0; j < n_dir; ++j) angle[j] = -gamma0 * (st.sin_phi[j] * root.x + st.cos_phi[j] * root.z);
    p.root_phase[s].resize(2 * (n_dir + 4));
    for (std::size_t j = 0; j < n_dir; j += 4) {
      simd::v4d sn, cs;
      simd::sincos(simd::v4d{angle[j], angle[j + 1], angle[j + 2], angle[j + 3]}, sn, cs);
      for (std::size_t l = 0; l < 4; ++l) {
        p.root_phase[s][2 * (j + l)] = cs[l];
        p.root_phase[s][2 * (j + l) + 1] = sn[l];
      }
    }
  }
  const double st = std::sin(theta_i_rad), ct = std::cos(theta_i_rad);
  Polarizations& pol = p.polarization;
  for (auto* v : {&pol.e1x, &pol.e1z, &pol.e2x, &pol.e2y, &pol.e2z}) v->clear();
  for (const double phi : leaf.phi) {
    const double sp = std::sin(phi), cp = std::cos(phi);
    pol.e1x.push_back(cp), pol.e1z.push_back(-sp);
    pol.e2x.push_back(st * sp), pol.e2y.push_back(ct), pol.e2z.push_back(st * cp);
  }
  p.outgoing.resize(chunks);
  for (std::size_t ci = 0; ci < chunks; ++ci) {
    const auto& c = p.tree.chunks[ci];
    p.outgoing[ci].build(vertices.subspan(c.first, c.count + 2), c.centre, gamma0, leaf.phi);
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
  const FarFieldTree tree = far_field_tree(vertices, segment_length, gamma0, options, false);
  const double samples = static_cast<double>(tree.grids.front().samples);
  const double chunks = static_cast<double>(tree.chunks.size());
  double node_points = 0.0;  // grid points of the internal nodes (their samples, transfers)
  for (std::size_t n = tree.chunks.size(); n < tree.nodes.size(); ++n)
    node_points += static_cast<double>(tree.grids[tree.nodes[n].grid].samples);
  const double stencil = static_cast<double>(kMaxStencilPoints);
  bytes += (verts + 2.0 * chunks) * samples * 16.0;                      // outgoing phases per chunk
  bytes += node_points * 3.0 * (4.0 + 4.0 * stencil + 8.0);            // transfers (≤ 3 children)
  // root stencils (first, weights, sin, cos) and phases
  bytes += (directions + 4.0 * static_cast<double>(target_sizes.size())) * (40.0 + 8.0 * stencil);
  bytes += 2.0 * samples * static_cast<double>(tree.max_count + 2) * 8.0 * 2.0;  // kernel_split, product
  bytes += static_cast<double>(tree.max_count) * 2.0 * c * 8.0;         // amplitude_split
  bytes += static_cast<double>(n_phi) * ((chunks * samples + node_points) * 4.0 + directions * 8.0) * 2.0 * outputs;
  bytes += static_cast<double>(tree.max_count + 2) * 8.0 * 13.0;      // the kernel's per-node buffers
  return bytes;
}

namespace {
// Project the six sums of each group on ê1, ê2 (radiation.hpp) at every grid point of a chunk's
// product [Re K; Im K]·[Re A | Im A] (azimuth a), into the chunk's rows (outputs q_lo …
// q_lo + outputs − 1). The sums are formed in double whatever the product's precision; one
// group at a time over all grid points (contiguous columns: vector loops), then scattered into
// the rows' [grid point][azimuth][output] layout.
template <class Matrix>
void project_samples(const Matrix& product, const Polarizations& pol, int q_lo, int outputs, std::size_t a,
                     std::size_t n_phi, float* __restrict rows, std::vector<float>& scratch) {
  using T = typename Matrix::Scalar;
  const Eigen::Index P = product.rows() / 2, columns = product.cols() / 2;
  const auto n = static_cast<std::size_t>(P);
  const int g_lo = q_lo / 2, g_hi = (q_lo + outputs + 1) / 2;
  const auto width = static_cast<std::size_t>(outputs) * 2;
  scratch.resize(4 * n);
  const double* __restrict e1x = pol.e1x.data();
  const double* __restrict e1z = pol.e1z.data();
  const double* __restrict e2x = pol.e2x.data();
  const double* __restrict e2y = pol.e2y.data();
  const double* __restrict e2z = pol.e2z.data();
  for (int g = g_lo; g < g_hi; ++g) {
    const Eigen::Index b = 6 * g;
    // Column c of Re K·Re A, Re K·Im A, Im K·Re A, Im K·Im A.
    auto rr = [&](int c) { return product.data() + (b + c) * 2 * P; };
    auto ri = [&](int c) { return product.data() + (columns + b + c) * 2 * P; };
    auto ir = [&](int c) { return product.data() + (b + c) * 2 * P + P; };
    auto ii = [&](int c) { return product.data() + (columns + b + c) * 2 * P + P; };
    const T *__restrict rr0 = rr(0), *__restrict rr1 = rr(1), *__restrict rr2 = rr(2), *__restrict rr3 = rr(3),
            *__restrict rr4 = rr(4), *__restrict rr5 = rr(5);
    const T *__restrict ri0 = ri(0), *__restrict ri1 = ri(1), *__restrict ri2 = ri(2), *__restrict ri3 = ri(3),
            *__restrict ri4 = ri(4), *__restrict ri5 = ri(5);
    const T *__restrict ir0 = ir(0), *__restrict ir1 = ir(1), *__restrict ir2 = ir(2), *__restrict ir3 = ir(3),
            *__restrict ir4 = ir(4), *__restrict ir5 = ir(5);
    const T *__restrict ii0 = ii(0), *__restrict ii1 = ii(1), *__restrict ii2 = ii(2), *__restrict ii3 = ii(3),
            *__restrict ii4 = ii(4), *__restrict ii5 = ii(5);
    float* __restrict o = scratch.data();
    for (std::size_t j = 0; j < n; ++j) {
      // s_c = Σ K·A (complex) for the six columns: (rr − ii) + i (ri + ir)
      const double s0r = double(rr0[j]) - double(ii0[j]), s0i = double(ri0[j]) + double(ir0[j]);
      const double s1r = double(rr1[j]) - double(ii1[j]), s1i = double(ri1[j]) + double(ir1[j]);
      const double s2r = double(rr2[j]) - double(ii2[j]), s2i = double(ri2[j]) + double(ir2[j]);
      const double s3r = double(rr3[j]) - double(ii3[j]), s3i = double(ri3[j]) + double(ir3[j]);
      const double s4r = double(rr4[j]) - double(ii4[j]), s4i = double(ri4[j]) + double(ir4[j]);
      const double s5r = double(rr5[j]) - double(ii5[j]), s5i = double(ri5[j]) + double(ir5[j]);
      // o1 = −ê1·S_J − ê2·S_M, o2 = −ê2·S_J + ê1·S_M (ê1 has no y component)
      const double e1jr = e1x[j] * s0r + e1z[j] * s2r, e1ji = e1x[j] * s0i + e1z[j] * s2i;
      const double e2jr = e2x[j] * s0r + e2y[j] * s1r + e2z[j] * s2r, e2ji = e2x[j] * s0i + e2y[j] * s1i + e2z[j] * s2i;
      const double e1mr = e1x[j] * s3r + e1z[j] * s5r, e1mi = e1x[j] * s3i + e1z[j] * s5i;
      const double e2mr = e2x[j] * s3r + e2y[j] * s4r + e2z[j] * s5r, e2mi = e2x[j] * s3i + e2y[j] * s4i + e2z[j] * s5i;
      o[4 * j] = static_cast<float>(-e1jr - e2mr);
      o[4 * j + 1] = static_cast<float>(-e1ji - e2mi);
      o[4 * j + 2] = static_cast<float>(-e2jr + e1mr);
      o[4 * j + 3] = static_cast<float>(-e2ji + e1mi);
    }
    const int k_first = std::max(2 * g, q_lo), k_end = std::min(2 * g + 2, q_lo + outputs);
    if (k_end <= k_first) continue;
    const auto copy = static_cast<std::size_t>(2 * (k_end - k_first));
    const float* from = o + 2 * (k_first - 2 * g);
    float* to = rows + a * width + static_cast<std::size_t>(2 * (k_first - q_lo));
    for (std::size_t j = 0; j < n; ++j) std::copy(from + 4 * j, from + 4 * j + copy, to + j * n_phi * width);
  }
}

// The root's samples of outputs [offset/2, offset/2 + O2/2) (O2 floats per azimuth, `stride`
// floats per grid point) interpolated to target set s and multiplied by e^{−iγ0 ρ̂_j·r_root}
// (in double), one direction at a time, into results[a · sets + s]. O2 > 0: known at compile
// time (four outputs: 8).
template <std::size_t O2>
void interpolate_root_impl(Radiator::Plan& p, std::size_t s, const float* root, std::size_t stride, std::size_t offset,
                           std::size_t runtime_o2, std::span<Eigen::MatrixXcd> results, std::size_t sets) {
  const std::size_t n_phi = results.size() / sets;
  const std::size_t o2 = O2 > 0 ? O2 : runtime_o2, width = n_phi * o2, per_azimuth = stride / n_phi;
  const Stencil& st = p.stencils[s];
  p.chunk_acc.resize(width);
  float* __restrict tmp = p.chunk_acc.data();
  const std::size_t n_dir = p.target_phi[s].size();
  for (std::size_t a = 0; a < n_phi; ++a) {
    results[a * sets + s].resize(static_cast<Eigen::Index>(n_dir), static_cast<Eigen::Index>(o2 / 2));
  }
  for (std::size_t j = 0; j < n_dir; ++j) {
    const auto& w = st.weight[j];
    for (std::size_t k = 0; k < width; ++k) tmp[k] = 0.0f;
    for (int pt = 0; pt < st.points; ++pt) {
      const auto point = static_cast<std::size_t>(st.first[j]) + static_cast<std::size_t>(pt);
      const float* __restrict y = root + point * stride + offset;
      const auto wa = static_cast<float>(w[static_cast<std::size_t>(pt)]);
      for (std::size_t a = 0; a < n_phi; ++a) {
        for (std::size_t k = 0; k < o2; ++k) tmp[a * o2 + k] += wa * y[a * per_azimuth + k];
      }
    }
    const double pr = p.root_phase[s][2 * j], pi = p.root_phase[s][2 * j + 1];
    for (std::size_t a = 0; a < n_phi; ++a) {
      Eigen::MatrixXcd& r = results[a * sets + s];
      for (std::size_t q = 0; q < o2 / 2; ++q) {
        const double re = tmp[a * o2 + 2 * q], im = tmp[a * o2 + 2 * q + 1];
        r(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(q)) = Complex(pr * re - pi * im, pr * im + pi * re);
      }
    }
  }
}

void interpolate_root(Radiator::Plan& p, std::size_t s, const float* root, std::size_t stride, std::size_t offset,
                      std::size_t o2, std::span<Eigen::MatrixXcd> results, std::size_t sets) {
  if (o2 == 8) return interpolate_root_impl<8>(p, s, root, stride, offset, o2, results, sets);
  interpolate_root_impl<0>(p, s, root, stride, offset, o2, results, sets);
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
  const std::size_t samples = p.tree.grids.front().samples, chunks = p.tree.chunks.size();
  for (std::size_t a = 0; a < n_phi; ++a) {
    if (amplitudes[a].cols() != columns) throw Error("radiate: azimuths differ in current columns");
  }
  // The outputs any target set wants, merged up the tree together.
  int q_lo = layout.front().first_output, q_hi = q_lo;
  for (const RadiationTargets& t : layout) {
    q_lo = std::min(q_lo, t.first_output);
    q_hi = std::max(q_hi, t.first_output + t.outputs);
  }
  const int outputs = q_hi - q_lo;
  const std::size_t stride = n_phi * 2 * static_cast<std::size_t>(outputs);  // floats per grid point
  // Every entry of rows is written before it is read: no clearing.
  p.rows.resize(chunks * samples * stride);
  for (std::size_t ci = 0; ci < chunks; ++ci) {
    const auto& c = p.tree.chunks[ci];
    const std::size_t v0 = c.first, nv = c.count + 2;
    float* rows = p.rows.data() + ci * samples * stride;
    for (std::size_t a = 0; a < n_phi; ++a) {
      // Real arithmetic: [Re K; Im K]·[Re A | Im A] holds the four real products of K·A. The
      // chunk's rows are split (and rounded) here, into a buffer that stays in cache for the GEMM.
      const auto rows_a =
          amplitudes[a].middleRows(static_cast<Eigen::Index>(c.first), static_cast<Eigen::Index>(c.count));
      if (p.single_precision) {
        p.amplitude_split_f.resize(rows_a.rows(), 2 * columns);
        p.amplitude_split_f.leftCols(columns) = rows_a.real().cast<float>();
        p.amplitude_split_f.rightCols(columns) = rows_a.imag().cast<float>();
        p.kernel.build(p.outgoing[ci], p.segment_length.subspan(v0, nv - 1),
                       std::span<const double>(chi[a]).subspan(v0, nv), p.kernel_split_f);
        p.product_f.noalias() = p.kernel_split_f * p.amplitude_split_f;
        project_samples(p.product_f, p.polarization, q_lo, outputs, a, n_phi, rows, p.projected);
      } else {
        p.amplitude_split.resize(rows_a.rows(), 2 * columns);
        p.amplitude_split.leftCols(columns) = rows_a.real();
        p.amplitude_split.rightCols(columns) = rows_a.imag();
        p.kernel.build(p.outgoing[ci], p.segment_length.subspan(v0, nv - 1),
                       std::span<const double>(chi[a]).subspan(v0, nv), p.kernel_split);
        p.product.noalias() = p.kernel_split * p.amplitude_split;
        project_samples(p.product, p.polarization, q_lo, outputs, a, n_phi, rows, p.projected);
      }
    }
  }
  aggregate(p.tree, p.rows.data(), stride, p.node_samples);
  const float* root = chunks == 1 ? p.rows.data() : p.node_samples.back().data();
  for (std::size_t s = 0; s < sets; ++s) {
    interpolate_root(p, s, root, stride, 2 * static_cast<std::size_t>(layout[s].first_output - q_lo),
                     2 * static_cast<std::size_t>(layout[s].outputs), results, sets);
  }
}

}  // namespace plumage::detail
