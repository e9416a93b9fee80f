// FeatherBsdf: the feather material as a renderer sees it (paper §5.2–5.3, §7.1–7.2; spec
// geometry-and-brdf §4.9–4.11). Reads a FeatherMaterial; evaluates the mean BRDF f̄ (paper
// Eq. 16) and BRDF instance k (paper Eq. 22); importance-samples the mean lobe; adds a small
// diffuse transmission lobe (paper §7.2, last paragraph).
//
// Values: eval() returns the BSDF f itself, in sr⁻¹, NOT cosine-weighted. The lobe model's
// L = f̄ · ω_o,z (lobe_model.hpp, spec §3) is divided by ω_o,z here; a renderer multiplies by
// |ω_o,z| itself. Sample weights are f·|ω_o,z|/pdf.
//
// Directions: unit vectors in the BRDF frame (conventions.hpp: x across the barbule, y along it,
// z the macro normal), ω_i toward the light, ω_o toward the viewer. The BSDF is two-sided: for
// ω_i,z < 0 both directions are mirrored through the xy-plane (the barbule's other face is
// modelled like the front, an approximation). ω_o on ω_i's side is reflection, on the other
// side diffuse transmission. ω_i,z = 0 gives 0.
//
// Symmetry (spec §4.9 step 1): parameters depend on (cos θ_i, cos φ_i) only; for θ_i < 0 the
// lobe is mirrored in y, for φ_i < 0 in x. The instance noise is NOT mirrored: it is indexed by
// the world-frame x = ω_i,x + ω_o,x (paper Eq. 24), so an instance varies continuously when φ_i
// changes sign (the reference code's mirrored lookup would jump from q(x) to q(−x) at φ_i = 0).
//
// Wavelength: floor binning λ → bin w (FeatherMaterial::wavelength_bin, spec §4.9 step 7); no
// interpolation across bins.
//
// Energy (white furnace): the reflected directional albedo A_r(λ, ω_i) = ∫ f̄ cos dω equals the
// simulated reflected energy E at the table nodes (the fitter's F_eff normalisation, paper
// Eq. 12), but between nodes the interpolated F_eff·cos θ_i cos φ_i and m_eff need not keep
// A_r ≤ 1 (measured: up to A_r = 2.3 in the first, grazing cell of a worst-case material,
// +0.4 % between interior nodes; docs/validation.md "BSDF"). So, per wavelength bin w:
//   * A_r is computed on a fine (cos θ_i, cos φ_i) table: the nodes, the edge midpoints and
//     centres of every cell, and extra rows 1/8, 1/4, 3/4 of the way into the grazing cells;
//     a cheap Gauss–Legendre screen over the sampler's unit square everywhere; within 0.15 of
//     the cap the same with the horizon crossings as panel breaks (≤ 1.7 % error, measured);
//     within 0.05 of the cap the fitter's accurate hemisphere integral (fitter.hpp, the rule of
//     its Eq. 12 normalisation);
//   * the transmission albedo is T_w = min(requested, 1 − max_nodes A_r − margin), constant in
//     ω_i (so the Lambertian transmission T_w/π is reciprocal);
//   * the reflection (mean and statistics lobes alike, so instances stay unbiased) is scaled by
//     min(1, (1 − T_w − margin)/A_r), A_r bilinear in the fine table. At the nodes the scale is
//     1: the fitted BRDF is unchanged where it was fitted.
// Hence A_r + T ≤ 1 at every table entry; between fine-table points up to the bilinear error.
//
// Deterministic: no hidden random state; sample() takes the caller's uniform numbers.
// Thread-safe after construction (all methods const).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "plumage/conventions.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/lobe_model.hpp"

namespace plumage {

struct FeatherBsdfOptions {
  // Requested diffuse transmission albedo (fraction of the incident flux sent into the lower
  // hemisphere, Lambertian); reduced per wavelength bin where the reflection leaves less room.
  double transmission_albedo = 0.02;
  // n × n Gauss–Legendre estimate of A_r at each fine-table entry (energy budget above). 0
  // skips the pass: then T_w = 0 and no reflection clamp.
  int albedo_strata = 12;
  // Margin of the energy budget (the accurate integral's error is ~1e-7; the margin keeps
  // A_r + T visibly below 1 at the nodes).
  double albedo_margin = 1e-3;
};

struct BsdfSample {
  Direction wo;
  double f = 0.0;       // BSDF value at wo (mean or instance, as asked), sr⁻¹
  double pdf = 0.0;     // density of wo per solid angle (the full mixture pdf(), also below the horizon)
  double weight = 0.0;  // f·|wo_z|/pdf, 0 when pdf = 0
  bool transmitted = false;
};

class FeatherBsdf {
 public:
  explicit FeatherBsdf(std::shared_ptr<const FeatherMaterial> material, FeatherBsdfOptions options = {});

  const FeatherMaterial& material() const { return *material_; }
  const FeatherBsdfOptions& options() const { return options_; }

  // Everything that depends on (λ bin, ω_i) only: looked up once, used for many ω_o.
  struct Incident {
    std::size_t bin = 0;
    bool valid = false;          // ω_i,z ≠ 0 and a nonzero lobe
    double flip_z = 1.0;         // −1: ω_i came from below (two-sided mirroring)
    double mirror_x = 1.0;       // −1: φ_i < 0 (spec §4.9 step 1)
    double mirror_y = 1.0;       // −1: θ_i < 0
    double theta_abs = 0.0;      // |θ_i|
    double wi_x_world = 0.0;     // ω_i,x in the world frame, for the noise coordinate (Eq. 24)
    MaterialNode p;              // looked-up parameters (F's divided back, spec §4.9 step 2)
    Lobe mean, stats;            // Eq. 16 and Eq. 20 lobes
    Direction w_eff;             // ω_eff (mirrored frame)
    bool reflects = false;       // the mean lobe is nonzero (F_eff > 0, ω_eff above the horizon)
    double energy_scale = 1.0;   // reflection clamp (energy budget above), already in mean/stats
    double transmission = 0.0;   // T_w
    double p_transmit = 0.0;     // probability that sample() picks the transmission lobe
  };
  Incident incident(double lambda_nm, const Direction& wi) const;
  Incident incident_bin(std::size_t bin, const Direction& wi) const;

  // What an Incident needs of ω_i alone, shared by all wavelength bins of one direction (a
  // spectral renderer asks for 4 bins per direction): cosines, |θ_i|, the material table's cell
  // and Hermite weights, the energy table's cell.
  struct IncidentGeometry {
    Direction wi;
    double ct = 0.0, cp = 0.0, theta_abs = 0.0;
    MaterialLookupTable::Point point;
    std::size_t energy_a = 0, energy_b = 0;  // energy table cell (axis indices)
    double energy_u = 0.0, energy_v = 0.0;   // and its bilinear weights
  };
  IncidentGeometry incident_geometry(const Direction& wi) const;
  // incident_bin(bin, wi) = incident_bin(bin, incident_geometry(wi)), bit for bit.
  Incident incident_bin(std::size_t bin, const IncidentGeometry& geometry) const;

  // Mean BSDF f̄ (Eq. 16 for reflection, spec §4.9 step 3) plus transmission T_w/π.
  double eval(double lambda_nm, const Direction& wi, const Direction& wo) const;
  double eval(const Incident& in, const Direction& wo) const;
  // BSDF instance k (Eq. 22, spec §4.9 steps 4–6); transmission as for the mean. E_k[f_k] = f̄.
  double eval(double lambda_nm, const Direction& wi, const Direction& wo, std::uint64_t instance) const;
  double eval(const Incident& in, const Direction& wo, std::uint64_t instance) const;

  // Density per solid angle of sample()'s ω_o (whole sphere).
  double pdf(double lambda_nm, const Direction& wi, const Direction& wo) const;
  double pdf(const Incident& in, const Direction& wo) const;

  // u_component picks the lobe (transmission with probability p_transmit); (u1, u2) drive it.
  // The mean lobe is sampled through its half vector (lobe_sampling.hpp); samples that land
  // below the horizon are returned with f = 0 and their true pdf.
  BsdfSample sample(double lambda_nm, const Direction& wi, double u_component, double u1, double u2) const;
  BsdfSample sample(const Incident& in, double u_component, double u1, double u2) const;
  // The same direction, f and weight of instance k (importance sampling by the mean, paper §7.2).
  BsdfSample sample(const Incident& in, double u_component, double u1, double u2, std::uint64_t instance) const;

  // Reflected directional albedo ∫_{H+} f̄ cos dω (stratified n × n importance sampling of the
  // mean lobe; exact up to the stratification error).
  double reflection_albedo(const Incident& in, int strata) const;
  double transmission_albedo(std::size_t bin) const { return transmission_.empty() ? 0.0 : transmission_[bin]; }
  // Largest estimated A_r over the nodes of a bin (before the clamp).
  double max_reflection_albedo(std::size_t bin) const { return max_albedo_.empty() ? 0.0 : max_albedo_[bin]; }
  // The fine (cos θ_i, cos φ_i) axis of the energy table (same for both cosines).
  const std::vector<double>& energy_axis() const { return axis_; }

  // The noise value of one function of the pool at x = ω_i,x + ω_o,x, domain scale l = the
  // relative correlation length l/l0 (spec §4.9 steps 2 and 5): variance-preserving linear
  // interpolation. Returns false where the instance falls back to the mean (|x| > l_min, the
  // smallest relative l over the bins at normal incidence, or |x/l| > 1).
  bool noise_value(std::size_t function, double x, double l, double* value) const;

 private:
  void compute_energy_budget();  // feather_bsdf_energy.cpp
  Incident raw_incident(std::size_t bin, const IncidentGeometry& geometry) const;
  IncidentGeometry make_geometry(double cos_theta, double cos_phi, const Direction& wi) const;
  void locate_energy(double v, std::size_t& index, double& weight) const;
  double energy_scale(std::size_t bin, const IncidentGeometry& geometry) const;
  double screen_albedo(const Incident& in, int strata) const;

  std::shared_ptr<const FeatherMaterial> material_;
  MaterialLookupTable table_;  // material_->lookup() with the node data precomputed (same values)
  FeatherBsdfOptions options_;
  double l_min_ = 0.0;
  std::vector<double> transmission_, max_albedo_, p_transmit_;
  std::vector<double> axis_, albedo_table_;  // [bin][cos θ_i][cos φ_i] on axis_ × axis_
  std::vector<std::size_t> axis_start_;      // upper_bound(axis_, c/M) for c = 0 … M (fast locate)
};

}  // namespace plumage
