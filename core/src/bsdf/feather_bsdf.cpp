// FeatherBsdf: parameter lookup with symmetry handling, the mean BSDF, its pdf and sampling
// (paper Eqs. 16–18, §7.2; spec geometry-and-brdf §4.9 steps 1–3, §4.10, §4.11).
#include <algorithm>
#include <cmath>

#include "plumage/error.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/lobe_sampling.hpp"

namespace plumage {

namespace {

// ω in the frame where the incident direction has θ_i, φ_i ≥ 0 and ω_i,z > 0.
Direction to_local(const FeatherBsdf::Incident& in, const Direction& w) {
  return {w.x * in.mirror_x, w.y * in.mirror_y, w.z * in.flip_z};
}

}  // namespace

FeatherBsdf::FeatherBsdf(std::shared_ptr<const FeatherMaterial> material, FeatherBsdfOptions options)
    : material_(std::move(material)), options_(options) {
  if (!material_) throw Error("FeatherBsdf: no material");
  const FeatherMaterial& m = *material_;
  const std::size_t per_bin = static_cast<std::size_t>(m.grid + 1) * static_cast<std::size_t>(m.grid + 1);
  if (m.grid < 1 || m.lambda_nm.empty() || m.nodes.size() != m.lambda_nm.size() * per_bin) {
    throw Error("FeatherBsdf: material " + m.label + " has inconsistent node tables");
  }
  if (!(m.sigma > 0.0)) throw Error("FeatherBsdf: material " + m.label + " has sigma <= 0");
  table_ = MaterialLookupTable(m);
  if (!(options_.transmission_albedo >= 0.0 && options_.transmission_albedo <= 1.0)) {
    throw Error("FeatherBsdf: transmission albedo must be in [0, 1]");
  }
  // Noise cut-off shared by all bins (spec §4.9 step 5): the smallest relative correlation
  // length l/l0 over the bins, at normal incidence (as FeatherMaterial::min_correlation_length,
  // which returns it times l0).
  l_min_ = 0.0;
  if (m.noise.count() > 0) {
    l_min_ = 1e300;
    for (std::size_t w = 0; w < m.lambda_nm.size(); ++w) l_min_ = std::min(l_min_, m.node(w, m.grid, m.grid).correlation);
  }
  compute_energy_budget();
}

FeatherBsdf::Incident FeatherBsdf::incident(double lambda_nm, const Direction& wi) const {
  return incident_bin(material_->wavelength_bin(lambda_nm), wi);
}

FeatherBsdf::Incident FeatherBsdf::incident_bin(std::size_t bin, const Direction& wi) const {
  return incident_bin(bin, incident_geometry(wi));
}

FeatherBsdf::IncidentGeometry FeatherBsdf::incident_geometry(const Direction& wi) const {
  if (wi.z == 0.0) {
    IncidentGeometry g;
    g.wi = wi;
    return g;
  }
  const double ct = std::min(1.0, std::sqrt(wi.x * wi.x + wi.z * wi.z));
  const double cp = ct > 0.0 ? std::min(1.0, std::abs(wi.z) / ct) : 0.0;
  return make_geometry(ct, cp, wi);
}

FeatherBsdf::IncidentGeometry FeatherBsdf::make_geometry(double ct, double cp, const Direction& wi) const {
  IncidentGeometry g;
  g.wi = wi;
  g.ct = ct;
  g.cp = cp;
  g.theta_abs = std::atan2(std::abs(wi.y), ct);
  g.point = table_.locate(ct, cp);
  if (!albedo_table_.empty()) {
    locate_energy(ct, g.energy_a, g.energy_u);
    locate_energy(cp, g.energy_b, g.energy_v);
  }
  return g;
}

FeatherBsdf::Incident FeatherBsdf::incident_bin(std::size_t bin, const IncidentGeometry& g) const {
  if (g.wi.z == 0.0) {
    Incident in;
    in.bin = bin;
    return in;
  }
  Incident in = raw_incident(bin, g);
  in.energy_scale = energy_scale(bin, g);
  in.mean.scale *= in.energy_scale;
  in.stats.scale *= in.energy_scale;
  in.transmission = transmission_albedo(bin);
  in.p_transmit = in.reflects ? (p_transmit_.empty() ? 0.0 : p_transmit_[bin]) : (in.transmission > 0.0 ? 1.0 : 0.0);
  return in;
}

// Lookup and symmetry only (spec §4.9 steps 1–2): no energy clamp, no transmission.
FeatherBsdf::Incident FeatherBsdf::raw_incident(std::size_t bin, const IncidentGeometry& g) const {
  Incident in;
  in.bin = bin;
  const Direction& wi = g.wi;
  if (wi.z == 0.0) return in;
  in.flip_z = wi.z < 0.0 ? -1.0 : 1.0;
  in.mirror_x = wi.x < 0.0 ? -1.0 : 1.0;  // φ_i < 0 (spec §4.9 step 1)
  in.mirror_y = wi.y < 0.0 ? -1.0 : 1.0;  // θ_i < 0
  in.wi_x_world = wi.x;
  in.theta_abs = g.theta_abs;
  in.p = table_.lookup(bin, g.point);  // = material_->lookup(bin, ct, cp), cheaper
  const double sigma = material_->sigma;
  in.mean = Lobe{in.p.m_eff, in.p.phi_eff, sigma, in.p.f_eff};
  in.stats = Lobe{in.p.m_sta, in.p.phi_sta, sigma, in.p.f_sta};
  in.w_eff = lobe::effective_incident(in.theta_abs, in.p.phi_eff);
  in.reflects = in.p.f_eff > 0.0 && in.w_eff.z > 0.0;
  in.valid = true;
  return in;
}

double FeatherBsdf::eval(double lambda_nm, const Direction& wi, const Direction& wo) const {
  return eval(incident(lambda_nm, wi), wo);
}

double FeatherBsdf::eval(const Incident& in, const Direction& wo) const {
  if (!in.valid) return 0.0;
  const Direction o = to_local(in, wo);
  if (o.z > 0.0) return in.reflects ? lobe_value(in.mean, in.theta_abs, o) / o.z : 0.0;  // L/ω_o,z (spec §3)
  if (o.z < 0.0) return in.transmission / kPi;                                            // Lambertian BTDF
  return 0.0;
}

double FeatherBsdf::pdf(double lambda_nm, const Direction& wi, const Direction& wo) const {
  return pdf(incident(lambda_nm, wi), wo);
}

double FeatherBsdf::pdf(const Incident& in, const Direction& wo) const {
  if (!in.valid) return 0.0;
  const Direction o = to_local(in, wo);
  double p = 0.0;
  if (in.reflects && in.p_transmit < 1.0) {
    p += (1.0 - in.p_transmit) * reflected_pdf(HalfVectorSampler(in.mean.m, in.mean.sigma), in.w_eff, o);
  }
  if (o.z < 0.0) p += in.p_transmit * (-o.z) / kPi;
  return p;
}

BsdfSample FeatherBsdf::sample(double lambda_nm, const Direction& wi, double u_component, double u1, double u2) const {
  return sample(incident(lambda_nm, wi), u_component, u1, u2);
}

BsdfSample FeatherBsdf::sample(const Incident& in, double u_component, double u1, double u2) const {
  BsdfSample s;
  if (!in.valid || (!in.reflects && in.p_transmit <= 0.0)) return s;
  Direction o;
  if (u_component < in.p_transmit) {
    // Cosine-weighted lower hemisphere.
    const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    o = {r * std::cos(phi), r * std::sin(phi), -std::sqrt(std::max(0.0, 1.0 - u1))};
    s.transmitted = true;
  } else {
    o = reflect(in.w_eff, HalfVectorSampler(in.mean.m, in.mean.sigma).sample(u1, u2));
  }
  s.wo = to_local(in, o);  // the mirrorings are involutions
  s.f = eval(in, s.wo);
  s.pdf = pdf(in, s.wo);
  s.weight = s.pdf > 0.0 ? s.f * std::abs(s.wo.z) / s.pdf : 0.0;
  return s;
}

BsdfSample FeatherBsdf::sample(const Incident& in, double u_component, double u1, double u2,
                               std::uint64_t instance) const {
  BsdfSample s = sample(in, u_component, u1, u2);
  if (s.pdf > 0.0) {
    s.f = eval(in, s.wo, instance);
    s.weight = s.f * std::abs(s.wo.z) / s.pdf;
  }
  return s;
}

}  // namespace plumage
