// One work unit: far fields of every instance → the eight parameters of a MaterialNode
// (spec §4.1–4.6, paper §5 Eqs. 11–13).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "noise_columns.hpp"

namespace plumage {

namespace {

// ---- stability checks (issue 9; docs/validation.md "Fit warnings") ----------------------------

// Reflected fraction E below which a unit is "near-zero energy": its lobe is replaced by the zero
// lobe (F_eff = F_sta = 0, m = 0.1, φ_c = φ_i) and `fit.near_zero_energy` is raised. 1e-8 is
// far below every real unit (faintest fitted node of the preview materials: bronzewing 0.014,
// hummingbird 0.017, starling 0.032, rock dove 0.046), below what float radiance resolves next
// to them (6e-8 relative), and below the absolute accuracy of the full-wave backends' energy (BEM
// optical theorem 4.6e-6 relative), so a pattern this faint is solver noise whose shape must not
// steer m and φ_c (which smoothing would carry into the neighbouring nodes).
constexpr double kNearZeroEnergy = 1e-8;

// Two-lobe detector. The mean pattern is smoothed with a Gaussian of kSmoothBins bins (σ; the
// instance speckle, ~1–3 bins wide, is cut by ~2–4 in amplitude). A local
// maximum of the smoothed pattern is a *separate peak* when, to reach any higher point, the
// pattern first drops to at most kValley of its height (topographic prominence ≥ 1 − kValley: a
// peak, not a shoulder or a speckle ripple); the global maximum always is one. The bins are cut
// into one segment per separate peak at the lowest point between neighbouring peaks. Two lobes:
// at least two segments each hold ≥ kSecondMass of the pattern's energy, and in one of them the
// single-lobe fit leaves ≥ kSecondMass of the energy unexplained (positive residual), i.e. the
// fitted lobe covers one of them, or sits between them. Thresholds measured on synthetic
// patterns (tests/test_fit_stability.cpp, docs/validation.md "Fit warnings").
constexpr double kSmoothBins = 3.0;
constexpr double kValley = 0.5;
constexpr double kSecondMass = 0.15;

std::vector<double> smoothed(const std::vector<double>& u) {
  const int n = static_cast<int>(u.size()), half = static_cast<int>(std::ceil(3.0 * kSmoothBins));
  // Gaussian taps w_d = exp(−d²/(2 s²)) once, not per output bin (the same values).
  std::vector<double> taps(static_cast<std::size_t>(2 * half + 1));
  for (int d = -half; d <= half; ++d) taps[static_cast<std::size_t>(d + half)] = std::exp(-0.5 * d * d / (kSmoothBins * kSmoothBins));
  std::vector<double> out(u.size());
  for (int k = 0; k < n; ++k) {
    double s = 0, ws = 0;
    for (int d = -half; d <= half; ++d) {
      const int j = k + d;
      if (j < 0 || j >= n) continue;  // renormalised at the ends of (−90°, 90°)
      const double w = taps[static_cast<std::size_t>(d + half)];
      s += w * u[static_cast<std::size_t>(j)];
      ws += w;
    }
    out[static_cast<std::size_t>(k)] = s / ws;
  }
  return out;
}

struct SecondLobe {
  bool found = false;
  std::size_t peak = 0, second = 0;  // bins of the fitted lobe's peak and of the unexplained peak
  double mass = 0.0;                 // positive residual in the unexplained peak's segment / Σ U
  double lobe_mass = 0.0;            // the second-largest segment's share of Σ U
};

// `fit` is the energy-matched single lobe at the same bins as `u`.
SecondLobe find_second_lobe(const std::vector<double>& u, const std::vector<double>& fit) {
  SecondLobe out;
  const std::size_t n = u.size();
  const auto us = smoothed(u), fs = smoothed(fit);  // both smoothed alike: a narrow fit is not a residual
  double total = 0;
  for (double v : us) total += v;
  if (n < 3 || !(total > 0)) return out;
  out.peak = static_cast<std::size_t>(std::max_element(fs.begin(), fs.end()) - fs.begin());
  // Separate peaks, in order of position.
  std::vector<std::size_t> peaks;
  for (std::size_t k = 0; k < n; ++k) {
    const bool left_ok = k == 0 || us[k] > us[k - 1], right_ok = k + 1 == n || us[k] >= us[k + 1];
    if (!left_ok || !right_ok || !(us[k] > 0)) continue;
    // Highest col on the way to a higher point (−1: none in that direction). Of equal peaks the
    // left one counts as higher, so exactly one peak is global and a tie needs a real valley.
    double col = -1.0;
    double low = us[k];
    for (std::size_t j = k; j-- > 0;) {
      if (us[j] >= us[k]) { col = std::max(col, low); break; }
      low = std::min(low, us[j]);
    }
    low = us[k];
    for (std::size_t j = k + 1; j < n; ++j) {
      if (us[j] > us[k]) { col = std::max(col, low); break; }
      low = std::min(low, us[j]);
    }
    if (col <= kValley * us[k]) peaks.push_back(k);
  }
  if (peaks.size() < 2) return out;
  // Segments cut at the lowest point between neighbouring peaks.
  std::vector<std::size_t> cut{0};
  for (std::size_t p = 0; p + 1 < peaks.size(); ++p) {
    std::size_t low = peaks[p];
    for (std::size_t j = peaks[p]; j <= peaks[p + 1]; ++j)
      if (us[j] < us[low]) low = j;
    cut.push_back(low);
  }
  cut.push_back(n);
  std::vector<double> share;
  for (std::size_t p = 0; p < peaks.size(); ++p) {
    double mass = 0, excess = 0;
    for (std::size_t j = cut[p]; j < cut[p + 1]; ++j) mass += us[j], excess += std::max(0.0, us[j] - fs[j]);
    share.push_back(mass / total);
    if (excess / total > out.mass) out.mass = excess / total, out.second = peaks[p];
  }
  std::sort(share.begin(), share.end(), std::greater<>());
  out.lobe_mass = share[1];
  out.found = out.lobe_mass >= kSecondMass && out.mass >= kSecondMass;
  return out;
}

std::string unit_label(const UnitInput& in) {
  char b[160];
  std::snprintf(b, sizeof b, "lambda = %.6g nm, theta_i = %.4g deg, phi_i = %.4g deg", in.lambda_nm,
                rad_to_deg(in.theta_i_rad), rad_to_deg(in.phi_i_rad));
  return b;
}

double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

// Noise data (spec §4.6 steps 1–3): per polarization the dominant field component, its
// normalised fluctuations (Re and Im per instance), weighted by the mean lobe's shape
// D(h; m_eff) G1(ω_i') G1(ω_o) at ω_o = (x, −sin θ_i, √(1 − x² − sin² θ_i)); returned centred
// (each column's mean removed, spec §4.6 step 4).
detail::NoiseColumns noise_columns(const UnitInput& in, const Lobe& mean_lobe) {
  const std::size_t first = in.pattern_count, count = in.instances.front().phi_o_rad.size() - first;
  const std::size_t n_inst = in.instances.size();
  if (count < 4 || n_inst < 2) return {};
  // Columns in the order p = 0 Re (instances in order), p = 0 Im, p = 1 Re, p = 1 Im.
  detail::NoiseColumns columns(4 * n_inst, count);
  const double ct = std::cos(in.theta_i_rad), st = std::sin(in.theta_i_rad);
  // Lobe weight per row, F = 1 and without D_y (h_y = 0 on the cone) and 1/(4 ω_i'_z).
  std::vector<double> weight(count);
  const Direction wi = direction_from_angles(in.theta_i_rad, mean_lobe.phi_c_rad);
  for (std::size_t r = 0; r < count; ++r) {
    const double phi = in.instances.front().phi_o_rad[first + r];
    const double x = ct * std::sin(phi);
    const double z = std::sqrt(std::max(0.0, 1.0 - x * x - st * st));
    double hx = wi.x + x, hy = wi.y - st, hz = wi.z + z;
    const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
    hx /= len;
    weight[r] = lobe::ggx_d(hx, mean_lobe.m) * lobe::smith_g1(wi.z, mean_lobe.m) * lobe::smith_g1(z, mean_lobe.m);
  }
  // The sums below run over instances in order, as the definitions do, but row block by row
  // block with the instance loop inside: a block of 32 rows of all instances (75 KB) stays in
  // cache between the mean and the variance pass, and each instance's field is read front to
  // back (the instance-innermost loops of before jumped between 50 arrays per sample and waited
  // on memory; the group's far fields, 137 MB at production, are far out of cache).
  constexpr std::size_t kRowBlock = 32;
  using Rows = std::array<std::vector<double>, 3>;  // [component][row]
  for (int p = 0; p < 2; ++p) {
    Rows mre, mim, vre, vim;
    for (int c = 0; c < 3; ++c) mre[c].assign(count, 0), mim[c].assign(count, 0), vre[c].assign(count, 0), vim[c].assign(count, 0);
    for (std::size_t r0 = 0; r0 < count; r0 += kRowBlock) {
      const std::size_t r1 = std::min(count, r0 + kRowBlock);
      for (const FarField& ff : in.instances) {
        const std::array<Complex, 3>* f = ff.field[p].data() + first;
        for (std::size_t r = r0; r < r1; ++r)
          for (int c = 0; c < 3; ++c) mre[c][r] += f[r][c].real(), mim[c][r] += f[r][c].imag();
      }
      for (int c = 0; c < 3; ++c)
        for (std::size_t r = r0; r < r1; ++r) mre[c][r] /= static_cast<double>(n_inst), mim[c][r] /= static_cast<double>(n_inst);
      for (const FarField& ff : in.instances) {
        const std::array<Complex, 3>* f = ff.field[p].data() + first;
        for (std::size_t r = r0; r < r1; ++r) {
          for (int c = 0; c < 3; ++c) {
            const double dr = f[r][c].real() - mre[c][r], di = f[r][c].imag() - mim[c][r];
            vre[c][r] += dr * dr;
            vim[c][r] += di * di;
          }
        }
      }
    }
    // Dominant component: max Σ_x (μ_Re² + μ_Im² + v_Re + v_Im).
    int best_c = 0;
    double best = -1;
    for (int c = 0; c < 3; ++c) {
      for (std::size_t r = 0; r < count; ++r) vre[c][r] /= static_cast<double>(n_inst - 1), vim[c][r] /= static_cast<double>(n_inst - 1);
      double score = 0;
      for (std::size_t r = 0; r < count; ++r) score += mre[c][r] * mre[c][r] + mim[c][r] * mim[c][r] + vre[c][r] + vim[c][r];
      if (score > best) best = score, best_c = c;
    }
    // Columns: the real parts of all instances, then the imaginary parts, both filled in one
    // read of each instance's field.
    const int c = best_c;
    std::vector<double> sd_re(count), sd_im(count);  // √var once per row, not per instance (the same value)
    for (std::size_t r = 0; r < count; ++r) sd_re[r] = std::sqrt(vre[c][r]), sd_im[r] = std::sqrt(vim[c][r]);
    const std::size_t base = 2 * n_inst * static_cast<std::size_t>(p);
    for (std::size_t i = 0; i < n_inst; ++i) {
      const std::array<Complex, 3>* f = in.instances[i].field[p].data() + first;
      double* re = columns.column(base + i);
      double* im = columns.column(base + n_inst + i);
      for (std::size_t r = 0; r < count; ++r) {
        re[r] = sd_re[r] > 0 ? (f[r][c].real() - mre[c][r]) / sd_re[r] * weight[r] : 0.0;
        im[r] = sd_im[r] > 0 ? (f[r][c].imag() - mim[c][r]) / sd_im[r] * weight[r] : 0.0;
      }
    }
  }
  detail::centre(columns);
  return columns;
}

}  // namespace

namespace {
// sin φ_o, cos φ_o at the cone sum's midpoints φ_o = −π/2 + (k + ½) π / count: the same for every
// lobe and θ_i, so tabulated once for the default count (two cone sums per unit, four per node in
// the assembly).
struct ConeMidpoints {
  std::vector<double> sin_phi, cos_phi;
  explicit ConeMidpoints(int count)  // count ≥ 0
      : sin_phi(static_cast<std::size_t>(count)), cos_phi(static_cast<std::size_t>(count)) {
    for (int k = 0; k < count; ++k) {
      const double phi_o = -0.5 * kPi + (k + 0.5) * kPi / count;
      sin_phi[static_cast<std::size_t>(k)] = std::sin(phi_o);
      cos_phi[static_cast<std::size_t>(k)] = std::cos(phi_o);
    }
  }
};
}  // namespace

double cone_lobe_sum(const Lobe& lobe, double theta_i_rad, int midpoints) {
  static const ConeMidpoints default_midpoints(2000);
  const ConeMidpoints other(midpoints == 2000 ? 0 : std::max(midpoints, 0));
  const ConeMidpoints& at = midpoints == 2000 ? default_midpoints : other;
  const LobeEvaluator value(lobe, theta_i_rad);
  const double ct = std::cos(-theta_i_rad), st = std::sin(-theta_i_rad);
  double s = 0;
  for (std::size_t k = 0; k < at.sin_phi.size(); ++k)
    s += value(Direction{ct * at.sin_phi[k], st, ct * at.cos_phi[k]});  // direction_from_angles(−θ_i, φ_o)
  return s;
}

UnitFit fit_unit(const UnitInput& in) {
  if (in.instances.empty()) throw Error("fit_unit: no instances");
  const std::size_t n_inst = in.instances.size(), np = in.pattern_count;
  const auto& phi_all = in.instances.front().phi_o_rad;
  if (np < 8 || phi_all.size() < np) throw Error("fit_unit: too few pattern directions");
  for (const FarField& ff : in.instances) {
    if (ff.phi_o_rad.size() != phi_all.size()) throw Error("fit_unit: instances differ in directions");
  }
  const std::span<const double> phi_o(phi_all.data(), np);
  const double bin = kPi / static_cast<double>(np);  // pattern bins cover (−90°, 90°)
  const double ct = std::cos(in.theta_i_rad);
  UnitFit out;

  // §4.1 mean pattern U (unpolarised, instance mean of the Eq. 10 density), §4.4 coherent part s,
  // §4.5 polarization share. Sums run in instance order (deterministic).
  std::vector<double> u(np, 0.0), s(np, 0.0);
  double pol1 = 0, pol_all = 0;
  for (int p = 0; p < 2; ++p) {
    std::vector<std::array<Complex, 3>> mean_field(np, {Complex{}, Complex{}, Complex{}});
    for (const FarField& ff : in.instances) {
      const double inv = ff.incident_power[p] > 0 ? 1.0 / std::sqrt(ff.incident_power[p]) : 0.0;
      // FarField::reflectance_density with its cos θ_i and divisor once per instance (the same
      // operations in the same order: the same bits).
      const double cos_theta = std::cos(ff.incident.theta_rad);
      const double divisor = 2.0 * kEta0_ohm * ff.incident_power[p];
      const bool lit = ff.incident_power[p] > 0.0;
      for (std::size_t k = 0; k < np; ++k) {
        const auto& f = ff.field[p][k];
        const double d = lit ? cos_theta * (std::norm(f[0]) + std::norm(f[1]) + std::norm(f[2])) / divisor : 0.0;
        u[k] += 0.5 * d / static_cast<double>(n_inst);
        pol_all += d;
        if (p == 0) pol1 += d;
        for (int c = 0; c < 3; ++c) mean_field[k][c] += ff.field[p][k][c] * inv;
      }
    }
    for (std::size_t k = 0; k < np; ++k) {
      double intensity = 0;
      for (int c = 0; c < 3; ++c) intensity += std::norm(mean_field[k][c] / static_cast<double>(n_inst));
      s[k] += 0.5 * ct * intensity / (2.0 * kEta0_ohm);
    }
  }
  out.node.pol_share = pol_all > 0 ? pol1 / pol_all : 0.5;
  out.energy = sum(u) * bin;  // reflected fraction: the density already carries cos θ_i (far_field.hpp)
  // Non-finite far fields cannot be fitted into anything meaningful: refuse, naming the unit.
  if (!std::isfinite(out.energy) || !std::isfinite(sum(s)) || !std::isfinite(pol_all))
    throw Error("fit_unit: non-finite far field or incident power at " + unit_label(in));
  const bool near_zero = out.energy < kNearZeroEnergy;
  const double phi_neutral = std::clamp(in.phi_i_rad, deg_to_rad(-89.5), deg_to_rad(89.5));
  Lobe mean_lobe{0.1, phi_neutral, in.sigma, 1.0};
  out.mean_pattern = u;
  if (near_zero) {
    // Below the noise floor: the zero lobe, a defined result (F = 0, neutral shape, no NaN).
    char b[96];
    std::snprintf(b, sizeof b, "near-zero reflected energy E = %.3g (< %.0e) at ", out.energy, kNearZeroEnergy);
    warn("fit.near_zero_energy", b + unit_label(in) + ": zero lobe returned (F = 0, m = 0.1, phi_c = phi_i)");
    out.node.f_eff = out.node.f_sta = 0.0;
    out.node.m_eff = out.node.m_sta = 0.1;
    out.node.phi_eff = out.node.phi_sta = phi_neutral;
    out.node.pol_share = 0.5;
    out.fit_pattern.assign(np, 0.0);
    out.rel_l2_eff = out.rel_l2_sta = 0.0;
  } else {
    // §4.2 mean lobe, §4.3 F_eff = E / ∫ L_{F=1} dω.
    const ConeFit eff = fit_cone_lobe(in.theta_i_rad, in.phi_i_rad, phi_o, u);
    mean_lobe = Lobe{eff.m, eff.phi_c_rad, in.sigma, 1.0};
    const double integral = hemisphere_lobe_integral(mean_lobe, in.theta_i_rad);
    const double f_eff = integral > 0 ? out.energy / integral : 0.0;
    out.node.m_eff = eff.m;
    out.node.phi_eff = eff.phi_c_rad;
    out.rel_l2_eff = eff.rel_l2;
    {
      const auto g = cone_lobe_shape(in.theta_i_rad, eff.m, eff.phi_c_rad, phi_o);
      const double sg = sum(g), su = sum(u);
      out.fit_pattern.resize(np);
      for (std::size_t k = 0; k < np; ++k) out.fit_pattern[k] = sg > 0 ? g[k] * su / sg : 0.0;
    }
    // Two separate lobes that the single GGX lobe cannot represent (the fitted lobe sits on one,
    // or between them): the node is kept, the unit reported.
    const SecondLobe second = find_second_lobe(u, out.fit_pattern);
    if (second.found) {
      char b[320];
      std::snprintf(b, sizeof b,
                    "two separate lobes at %s: a second peak at phi_o = %.1f deg carries %.0f %% of the energy "
                    "outside the fitted lobe (peak at phi_o = %.1f deg); relative L2 of the single-lobe fit %.3f",
                    unit_label(in).c_str(), rad_to_deg(phi_o[second.second]), 100.0 * second.mass,
                    rad_to_deg(phi_o[second.peak]), eff.rel_l2);
      warn("fit.two_lobes", b);
    }

    // §4.4 statistics lobe: shape fitted to s, scale from the coherent fraction s0 and the cone
    // sums of both lobes over 2000 midpoints.
    const ConeFit sta = fit_cone_lobe(in.theta_i_rad, in.phi_i_rad, phi_o, s);
    out.node.m_sta = sta.m;
    out.node.phi_sta = sta.phi_c_rad;
    out.rel_l2_sta = sta.rel_l2;
    const double su = sum(u), s0 = su > 0 ? sum(s) / su : 0.0;
    mean_lobe.scale = f_eff;
    const double num = cone_lobe_sum(mean_lobe, in.theta_i_rad);
    const double den = cone_lobe_sum(Lobe{sta.m, sta.phi_c_rad, in.sigma, 1.0}, in.theta_i_rad);
    const double f_sta = den > 0 ? s0 * num / den : 0.0;
    const double w = ct * std::cos(in.phi_i_rad);  // premultiplication (spec §4.3)
    out.node.f_eff = f_eff * w;
    out.node.f_sta = f_sta * w;
  }

  // §4.6 correlation length on the projected samples (spacing 2/N in the direction cosine).
  mean_lobe.scale = 1.0;
  const auto columns = noise_columns(in, mean_lobe);
  if (!columns.empty()) {
    const std::size_t first = np, count = phi_all.size() - np;
    const double x0 = ct * std::sin(phi_all[first]), x1 = ct * std::sin(phi_all[first + count - 1]);
    const double spacing = (x1 - x0) / static_cast<double>(count - 1);
    out.node.correlation = detail::correlation_length(columns, spacing);
    if (in.want_autocorrelation) out.autocorrelation = detail::mean_autocorrelation(columns);
  } else {
    out.node.correlation = 0.0;
  }
  return out;
}

}  // namespace plumage
