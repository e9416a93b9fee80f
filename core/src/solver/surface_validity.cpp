#include "surface_validity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "plumage/conventions.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/geometry.hpp"

namespace plumage::detail {

namespace {

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buffer[320];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c, d);
  return buffer;
}

}  // namespace

TopSurfaceStatistics top_surface_statistics(std::span<const Vec2> top, std::span<const Vec2> normals,
                                            std::span<const double> window, std::span<const double> node_length,
                                            double window_nm) {
  TopSurfaceStatistics out;
  out.window_nm = window_nm;
  const std::size_t n = normals.size();  // interior nodes: top[m + 1]
  if (n == 0 || top.size() < n + 2) return out;
  std::vector<double> s(n), beta(n), w(n);
  double arc = 0.0;
  for (std::size_t m = 0; m < n; ++m) {
    arc += norm(top[m + 1] - top[m]);
    s[m] = arc;
    beta[m] = std::atan2(normals[m].x, normals[m].z);
    w[m] = window[m] * window[m] * node_length[m];
  }
  // Weighted least squares β ≈ β̄ + κ̄ (s − s̄).
  double sw = 0, ss = 0, sb = 0;
  for (std::size_t m = 0; m < n; ++m) sw += w[m], ss += w[m] * s[m], sb += w[m] * beta[m];
  if (!(sw > 0.0)) return out;
  const double s_mean = ss / sw, b_mean = sb / sw;
  double sxx = 0, sxy = 0;
  for (std::size_t m = 0; m < n; ++m) {
    sxx += w[m] * (s[m] - s_mean) * (s[m] - s_mean);
    sxy += w[m] * (s[m] - s_mean) * (beta[m] - b_mean);
  }
  const double kappa = sxx > 0.0 ? sxy / sxx : 0.0;
  double r2 = 0.0;
  for (std::size_t m = 0; m < n; ++m) {
    const double d = beta[m] - b_mean - kappa * (s[m] - s_mean);
    r2 += w[m] * d * d;
  }
  out.rough_slope_rad = std::sqrt(r2 / sw);
  out.mean_curvature_per_nm = std::abs(kappa);
  out.curvature_spread_rad = std::abs(kappa) * std::sqrt(sxx / sw);
  out.mean_normal_rad = b_mean;
  out.weight = sw;
  return out;
}

TopSurfaceStatistics top_surface_statistics(const CrossSection& section, double window_fraction) {
  const Polyline& top = section.top;
  if (top.size() < 3) return {};
  const auto all = vertex_normals(top);
  const double x0 = 0.5 * (top.front().x + top.back().x);
  const double s = window_fraction * section.width_nm();
  std::vector<Vec2> normals;
  std::vector<double> window, length;
  for (std::size_t i = 1; i + 1 < top.size(); ++i) {
    normals.push_back(all[i]);
    const double x = top[i].x - x0;
    window.push_back(std::exp(-(x * x) / (s * s)));
    length.push_back(0.5 * (norm(top[i] - top[i - 1]) + norm(top[i + 1] - top[i])));
  }
  return top_surface_statistics(top, normals, window, length, s);
}

double horizon_spill(const TopSurfaceStatistics& stats, double lambda_nm, double theta_i_rad, double phi_i_rad) {
  const double gamma0 = 2.0 * kPi / lambda_nm * std::cos(theta_i_rad);
  const double phi_r = 2.0 * stats.mean_normal_rad - phi_i_rad;
  const double room = 0.5 * kPi - std::abs(phi_r) - 2.0 * stats.rough_slope_rad;
  const double spread = gamma0 * stats.window_nm * std::cos(phi_r);
  if (!(room > 0.0) || !(spread > 0.0)) return std::numeric_limits<double>::infinity();
  return 2.0 / spread / room;
}

// The messages carry the limits and name the instance (a geometry has one instance and seed,
// whatever the scheduling), not the values of the raise: a code is kept with its smallest
// message, and a fixed message per code and instance keeps the files that carry the warnings
// reproducible (counts add up across shards). The values go to the caller's WarningSites
// (warn_at), which turns them into "where and how much" (the material's warnings, simulate's list
// of instances); they are also in the study's CSV and in the statistics above.
double max_rough_slope(double curvature_spread_rad) {
  const double t = std::min(curvature_spread_rad / kCurvedSpreadRad, 1.0);
  return kMaxRoughSlopeRad + t * (kMaxRoughSlopeCurvedRad - kMaxRoughSlopeRad);
}

std::string instance_name(const CrossSection& section) {
  char seed[32];
  std::snprintf(seed, sizeof seed, "0x%016llx", static_cast<unsigned long long>(section.seed));
  return "instance " + std::to_string(section.instance) + " (seed " + seed + ")" +
         (section.label.empty() ? std::string() : " of " + section.label);
}

void warn_if_rough(const TopSurfaceStatistics& stats, const std::string& instance, std::size_t index) {
  if (stats.rough_slope_rad > max_rough_slope(stats.curvature_spread_rad)) {
    warn_at("approx.rough_surface",
            "approximate solver: " + instance + ": " +
                format("top-surface rms slope under the window above %.2f rad (%.2f on a top curved by %.1f rad "
                       "across the window), beyond the roughness checked against the full-wave BEM (pattern error "
                       "above %.0f %% there)",
                       kMaxRoughSlopeRad, kMaxRoughSlopeCurvedRad, kCurvedSpreadRad, 15.0),
            WarningSite::Item::instance, index, stats.rough_slope_rad);
  }
}

void warn_if_curved(const TopSurfaceStatistics& stats, double lambda_nm, const std::string& instance,
                    std::size_t index) {
  const double radius = stats.mean_curvature_per_nm > 0.0 ? 1.0 / stats.mean_curvature_per_nm
                                                          : std::numeric_limits<double>::infinity();
  if (radius < kMinRadiusWavelengths * lambda_nm) {
    warn_at("approx.high_curvature",
            "approximate solver: " + instance + ": " +
                format("top-surface radius of curvature under the window below %.1f wavelengths, beyond the "
                       "curvature checked against the full-wave BEM (pattern error above %.0f %% there)",
                       kMinRadiusWavelengths, 15.0),
            WarningSite::Item::instance, index, radius / lambda_nm);
  }
}

void warn_if_grazing(const TopSurfaceStatistics& stats, double lambda_nm, double theta_i_rad, double phi_i_rad,
                     std::size_t item) {
  const double spill = horizon_spill(stats, lambda_nm, theta_i_rad, phi_i_rad);
  if (spill > kMaxHorizonSpill) {
    warn_at("approx.grazing",
            format("approximate solver: near-grazing incidence, the window's specular lobe reaches the horizon (lobe "
                   "half-width over its distance to phi_o = +-90 deg above %.1f): Eq. 9 and the pattern are "
                   "unreliable (full-wave BEM: pattern error above %.0f %%)",
                   kMaxHorizonSpill, 15.0),
            WarningSite::Item::azimuth, item, spill);
  }
}

}  // namespace plumage::detail
