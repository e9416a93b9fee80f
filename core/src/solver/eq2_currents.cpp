#include "eq2_currents.hpp"

#include <algorithm>
#include <cmath>


namespace plumage::detail {

namespace {

using Vec3 = std::array<double, 3>;
using CVec3 = std::array<Complex, 3>;

double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

[[gnu::always_inline]] inline Vec3 cross3(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
[[gnu::always_inline]] inline CVec3 cross3(const Vec3& a, const CVec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The Eq. 2 currents (J̃ = n̂ × η0H, M = −n̂ × E; incident phase factored out) of both
// polarizations at a surface point with normal n̂ and local reflection r, into out[0]; with
// `with_lossless` also those of the lossless reference (fill_amplitudes) into out[1], from the
// same local basis (one pass instead of two over the nodes). False if the point faces away from
// the light (within kGrazingCutoff of grazing or beyond). The sub-sampled path; whole nodes go
// through NodeLanes below, the same arithmetic four nodes at a time.
using PointCurrents = std::array<std::array<Complex, 6>, 2>;  // [pol][J̃x J̃y J̃z Mx My Mz]

bool point_currents(const Vec2& normal, const Vec3& w_i, const JonesReflection& r,
                    const PlaneWavePolarization (&pol)[2], bool with_incident, bool with_lossless,
                    PointCurrents (&out)[2]) {
  const Vec3 n{normal.x, 0.0, normal.z};
  const double cos_a = dot3(w_i, n);
  if (cos_a <= std::sin(kGrazingCutoff)) return false;
  // Local s direction ŝ = ω_i × n̂/|…| (ŷ at exactly normal incidence), reflected direction
  // ω_r = 2 cos α n̂ − ω_i, and r̂ = ω_r × ŝ (the reflected p-wave's E is −a_p r̂).
  Vec3 s_hat = cross3(w_i, n);
  const double s_len = std::sqrt(dot3(s_hat, s_hat));
  s_hat = s_len < 1e-4 ? Vec3{0.0, 1.0, 0.0} : Vec3{s_hat[0] / s_len, s_hat[1] / s_len, s_hat[2] / s_len};
  const Vec3 w_r{2 * cos_a * n[0] - w_i[0], 2 * cos_a * n[1] - w_i[1], 2 * cos_a * n[2] - w_i[2]};
  const Vec3 r_hat = cross3(w_r, s_hat);
  const int variants = with_lossless ? 2 : 1;
  for (int p = 0; p < 2; ++p) {
    const Vec3& e = pol[p].e;
    const Vec3& h = pol[p].eta0_h;
    const double c_e = dot3(e, s_hat), c_h = dot3(h, s_hat);
    for (int v = 0; v < variants; ++v) {
      Complex a_s = r.ss * c_e + r.sp * c_h;
      Complex a_p = r.ps * c_e + r.pp * c_h;
      if (v == 1) {  // lossless: all the incident power, phase and polarization kept
        const double in = c_e * c_e + c_h * c_h, reflected = std::norm(a_s) + std::norm(a_p);
        if (reflected > 1e-24 * in) {
          const double scale = std::sqrt(in / reflected);
          a_s *= scale, a_p *= scale;
        } else {
          a_s = -c_e, a_p = c_h;
        }
      }
      CVec3 e_tot, h_tot;  // E and η0 H at the point, incident phase factored out
      for (int c = 0; c < 3; ++c) {
        e_tot[c] = a_s * s_hat[c] - a_p * r_hat[c];
        h_tot[c] = a_s * r_hat[c] + a_p * s_hat[c];
        if (with_incident) {
          e_tot[c] += e[c];
          h_tot[c] += h[c];
        }
      }
      const CVec3 j = cross3(n, h_tot);
      const CVec3 ne = cross3(n, e_tot);
      for (int c = 0; c < 3; ++c) out[v][p][c] = j[c], out[v][p][3 + c] = -ne[c];
    }
  }
  return true;
}

// Sub-sampled reflection (K > 1): node m's currents are the trapezoid-weighted mean of its lit
// sub-samples' currents; unlit nodes get a zero row.
void fill_sampled_amplitudes(const CurrentNodes& top, const Vec3& w_i, std::span<const JonesReflection> jones,
                             const PlaneWavePolarization (&pol)[2], bool with_incident,
                             Eigen::Ref<Eigen::MatrixXcd> amplitudes) {
  const bool with_lossless = amplitudes.cols() == 24;
  const int variants = with_lossless ? 2 : 1;
  const auto k = static_cast<std::size_t>(top.samples);
  PointCurrents point[2]{};
  for (std::size_t m = 0; m < top.normals.size(); ++m) {
    PointCurrents sum[2]{};
    double weights = 0.0;
    // Node m is fine vertex (m + 1)K; its support spans fine vertices mK … (m + 2)K, i.e.
    // sub-sample indices mK − 1 … (m + 2)K − 1, the two ends with weight 0.
    for (std::size_t q = 1; q < 2 * k; ++q) {
      const std::size_t f = m * k + q - 1;
      if (!point_currents(top.sample_normals[f], w_i, jones[f], pol, with_incident, with_lossless, point)) continue;
      // Trapezoid rule of ∫ Λ_m J dl: tent value times the sub-segment length of its side.
      const double w = static_cast<double>(q <= k ? q : 2 * k - q) *
                       (q <= k ? top.segment_length[m] : top.segment_length[m + 1]);
      for (int v = 0; v < variants; ++v) {
        for (int p = 0; p < 2; ++p) {
          for (int c = 0; c < 6; ++c) sum[v][p][c] += w * point[v][p][c];
        }
      }
      weights += w;
    }
    const auto row = static_cast<Eigen::Index>(m);
    if (!(weights > 0.0)) {  // unlit: a zero row (only these rows are zeroed, not the matrix)
      amplitudes.row(row).setZero();
      continue;
    }
    for (int v = 0; v < variants; ++v) {
      const double weight = top.window[m] * (v == 1 ? 1.0 : top.regularity[m]) / weights;
      for (int p = 0; p < 2; ++p) {
        for (int c = 0; c < 6; ++c) amplitudes(row, 12 * v + 6 * p + c) = weight * sum[v][p][c];
      }
    }
  }
}

// point_currents for four nodes at once as GCC vectors over nodes (structure of arrays; issue 26:
// the scalar version was 8 % of a production group). Same formulas, order of operations and
// selects in place of branches; FMA contraction may round differently from the scalar code.
// Four lanes (one AVX2 register): eight (AVX-512 on this machine) measured 13 % slower in the
// profile, 5160 vs 4559 samples of fill_amplitudes in a 550 nm production run.
constexpr int kNodeLanes = 4;
using NodeVec = double __attribute__((vector_size(sizeof(double) * kNodeLanes)));  // one node per lane
inline NodeVec splat(double x) { return NodeVec{} + x; }

struct LaneComplex {
  NodeVec re, im;
};
inline LaneComplex operator+(const LaneComplex& a, const LaneComplex& b) { return {a.re + b.re, a.im + b.im}; }
inline LaneComplex operator-(const LaneComplex& a, const LaneComplex& b) { return {a.re - b.re, a.im - b.im}; }
inline LaneComplex operator*(const LaneComplex& a, NodeVec s) { return {a.re * s, a.im * s}; }
struct LaneVec3 {
  NodeVec x, y, z;
};

inline NodeVec lane_sqrt(NodeVec x) {
  NodeVec r;
  for (int l = 0; l < kNodeLanes; ++l) r[l] = std::sqrt(x[l]);  // -fno-math-errno: vsqrtpd
  return r;
}

class NodeLanes {
 public:
  NodeLanes(const CurrentNodes& top, const Vec3& w_i, std::span<const JonesReflection> jones,
            const PlaneWavePolarization (&pol)[2], bool with_incident, Eigen::Ref<Eigen::MatrixXcd> amplitudes)
      : top_(top), w_(w_i), jones_(jones), pol_(pol), with_incident_(with_incident), amplitudes_(amplitudes) {}

  // Nodes m0 … m0 + count − 1 (count ≤ 4; the last lane's node repeated to fill the vector).
  void block(std::size_t m0, int count) {
    NodeVec nx, nz, window, regularity;
    LaneComplex ss, sp, ps, pp;
    for (int l = 0; l < kNodeLanes; ++l) {
      const std::size_t m = m0 + static_cast<std::size_t>(std::min(l, count - 1));
      nx[l] = top_.normals[m].x, nz[l] = top_.normals[m].z;
      window[l] = top_.window[m], regularity[l] = top_.regularity[m];
      const JonesReflection& r = jones_[m];
      ss.re[l] = r.ss.real(), ss.im[l] = r.ss.imag(), sp.re[l] = r.sp.real(), sp.im[l] = r.sp.imag();
      ps.re[l] = r.ps.real(), ps.im[l] = r.ps.imag(), pp.re[l] = r.pp.real(), pp.im[l] = r.pp.imag();
    }
    const double w0 = w_[0], w1 = w_[1], w2 = w_[2];
    const NodeVec cos_a = w0 * nx + w2 * nz;  // ω_i·n̂, n̂ = (n_x, 0, n_z)
    const auto lit = cos_a > std::sin(kGrazingCutoff);
    // ŝ = ω_i × n̂/|…| (ŷ where |ω_i × n̂| < 1e-4), ω_r = 2 cos α n̂ − ω_i, r̂ = ω_r × ŝ.
    const LaneVec3 s{w1 * nz, w2 * nx - w0 * nz, -(w1 * nx)};
    const NodeVec s_len = lane_sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
    const auto small = s_len < 1e-4;
    const NodeVec safe_len = small ? splat(1.0) : s_len;
    s_hat_ = {small ? splat(0.0) : s.x / safe_len, small ? splat(1.0) : s.y / safe_len,
              small ? splat(0.0) : s.z / safe_len};
    const LaneVec3 w_r{2 * cos_a * nx - w0, splat(-w1), 2 * cos_a * nz - w2};
    r_hat_ = {w_r.y * s_hat_.z - w_r.z * s_hat_.y, w_r.z * s_hat_.x - w_r.x * s_hat_.z,
              w_r.x * s_hat_.y - w_r.y * s_hat_.x};
    nx_ = nx, nz_ = nz;
    const bool with_lossless = amplitudes_.cols() == 24;
    for (int p = 0; p < 2; ++p) {
      const Vec3& e = pol_[p].e;
      const Vec3& h = pol_[p].eta0_h;
      const NodeVec c_e = e[0] * s_hat_.x + e[1] * s_hat_.y + e[2] * s_hat_.z;
      const NodeVec c_h = h[0] * s_hat_.x + h[1] * s_hat_.y + h[2] * s_hat_.z;
      const LaneComplex a_s = ss * c_e + sp * c_h, a_p = ps * c_e + pp * c_h;
      store(m0, count, 6 * p, pol_[p], a_s, a_p, lit ? window * regularity : splat(0.0));
      if (!with_lossless) continue;
      // Lossless: all the incident power, phase and polarization kept; a perfect conductor
      // where nothing is reflected.
      const NodeVec in = c_e * c_e + c_h * c_h;
      const NodeVec reflected = a_s.re * a_s.re + a_s.im * a_s.im + (a_p.re * a_p.re + a_p.im * a_p.im);
      const auto scaled = reflected > 1e-24 * in;
      const NodeVec scale = lane_sqrt(in / (scaled ? reflected : splat(1.0)));
      const LaneComplex ref_s{scaled ? a_s.re * scale : -c_e, scaled ? a_s.im * scale : splat(0.0)};
      const LaneComplex ref_p{scaled ? a_p.re * scale : c_h, scaled ? a_p.im * scale : splat(0.0)};
      store(m0, count, 12 + 6 * p, pol_[p], ref_s, ref_p, lit ? window : splat(0.0));
    }
  }

 private:
  // E = a_s ŝ − a_p r̂ and η0H = a_s r̂ + a_p ŝ (plus the incident wave with `with_incident`),
  // J̃ = n̂ × η0H and M = −n̂ × E, times `weight` (0 on unlit lanes), into columns column … +5.
  void store(std::size_t m0, int count, int column, const PlaneWavePolarization& pol, const LaneComplex& a_s,
             const LaneComplex& a_p, NodeVec weight) {
    LaneComplex e_tot[3], h_tot[3];
    const NodeVec s_hat[3] = {s_hat_.x, s_hat_.y, s_hat_.z}, r_hat[3] = {r_hat_.x, r_hat_.y, r_hat_.z};
    for (int c = 0; c < 3; ++c) {
      e_tot[c] = a_s * s_hat[c] - a_p * r_hat[c];
      h_tot[c] = a_s * r_hat[c] + a_p * s_hat[c];
      if (with_incident_) e_tot[c].re += pol.e[c], h_tot[c].re += pol.eta0_h[c];
    }
    const NodeVec zero = splat(0.0);
    const LaneComplex current[6] = {
        h_tot[1] * (-nz_),                    // J̃x = −n_z η0H_y
        h_tot[0] * nz_ - h_tot[2] * nx_,      // J̃y = n_z η0H_x − n_x η0H_z
        h_tot[1] * nx_,                       // J̃z = n_x η0H_y
        e_tot[1] * nz_,                       // Mx = n_z E_y
        e_tot[2] * nx_ - e_tot[0] * nz_,      // My = n_x E_z − n_z E_x
        e_tot[1] * (-nx_)};                   // Mz = −n_x E_y
    const auto lit = weight != zero;  // unlit lanes: exact zeros, whatever their arithmetic gave
    for (int c = 0; c < 6; ++c) {
      Complex* out = amplitudes_.data() + (column + c) * amplitudes_.outerStride() + static_cast<Eigen::Index>(m0);
      const NodeVec re = lit ? current[c].re * weight : zero;
      const NodeVec im = lit ? current[c].im * weight : zero;
      if (count == kNodeLanes) {  // a constant trip count: interleaved vector stores
        for (int l = 0; l < kNodeLanes; ++l) out[l] = Complex(re[l], im[l]);
      } else {
        for (int l = 0; l < count; ++l) out[l] = Complex(re[l], im[l]);
      }
    }
  }

  const CurrentNodes& top_;
  const Vec3& w_;
  std::span<const JonesReflection> jones_;
  const PlaneWavePolarization (&pol_)[2];
  bool with_incident_;
  Eigen::Ref<Eigen::MatrixXcd> amplitudes_;
  LaneVec3 s_hat_, r_hat_;
  NodeVec nx_, nz_;
};

}  // namespace

void fill_amplitudes(const CurrentNodes& top, const IncidentDirection& incident, const Vec3& w_i,
                     std::span<const JonesReflection> jones, bool with_incident,
                     Eigen::Ref<Eigen::MatrixXcd> amplitudes, std::array<double, 2>& incident_power) {
  const PlaneWavePolarization pol[2] = {incident_polarization(0, incident),
                                        incident_polarization(1, incident)};
  incident_power = {0.0, 0.0};
  for (std::size_t m = 0; m < top.normals.size(); ++m) {
    const double cos_a = dot3(w_i, {top.normals[m].x, 0.0, top.normals[m].z});
    if (cos_a > 0.0) {  // Eq. 9: power through the lit part of the top surface, in node order
      const double flux = top.node_length[m] * top.window[m] * top.window[m] * cos_a / (2.0 * kEta0_ohm);
      incident_power[0] += flux;
      incident_power[1] += flux;
    }
  }
  if (top.samples > 1) {
    fill_sampled_amplitudes(top, w_i, jones, pol, with_incident, amplitudes);
    return;
  }
  NodeLanes lanes(top, w_i, jones, pol, with_incident, amplitudes);
  const std::size_t nodes = top.normals.size();
  for (std::size_t m0 = 0; m0 < nodes; m0 += kNodeLanes) {
    lanes.block(m0, static_cast<int>(std::min<std::size_t>(kNodeLanes, nodes - m0)));
  }
}

}  // namespace plumage::detail
