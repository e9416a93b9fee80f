// GGX fit of (m, φ_c) on the specular cone with energy matching (spec §4.2, paper Eq. 11).
//
// On the cone ω_o = (cos θ_i sin φ_o, −sin θ_i, cos θ_i cos φ_o) and ω_i' = (cos θ_i sin φ_c,
// sin θ_i, cos θ_i cos φ_c), so ω_i' + ω_o ∝ (sin φ_c + sin φ_o, 0, cos φ_c + cos φ_o) and
// h_x = sin((φ_c + φ_o)/2) exactly. G1(ω_i') is constant over the pattern and cancels with F in
// the energy matching Ĝ = G · ΣU / ΣG; the model used below therefore is
//   G_k ∝ D(sin((φ_c + φ_o,k)/2); m) · G1(cos θ_i cos φ_o,k; m).
//
// Optimiser (a departure from the spec's 1° / 0.001 grid search, same objective): a coarse grid
// (φ_c every 2°, 28 m values log-spaced on [0.001, 1]), then Ceres (trust region, one thread,
// automatic derivatives) from the best grid point, with the bounds as parameter bounds. Both are
// deterministic. The grazing blend then fixes φ_c and m is refitted alone (spec §4.2).
#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "plumage/fitter.hpp"
#include "plumage/simd_math.hpp"

namespace plumage {

namespace {

constexpr double kMinM = 0.001, kMaxM = 1.0;
constexpr double kMaxPhi = 89.5 * kPi / 180.0;

template <class T>
T ggx_d_t(T hx, T m) {
  const T m2 = m * m;
  const T q = m2 + (T(1.0) - m2) * hx * hx;
  return m2 / (T(kPi) * q * q);
}

// tan² θ_o = (1 − cos²)/cos² of a direction, or −1 below the horizon (G1 = 0).
double tan2_or_below(double cos_z) {
  if (cos_z <= 0.0) return -1.0;
  return (1.0 - cos_z * cos_z) / (cos_z * cos_z);
}

// Smith G1 from tan² θ (tan2_or_below): 2 / (1 + √(1 + m² tan² θ)).
template <class T>
T smith_g1_t(double t2, T m) {
  if (t2 < 0.0) return T(0.0);
  return T(2.0) / (T(1.0) + sqrt(T(1.0) + m * m * T(t2)));
}

// Energy-matched residuals r_k = U_k − G_k ΣU/ΣG for parameters (m, φ_c). tan² of each
// sample's ω_o (ω_o,z = cos θ_i cos φ_o,k) is tabulated once: Ceres evaluates the residuals
// ~10–50 times per fit, and the cosine per sample was a third of each evaluation.
struct ConeResidual {
  double cos_theta;
  std::span<const double> phi_o, u;
  double sum_u;
  std::vector<double> tan2_o;

  ConeResidual(double cos_theta_i, std::span<const double> phi_o_rad, std::span<const double> pattern, double sum)
      : cos_theta(cos_theta_i), phi_o(phi_o_rad), u(pattern), sum_u(sum), tan2_o(phi_o_rad.size()) {
    for (std::size_t k = 0; k < tan2_o.size(); ++k) tan2_o[k] = tan2_or_below(cos_theta * std::cos(phi_o[k]));
  }

  template <class T>
  bool operator()(const T* m, const T* phi_c, T* r) const {
    using std::sin;
    using ceres::sin;
    T sum_g(0.0);
    const std::size_t n = phi_o.size();
    for (std::size_t k = 0; k < n; ++k) {
      const T g = ggx_d_t(sin((phi_c[0] + T(phi_o[k])) * T(0.5)), m[0]) * smith_g1_t(tan2_o[k], m[0]);
      r[k] = g;
      sum_g += g;
    }
    if (!(sum_g > T(0.0))) return false;
    const T scale = T(sum_u) / sum_g;
    for (std::size_t k = 0; k < n; ++k) r[k] = T(u[k]) - r[k] * scale;
    return true;
  }
};

double objective(const ConeResidual& f, double m, double phi_c, std::vector<double>& r) {
  r.resize(f.phi_o.size());
  if (!f(&m, &phi_c, r.data())) return std::numeric_limits<double>::infinity();
  double s = 0;
  for (double v : r) s += v * v;
  return s;
}

std::vector<double> m_candidates() {
  std::vector<double> ms;
  for (int k = 0; k < 28; ++k) ms.push_back(kMinM * std::pow(kMaxM / kMinM, k / 27.0));
  return ms;
}

// Ceres refinement of (m, φ_c) — or of m alone when φ_c is fixed.
void refine(const ConeResidual& f, double& m, double& phi_c, bool phi_fixed) {
  auto* cost = new ceres::AutoDiffCostFunction<ConeResidual, ceres::DYNAMIC, 1, 1>(
      new ConeResidual(f), static_cast<int>(f.phi_o.size()));
  ceres::Problem problem;
  double pm[1] = {m}, pp[1] = {phi_c};
  problem.AddResidualBlock(cost, nullptr, pm, pp);
  problem.SetParameterLowerBound(pm, 0, kMinM);
  problem.SetParameterUpperBound(pm, 0, kMaxM);
  if (phi_fixed) {
    problem.SetParameterBlockConstant(pp);
  } else {
    problem.SetParameterLowerBound(pp, 0, -kMaxPhi);
    problem.SetParameterUpperBound(pp, 0, kMaxPhi);
  }
  ceres::Solver::Options options;
  options.num_threads = 1;
  options.max_num_iterations = 50;
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-10;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  std::vector<double> r;
  // Keep the refinement only if it improved the objective (it starts from the grid optimum).
  if (std::isfinite(pm[0]) && std::isfinite(pp[0]) && objective(f, pm[0], pp[0], r) <= objective(f, m, phi_c, r)) {
    m = pm[0];
    phi_c = pp[0];
  }
}

// The coarse search evaluates the objective at 28 m × 89 φ_c: G1(cos θ_i cos φ_o; m) does not
// depend on φ_c and h_x = sin((φ_c + φ_o)/2) not on m, so both are tabulated once. The 28 m
// run as 7 vectors of 4 (one lane per m), so each m's sums take their terms in the order
// ConeResidual does (k = 0 … n − 1), with the same operations per term (h_x from the vector sin).
struct CoarseTable {
  using v4d = simd::v4d;
  static constexpr std::size_t kVectors = 7;  // 28 m candidates
  const ConeResidual& f;
  std::vector<double> ms;
  std::array<v4d, kVectors> m2;
  std::vector<std::array<v4d, kVectors>> g1;  // [k][m / 4]
  explicit CoarseTable(const ConeResidual& residual) : f(residual), ms(m_candidates()), g1(f.phi_o.size()) {
    static_assert(kVectors * 4 == 28);
    for (std::size_t a = 0; a < ms.size(); ++a) m2[a / 4][a % 4] = ms[a] * ms[a];
    for (std::size_t k = 0; k < g1.size(); ++k) {
      for (std::size_t a = 0; a < ms.size(); ++a) g1[k][a / 4][a % 4] = smith_g1_t(f.tan2_o[k], ms[a]);
    }
  }
  // Best m on the coarse list at fixed φ_c.
  double best_m(double phi_c, double& best) const {
    const std::size_t n = f.phi_o.size();
    // h_x = sin((φ_c + φ_o)/2) four samples at a time (simd::sincos, ≤ 2 ulp from libm's sin:
    // the grid only picks Ceres' starting point, which ConeResidual then refines with libm).
    std::vector<double> hx_k((n + 3) / 4 * 4);
    for (std::size_t k = 0; k < n; k += 4) {
      v4d arg{};
      for (std::size_t l = 0; l < 4; ++l) arg[l] = k + l < n ? (phi_c + f.phi_o[k + l]) * 0.5 : 0.0;
      v4d sin_arg, cos_arg;
      simd::sincos(arg, sin_arg, cos_arg);
      for (std::size_t l = 0; l < 4; ++l) hx_k[k + l] = sin_arg[l];
    }
    std::vector<std::array<v4d, kVectors>> g(n);
    std::array<v4d, kVectors> sum_g{};
    for (std::size_t k = 0; k < n; ++k) {
      const v4d hx = simd::splat(hx_k[k]);
      for (std::size_t j = 0; j < kVectors; ++j) {
        // ggx_d_t(hx, m) lane by lane: m² / (π q q), q = m² + (1 − m²) h_x².
        const v4d q = m2[j] + (1.0 - m2[j]) * hx * hx;
        g[k][j] = m2[j] / (kPi * q * q) * g1[k][j];
        sum_g[j] += g[k][j];
      }
    }
    std::array<v4d, kVectors> scale, v{};
    for (std::size_t j = 0; j < kVectors; ++j) scale[j] = f.sum_u / sum_g[j];
    for (std::size_t k = 0; k < n; ++k) {
      const double u = f.u[k];
      for (std::size_t j = 0; j < kVectors; ++j) {
        const v4d r = u - g[k][j] * scale[j];
        v[j] += r * r;
      }
    }
    double m_best = 0.1;
    best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < ms.size(); ++a) {
      if (!(sum_g[a / 4][a % 4] > 0.0)) continue;  // objective() = ∞
      const double va = v[a / 4][a % 4];
      if (va < best) best = va, m_best = ms[a];
    }
    return m_best;
  }
};

}  // namespace

std::vector<double> cone_lobe_shape(double theta_i_rad, double m, double phi_c_rad, std::span<const double> phi_o_rad) {
  const double ct = std::cos(theta_i_rad);
  std::vector<double> g(phi_o_rad.size());
  const double g1i = lobe::smith_g1(ct * std::cos(phi_c_rad), m);
  for (std::size_t k = 0; k < g.size(); ++k)
    g[k] = lobe::ggx_d(std::sin(0.5 * (phi_c_rad + phi_o_rad[k])), m) * g1i * lobe::smith_g1(ct * std::cos(phi_o_rad[k]), m);
  return g;
}

ConeFit fit_cone_lobe(double theta_i_rad, double phi_i_rad, std::span<const double> phi_o_rad,
                      std::span<const double> raw_pattern) {
  ConeFit out;
  out.phi_c_rad = std::clamp(phi_i_rad, -kMaxPhi, kMaxPhi);
  // The fit is scale-free (energy matching), but Ceres' gradient tolerance is absolute and
  // Σu² underflows: unnormalised, a lobe scaled by 1e-12 stopped at the coarse grid (m off by
  // 11 %) and one scaled by 1e-200 returned m = 0.001, φ_c = −88°, relative L2 NaN (issue 9,
  // measured). The pattern is therefore divided by its largest sample first; every scale then
  // gives the same (m, φ_c) down to subnormal samples.
  double peak = 0.0;
  for (double u : raw_pattern) peak = std::max(peak, u);
  if (!(peak > 0.0) || !std::isfinite(peak)) {  // nothing reflected: keep the specular direction, a mid roughness
    out.m = 0.1;
    out.rel_l2 = 0.0;
    return out;
  }
  std::vector<double> normalised(raw_pattern.size());
  for (std::size_t k = 0; k < normalised.size(); ++k) normalised[k] = raw_pattern[k] / peak;
  const std::span<const double> pattern(normalised);
  double sum_u = 0, norm_u = 0;
  for (double u : pattern) sum_u += u, norm_u += u * u;
  if (!(sum_u > 0.0)) {
    out.m = 0.1;
    out.rel_l2 = 0.0;
    return out;
  }
  const ConeResidual f(std::cos(theta_i_rad), phi_o_rad, pattern, sum_u);
  std::vector<double> r;
  // The coarse search sees every 4th sample only (box-summed, so narrow peaks are not missed):
  // it has to find the basin, Ceres then fits all samples.
  std::vector<double> phi4, u4;
  for (std::size_t k = 0; k + 3 < phi_o_rad.size(); k += 4) {
    phi4.push_back(0.25 * (phi_o_rad[k] + phi_o_rad[k + 1] + phi_o_rad[k + 2] + phi_o_rad[k + 3]));
    u4.push_back(pattern[k] + pattern[k + 1] + pattern[k + 2] + pattern[k + 3]);
  }
  double sum4 = 0;
  for (double u : u4) sum4 += u;
  const bool decimate = phi4.size() >= 20 && sum4 > 0;
  const ConeResidual coarse = decimate ? ConeResidual(f.cos_theta, phi4, u4, sum4) : f;

  // 1. Fit of both parameters: coarse grid, then Ceres.
  const CoarseTable table(coarse);
  double best = std::numeric_limits<double>::infinity(), m_fit = 0.1, phi_fit = 0.0;
  for (int p = -44; p <= 44; ++p) {
    const double phi = deg_to_rad(2.0 * p);
    double v;
    const double m = table.best_m(phi, v);
    if (v < best) best = v, m_fit = m, phi_fit = phi;
  }
  refine(f, m_fit, phi_fit, false);

  // 2. Grazing blend of φ_c with w = cos θ_i cos φ_i (spec §4.2), then m alone at that φ_c.
  const double w = std::cos(theta_i_rad) * std::cos(phi_i_rad);
  double phi_c = phi_fit;
  if (w <= 0.05) phi_c = phi_i_rad;
  else if (w < 0.10) {
    const double s = (w - 0.05) / 0.05;
    phi_c = (1.0 - s) * phi_i_rad + s * phi_fit;
  }
  phi_c = std::clamp(phi_c, -kMaxPhi, kMaxPhi);
  double m = m_fit;
  if (phi_c != phi_fit) {
    double v;
    m = table.best_m(phi_c, v);
    refine(f, m, phi_c, true);
  }
  out.m = m;
  out.phi_c_rad = phi_c;
  out.rel_l2 = std::sqrt(objective(f, m, phi_c, r) / norm_u);
  return out;
}

}  // namespace plumage
