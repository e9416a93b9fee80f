// From simulated far fields to the lobe parameters of one work unit (paper §5, Eqs. 11–13;
// spec geometry-and-brdf §4.1–4.6), and from all units to a FeatherMaterial (§4.7–4.8).
//
// A work unit is (λ, cos θ_i = a/G, cos φ_i = b/G) with the far fields of every instance, at the
// pattern directions (spec §0.4, first `pattern_count` entries) followed by the on-cone
// projected directions (`projected_directions`). fit_unit() is a function of its input alone:
// single-threaded, deterministic (coarse grid search, then Ceres with one thread), so shards,
// MPI ranks and single runs produce identical records. Besides its result it may raise the
// warnings fit.near_zero_energy and fit.two_lobes (plumage/diagnostics.hpp, issue 9).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "plumage/far_field.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/lobe_model.hpp"

namespace plumage {

// Revision of what fitting and assembly make of the same far fields. Bumped whenever this code
// changes the numbers a work record or a material holds, so that journals, shard files and
// cached materials of older code are never mixed with new ones (characterize_settings.hpp).
// 3: records carry their warning codes; fits normalise the pattern's scale and give a zero lobe
// for near-zero energy (issue 9).
inline constexpr int kFitRevision = 3;

// ---- lobe on the specular cone (spec §4.2) ----------------------------------------------------

// The fitted shape of a pattern: G_k = D(h; m) G1(ω_i'; m) G1(ω_o,k; m) on the cone (spec §4.2).
// On the cone h_y = 0 and h_x = sin((φ_c + φ_o)/2), so D_y = 1.
std::vector<double> cone_lobe_shape(double theta_i_rad, double m, double phi_c_rad,
                                    std::span<const double> phi_o_rad);

struct ConeFit {
  double m = 0.1;
  double phi_c_rad = 0.0;
  double rel_l2 = 0.0;  // ‖U − Ĝ‖ / ‖U‖ with Ĝ energy-matched (spec §4.2)
};

// GGX fit of (m, φ_c) to a non-negative pattern on the cone with energy matching and the grazing
// blend of φ_c (spec §4.2): deterministic coarse search over (m, φ_c), then a Ceres refinement;
// m ∈ [0.001, 1], φ_c ∈ [−89.5°, 89.5°]. `phi_i_rad` is the nominal incident azimuth.
ConeFit fit_cone_lobe(double theta_i_rad, double phi_i_rad, std::span<const double> phi_o_rad,
                      std::span<const double> pattern);

// ---- hemisphere integral of a lobe (spec §4.3) ------------------------------------------------

// ∫_{H²} L(ω_o) dω_o for the lobe (scale included), by tensor Gauss–Legendre on panels graded
// geometrically around the lobe's peak (θ_o = −θ_i, φ_o = −φ_c) with the lobe's widths σ and m.
// Error against a converged brute-force rule: tests/test_fit_integral.cpp.
double hemisphere_lobe_integral(const Lobe& lobe, double theta_i_rad);
// The spec's reference rule: n × n midpoints in (θ_o, φ_o) ∈ (−π/2, π/2)², dω = cos θ_o dθ dφ.
double hemisphere_lobe_integral_midpoint(const Lobe& lobe, double theta_i_rad, int n);

// Σ_k L(ω_o,k) over `midpoints` midpoints in φ_o ∈ (−π/2, π/2) on the specular cone
// ω_o = (cos θ_i sin φ_o, −sin θ_i, cos θ_i cos φ_o): the cone sums of the F_sta ratio (spec §4.4).
double cone_lobe_sum(const Lobe& lobe, double theta_i_rad, int midpoints = 2000);

// ---- correlation length and autocorrelation (spec §4.6, §4.8) ----------------------------------

// Columns of equal length N. Circular autocovariance of each mean-removed column (divisor N − 1),
// summed over columns and normalised by lag 0; the first lag where it drops below e⁻¹, linearly
// interpolated, times `spacing` (spec §4.6 steps 4–5). Lags beyond N/2 − 1 are not examined; a
// correlation that never drops returns (N/2 − 1) · spacing.
double correlation_length(const std::vector<std::vector<double>>& columns, double spacing);
// The mean normalised circular autocorrelation over all rows, mirrored to a full period of N
// (spec §4.8 step 2): lags 0 … N/2 − 1, lag N/2 the mean of its neighbours, then N/2 − 1 … 1.
std::vector<double> mean_autocorrelation(const std::vector<std::vector<double>>& columns);

// ---- one work unit --------------------------------------------------------------------------

struct UnitInput {
  double lambda_nm = 0.0;
  double theta_i_rad = 0.0;  // nominal
  double phi_i_rad = 0.0;    // nominal (instances carry their jitter)
  double sigma = kLobeSigma;  // D_y spread used for F (spec §4.3)
  std::size_t pattern_count = 0;
  std::span<const FarField> instances;  // pattern directions then the on-cone projected ones
  bool want_autocorrelation = false;    // the reference unit (first λ, normal incidence), §4.8
};

struct UnitFit {
  MaterialNode node;  // f_eff, f_sta premultiplied by cos θ_i cos φ_i; correlation = absolute l
  double rel_l2_eff = 0.0;  // fit quality of the mean lobe on the cone
  double rel_l2_sta = 0.0;  // of the statistics lobe
  double energy = 0.0;      // E: reflected fraction on the cone (∫ U dφ_o)
  std::vector<double> mean_pattern;  // U on the pattern directions (spec §4.1)
  std::vector<double> fit_pattern;   // the energy-matched fitted lobe Ĝ at the same directions
  std::vector<double> autocorrelation;  // only when want_autocorrelation
};

UnitFit fit_unit(const UnitInput& input);

// ---- assembly (spec §4.7) and the noise pool (§4.8) ---------------------------------------------

// `material.nodes` holds fitted values at i, j ≥ 1 with correlation = absolute l. Sets l0 from
// the first bin's normal-incidence node, divides correlation by it, fills the grazing row i = 0
// and column j = 0 per spec §4.7 and smooths m_eff, m_sta and correlation. Then (a departure
// from the spec, which smooths m after F was normalised) every fitted node's F_eff is
// renormalised so that the stored lobe keeps the fitted directional albedo,
// ∫ L dω (smoothed m) = ∫ L dω (fitted m) = E (Eq. 12, the accurate hemisphere integral), and
// F_sta is recomputed by the §4.4 cone-sum ratio with the stored lobes. Without this, smoothing
// lowered m at the grazing nodes by ~10 % and raised A_r there by up to 20 % (A_r = 1.17 on the
// rock-dove preview material, docs/validation.md "BSDF").
void assemble_tables(FeatherMaterial& material);

// `count` functions of `acf.size()` samples with autocorrelation `acf` (a full circular period,
// acf[0] = 1): random-phase synthesis through FFTW (spec §4.8 step 5) without the DC and Nyquist
// terms, each function then shifted to zero mean and scaled to unit variance (population
// variance over its samples). Function k draws from RandomStream(seed, k).
NoisePool synthesize_noise_pool(const std::vector<double>& acf, int count, std::uint64_t seed);

}  // namespace plumage
