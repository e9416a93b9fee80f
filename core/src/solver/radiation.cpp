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

// 6-point Lagrange stencil on the uniform grid φ_p = lo + p·step.
struct Stencil {
  std::vector<Eigen::Index> first;
  std::vector<std::array<double, 6>> weight;
  std::vector<double> sin_phi, cos_phi;
};

Stencil make_stencil(std::span<const double> phi_o_rad, double lo, double step) {
  Stencil s;
  for (const double phi : phi_o_rad) {
    const double t = (phi - lo) / step;
    const double base = std::floor(t) - 2.0;
    const double f = t - base;  // in [2, 3): position among nodes 0…5
    std::array<double, 6> w{};
    for (int a = 0; a < 6; ++a) {
      double num = 1.0, den = 1.0;
      for (int b = 0; b < 6; ++b) {
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

void radiate_chunked(std::span<const Vec2> vertices, std::span<const double> segment_length,
                     std::span<const double> chi, double gamma0, double theta_i_rad,
                     const Eigen::MatrixXcd& amplitudes, std::span<const RadiationTargets> targets,
                     const ChunkingOptions& options) {
  const std::size_t nodes = vertices.size() - 2;
  const int groups = static_cast<int>(amplitudes.cols() / 6);
  double total = 0.0;
  for (const double h : segment_length) total += h;
  const double mean_h = total / static_cast<double>(segment_length.size());
  const auto per_chunk = static_cast<std::size_t>(
      std::max(8.0, std::round(2.0 * options.chunk_phase / std::max(gamma0 * mean_h, 1e-12))));

  // Chunks: node ranges, their centres and their band limits.
  struct Chunk {
    std::size_t first, count;
    Vec2 centre;
  };
  // Chunk sizes as equal as possible and palindromic, so that a mirrored barbule is cut into
  // the mirrored chunks.
  std::size_t count = (nodes + per_chunk - 1) / per_chunk;
  if (count % 2 == 0 && nodes % 2 == 1) ++count;
  std::vector<std::size_t> sizes(count, nodes / count);
  std::size_t extra = nodes % count;
  if (extra % 2 == 1) ++sizes[count / 2], --extra;  // count is odd here
  for (std::size_t k = 0; k < extra / 2; ++k) ++sizes[k], ++sizes[count - 1 - k];
  std::vector<Chunk> chunks;
  double band = 0.0;
  for (std::size_t k = 0, m0 = 0; k < count; m0 += sizes[k], ++k) {
    Chunk c{m0, sizes[k], {}};
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
    chunks.push_back(c);
  }
  // A whole number of steps across (−π/2, π/2), so that the grid is symmetric about 0 and a
  // mirrored barbule sees the mirrored grid.
  const double intervals = std::ceil(options.oversampling * band);
  const double step = kPi / intervals;
  const double lo = -0.5 * kPi - 3.0 * step;
  const auto samples = static_cast<std::size_t>(intervals) + 7;
  std::vector<double> grid(samples);
  for (std::size_t p = 0; p < samples; ++p) {
    grid[p] = step * (static_cast<double>(p) - 3.0 - 0.5 * intervals);
  }

  std::vector<Stencil> stencils;
  std::vector<std::vector<Complex>> accumulated;  // per target set, row-major (direction, output)
  for (const RadiationTargets& t : targets) {
    stencils.push_back(make_stencil(t.phi_o_rad, lo, step));
    accumulated.emplace_back(t.phi_o_rad.size() * static_cast<std::size_t>(t.outputs), Complex(0.0, 0.0));
  }

  TentKernel kernel(*std::max_element(sizes.begin(), sizes.end()) + 2);
  Eigen::MatrixXcd kt, sums, projected;
  // The projected samples of one chunk, row-major: all outputs of a grid point side by side, so
  // that one stencil serves every output.
  std::vector<double> rows;
  const int outputs = 2 * groups;
  std::vector<double> angle, phase_re, phase_im;
  for (const Chunk& c : chunks) {
    const std::size_t v0 = c.first, nv = c.count + 2;
    kernel.build(vertices.subspan(v0, nv), segment_length.subspan(v0, nv - 1), chi.subspan(v0, nv),
                 c.centre, gamma0, grid, kt);
    sums.noalias() = kt.transpose() * amplitudes.middleRows(static_cast<Eigen::Index>(c.first),
                                                            static_cast<Eigen::Index>(c.count));
    project_rows(sums, grid, theta_i_rad, groups, projected);
    rows.resize(samples * 2 * static_cast<std::size_t>(outputs));
    for (std::size_t p = 0; p < samples; ++p) {
      for (int q = 0; q < outputs; ++q) {
        const Complex y = projected(static_cast<Eigen::Index>(p), q);
        rows[2 * (p * outputs + q)] = y.real();
        rows[2 * (p * outputs + q) + 1] = y.imag();
      }
    }
    for (std::size_t s = 0; s < targets.size(); ++s) {
      const RadiationTargets& t = targets[s];
      const Stencil& st = stencils[s];
      const std::size_t n_dir = t.phi_o_rad.size();
      // e^{−iγ0 ρ̂_j·r_c}, four directions at a time.
      angle.assign(n_dir + 4, 0.0);
      phase_re.resize(n_dir + 4), phase_im.resize(n_dir + 4);
      for (std::size_t j = 0; j < n_dir; ++j) {
        angle[j] = -gamma0 * (st.sin_phi[j] * c.centre.x + st.cos_phi[j] * c.centre.z);
      }
      for (std::size_t j = 0; j < n_dir; j += 4) {
        simd::v4d sn, cs;
        simd::sincos(simd::v4d{angle[j], angle[j + 1], angle[j + 2], angle[j + 3]}, sn, cs);
        for (int l = 0; l < 4; ++l) phase_re[j + l] = cs[l], phase_im[j + l] = sn[l];
      }
      const int width = 2 * t.outputs;  // doubles per direction
      double acc[2 * 16];
      for (std::size_t j = 0; j < n_dir; ++j) {
        const double* y = rows.data() + 2 * (static_cast<std::size_t>(st.first[j]) * outputs + t.first_output);
        const auto& w = st.weight[j];
        for (int k = 0; k < width; ++k) acc[k] = 0.0;
        for (int a = 0; a < 6; ++a) {
          const double* ya = y + 2 * a * outputs;
          for (int k = 0; k < width; ++k) acc[k] += w[a] * ya[k];
        }
        Complex* out = accumulated[s].data() + j * static_cast<std::size_t>(t.outputs);
        for (int q = 0; q < t.outputs; ++q) {
          const double re = acc[2 * q], im = acc[2 * q + 1];
          out[q] += Complex(phase_re[j] * re - phase_im[j] * im, phase_re[j] * im + phase_im[j] * re);
        }
      }
    }
  }
  for (std::size_t s = 0; s < targets.size(); ++s) {
    const RadiationTargets& t = targets[s];
    t.result->resize(static_cast<Eigen::Index>(t.phi_o_rad.size()), t.outputs);
    for (std::size_t j = 0; j < t.phi_o_rad.size(); ++j) {
      for (int q = 0; q < t.outputs; ++q) {
        (*t.result)(static_cast<Eigen::Index>(j), q) = accumulated[s][j * static_cast<std::size_t>(t.outputs) + q];
      }
    }
  }
}

}  // namespace

void radiate(std::span<const Vec2> vertices, std::span<const double> segment_length,
             std::span<const double> chi, double gamma0, double theta_i_rad,
             const Eigen::MatrixXcd& amplitudes, std::span<const RadiationTargets> targets,
             const ChunkingOptions& options) {
  for (const RadiationTargets& t : targets) {
    if (t.outputs < 1 || t.outputs > 16 || t.first_output < 0 ||
        t.first_output + t.outputs > 2 * amplitudes.cols() / 6) {
      throw Error("radiate: target outputs out of range");
    }
  }
  if (vertices.size() < 3) throw Error("radiate: a polyline needs at least 3 vertices");
  bool on_cone = true;
  for (const RadiationTargets& t : targets) {
    for (const double phi : t.phi_o_rad) on_cone = on_cone && std::abs(phi) <= 0.5 * kPi;
  }
  if (options.chunked && on_cone) {
    radiate_chunked(vertices, segment_length, chi, gamma0, theta_i_rad, amplitudes, targets, options);
  } else {
    radiate_exact(vertices, segment_length, chi, gamma0, theta_i_rad, amplitudes, targets);
  }
}

}  // namespace plumage::detail
