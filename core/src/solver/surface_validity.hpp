// Where the approximate solver's input is beyond the range in which its accuracy was measured
// against the full-wave BEM (issue 9's stability study; docs/validation.md "Roughness, curvature
// and grazing: where the approximate solver holds"): statistics of the top surface under the
// window, computed from the input geometry alone, and the criteria that turn them into warnings
// (plumage/diagnostics.hpp codes approx.rough_surface, approx.high_curvature, approx.grazing).
#pragma once

#include <span>
#include <string>

#include "plumage/cross_section.hpp"

namespace plumage::detail {

// Statistics of the top polyline's interior nodes, each weighted by its share of the incident
// power at normal incidence (window² × node length, as in Eq. 9):
//  * the node normals' angle β(s) (from +z, positive toward +x) along the arc length s, fitted by
//    a weighted straight line β ≈ β̄ + κ̄ (s − s̄): κ̄ is the mean curvature under the window (a
//    circular arc has β linear in s), 1/|κ̄| its radius;
//  * `rough_slope_rad`: the weighted rms of β about that line, the slope of whatever is not a
//    constant-curvature arc — the roughness (≈ σ/τ for a Gaussian-correlated height profile of
//    rms σ and correlation length τ, flat or curved body alike).
//  * `curvature_spread_rad`: |κ̄| × the weighted rms of s − s̄, the rms turn of the normal that the
//    mean curvature alone causes across the lit window (0.1 rad for a 4 µm arc of 4 µm radius
//    under s = 0.8 µm).
struct TopSurfaceStatistics {
  double rough_slope_rad = 0.0;
  double mean_curvature_per_nm = 0.0;  // |κ̄|
  double curvature_spread_rad = 0.0;
  double mean_normal_rad = 0.0;        // β̄
  double window_nm = 0.0;              // s of the window exp(−x²/s²)
  double weight = 0.0;                 // Σ weights (0: no interior node)
};
TopSurfaceStatistics top_surface_statistics(std::span<const Vec2> top, std::span<const Vec2> normals,
                                            std::span<const double> window, std::span<const double> node_length,
                                            double window_nm);
// The same for a cross section as the approximate solver sees it (vertex normals, Gaussian
// window exp(−x²/s²) with s = window_fraction × width, centred between the top's ends).
TopSurfaceStatistics top_surface_statistics(const CrossSection& section, double window_fraction);

// Measured limits (docs/validation.md, tests/test_solver_stability_study.cpp, which checks them
// against the BEM). Inside them the approximate pattern was within 15 % (relative L2, mean of
// λ = 550/650 nm and φ_i = 0°/−30°) of the full-wave one on 300 nm keratin films; beyond them
// the error was above that.
// Roughness: on flat tops rms slope ≤ 0.108 held (≤ 0.105) and ≥ 0.13 mostly did not (0.13–0.25,
// ≥ 0.23 from 0.2 on), whatever the correlation length (0.25–1 µm): limit 0.12. On a top whose
// window also spans curvature (curvature_spread 0.1 rad: a 4 µm arc of 4 µm radius) roughness
// compounds with it: slope 0.043 held (0.055), 0.067 did not (0.18). The limit falls linearly from
// 0.12 (flat) to 0.05 at a spread of 0.1 and stays there beyond (not measured with roughness).
constexpr double kMaxRoughSlopeRad = 0.12;
constexpr double kMaxRoughSlopeCurvedRad = 0.05;
constexpr double kCurvedSpreadRad = 0.1;
double max_rough_slope(double curvature_spread_rad);
// Curvature: compared with the mean radius under the window. Films curved down to 2.5 µm and
// melanin cylinders down to 1.5 µm (2.3 λ at 650 nm) held (≤ 0.14); a 1 µm cylinder (1.5–1.8 λ)
// did not (0.27), nor one of 0.6 µm.
constexpr double kMinRadiusWavelengths = 2.0;
// Grazing: the windowed specular lobe's 1/e² half-width in φ_o, 2/(γ0 s cos φ_r), over its
// distance to the end of the pattern range, π/2 − |φ_r| (less twice the rough slope, whose
// normals tilt the lobe toward the horizon). Beyond 0.5 the lobe runs into the horizon: the
// pattern is the window's diffraction and Eq. 9 stops bounding the power (the flat mirror's
// R = 0.68 … 1.56 of the grazing rows).
constexpr double kMaxHorizonSpill = 0.5;

// The spill ratio above for one incident direction (φ_r = 2β̄ − φ_i mirrored about the mean
// normal); +∞ when the specular direction is at or beyond the horizon.
double horizon_spill(const TopSurfaceStatistics& stats, double lambda_nm, double theta_i_rad, double phi_i_rad);

// Raise approx.rough_surface / approx.high_curvature (per geometry; `lambda_nm` > 0 for the
// curvature check) and approx.grazing (per incident direction) when beyond the limits above.
// `instance` names the geometry ("instance 3 (seed 0x…) of species/variant", instance_name()):
// the per-geometry warnings say which instance; they are raised through warn_at() with the
// instance index as item (rough) and the azimuth's index `item` in the solve (grazing), so a
// caller's WarningSites learns which instance or unit raised them and by how much (the rms slope,
// the radius in wavelengths, the spill ratio).
std::string instance_name(const CrossSection& section);
void warn_if_rough(const TopSurfaceStatistics& stats, const std::string& instance, std::size_t index);
void warn_if_curved(const TopSurfaceStatistics& stats, double lambda_nm, const std::string& instance,
                    std::size_t index);
void warn_if_grazing(const TopSurfaceStatistics& stats, double lambda_nm, double theta_i_rad, double phi_i_rad,
                     std::size_t item);

}  // namespace plumage::detail
