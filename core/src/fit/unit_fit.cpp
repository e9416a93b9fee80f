// One work unit: far fields of every instance → the eight parameters of a MaterialNode
// (spec §4.1–4.6, paper §5 Eqs. 11–13).
#include <algorithm>
#include <array>
#include <cmath>

#include "plumage/error.hpp"
#include "plumage/fitter.hpp"

namespace plumage {

namespace {

double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

// Noise data (spec §4.6 steps 1–3): per polarization the dominant field component, its
// normalised fluctuations (Re and Im per instance), weighted by the mean lobe's shape
// D(h; m_eff) G1(ω_i') G1(ω_o) at ω_o = (x, −sin θ_i, √(1 − x² − sin² θ_i)).
std::vector<std::vector<double>> noise_columns(const UnitInput& in, const Lobe& mean_lobe) {
  const std::size_t first = in.pattern_count, count = in.instances.front().phi_o_rad.size() - first;
  const std::size_t n_inst = in.instances.size();
  std::vector<std::vector<double>> columns;
  if (count < 4 || n_inst < 2) return columns;
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
  for (int p = 0; p < 2; ++p) {
    // Dominant component: max Σ_x (μ_Re² + μ_Im² + v_Re + v_Im).
    int best_c = 0;
    double best = -1;
    std::array<std::vector<double>, 3> mre, mim, vre, vim;
    for (int c = 0; c < 3; ++c) {
      mre[c].assign(count, 0), mim[c].assign(count, 0), vre[c].assign(count, 0), vim[c].assign(count, 0);
      for (std::size_t r = 0; r < count; ++r) {
        for (const FarField& ff : in.instances) {
          mre[c][r] += ff.field[p][first + r][c].real();
          mim[c][r] += ff.field[p][first + r][c].imag();
        }
        mre[c][r] /= static_cast<double>(n_inst);
        mim[c][r] /= static_cast<double>(n_inst);
        for (const FarField& ff : in.instances) {
          const double dr = ff.field[p][first + r][c].real() - mre[c][r], di = ff.field[p][first + r][c].imag() - mim[c][r];
          vre[c][r] += dr * dr;
          vim[c][r] += di * di;
        }
        vre[c][r] /= static_cast<double>(n_inst - 1);
        vim[c][r] /= static_cast<double>(n_inst - 1);
      }
      double score = 0;
      for (std::size_t r = 0; r < count; ++r) score += mre[c][r] * mre[c][r] + mim[c][r] * mim[c][r] + vre[c][r] + vim[c][r];
      if (score > best) best = score, best_c = c;
    }
    const int c = best_c;
    for (int part = 0; part < 2; ++part) {
      for (const FarField& ff : in.instances) {
        std::vector<double> col(count);
        for (std::size_t r = 0; r < count; ++r) {
          const auto v = ff.field[p][first + r][c];
          const double mu = part == 0 ? mre[c][r] : mim[c][r];
          const double var = part == 0 ? vre[c][r] : vim[c][r];
          const double x = part == 0 ? v.real() : v.imag();
          col[r] = var > 0 ? (x - mu) / std::sqrt(var) * weight[r] : 0.0;
        }
        columns.push_back(std::move(col));
      }
    }
  }
  return columns;
}

}  // namespace

double cone_lobe_sum(const Lobe& lobe, double theta_i_rad, int midpoints) {
  const LobeEvaluator value(lobe, theta_i_rad);
  const double ct = std::cos(-theta_i_rad), st = std::sin(-theta_i_rad);
  double s = 0;
  for (int k = 0; k < midpoints; ++k) {
    const double phi_o = -0.5 * kPi + (k + 0.5) * kPi / midpoints;
    s += value(Direction{ct * std::sin(phi_o), st, ct * std::cos(phi_o)});  // direction_from_angles(−θ_i, φ_o)
  }
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
      for (std::size_t k = 0; k < np; ++k) {
        const double d = ff.reflectance_density(p, k);
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

  // §4.2 mean lobe, §4.3 F_eff = E / ∫ L_{F=1} dω.
  const ConeFit eff = fit_cone_lobe(in.theta_i_rad, in.phi_i_rad, phi_o, u);
  Lobe mean_lobe{eff.m, eff.phi_c_rad, in.sigma, 1.0};
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
  out.mean_pattern = u;

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

  // §4.6 correlation length on the projected samples (spacing 2/N in the direction cosine).
  mean_lobe.scale = 1.0;
  const auto columns = noise_columns(in, mean_lobe);
  if (!columns.empty()) {
    const std::size_t first = np, count = phi_all.size() - np;
    const double x0 = ct * std::sin(phi_all[first]), x1 = ct * std::sin(phi_all[first + count - 1]);
    const double spacing = (x1 - x0) / static_cast<double>(count - 1);
    out.node.correlation = correlation_length(columns, spacing);
    if (in.want_autocorrelation) out.autocorrelation = mean_autocorrelation(columns);
  } else {
    out.node.correlation = 0.0;
  }
  return out;
}

}  // namespace plumage
