// Energy budget of FeatherBsdf: reflected directional albedo by stratified importance sampling
// and the transmission albedo T_w that keeps A_r + T ≤ 1 at every table entry (paper §7.2, last
// paragraph; spec geometry-and-brdf §4.11).
#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "plumage/feather_bsdf.hpp"
#include "plumage/lobe_sampling.hpp"

namespace plumage {

double FeatherBsdf::reflection_albedo(const Incident& in, int strata) const {
  if (!in.valid || !in.reflects || strata < 1) return 0.0;
  const HalfVectorSampler sampler(in.mean.m, in.mean.sigma);
  double sum = 0.0;
  for (int a = 0; a < strata; ++a) {
    for (int b = 0; b < strata; ++b) {
      const Direction h = sampler.sample((a + 0.5) / strata, (b + 0.5) / strata);
      const Direction o = reflect(in.w_eff, h);
      if (!(o.z > 0.0)) continue;
      const double p = reflected_pdf(sampler, in.w_eff, o);
      if (p > 0.0) sum += lobe_value(in.mean, in.theta_abs, o) / p;  // L = f̄ cos (spec §3)
    }
  }
  return sum / (static_cast<double>(strata) * strata);
}

void FeatherBsdf::compute_energy_budget() {
  const FeatherMaterial& m = *material_;
  const std::size_t bins = m.lambda_nm.size();
  transmission_.assign(bins, 0.0);
  p_transmit_.assign(bins, 0.0);
  max_albedo_.assign(bins, 0.0);
  if (!(options_.transmission_albedo > 0.0) || options_.albedo_strata < 1) return;
  std::vector<double> mean_albedo(bins, 0.0);
  tbb::parallel_for(std::size_t{0}, bins, [&](std::size_t w) {
    const int g = m.grid;
    double worst = 0.0, total = 0.0;
    int count = 0;
    auto visit = [&](double ct, double cp) {
      const Direction wi = direction_from_angles(std::acos(ct), std::acos(cp));
      const double a = reflection_albedo(incident_bin(w, wi), options_.albedo_strata);
      worst = std::max(worst, a);
      total += a;
      ++count;
    };
    // Nodes (i, j ≥ 1; row and column 0 are grazing, F = 0) and cell centres.
    for (int i = 1; i <= g; ++i)
      for (int j = 1; j <= g; ++j) visit(static_cast<double>(i) / g, static_cast<double>(j) / g);
    for (int i = 0; i < g; ++i)
      for (int j = 0; j < g; ++j) visit((i + 0.5) / g, (j + 0.5) / g);
    max_albedo_[w] = worst;
    mean_albedo[w] = total / count;
  });
  for (std::size_t w = 0; w < bins; ++w) {
    transmission_[w] = std::clamp(1.0 - max_albedo_[w] - options_.albedo_margin, 0.0, options_.transmission_albedo);
    // Lobe choice in proportion to the albedos (constant per bin, so pdf() stays cheap).
    const double t = transmission_[w];
    p_transmit_[w] = t > 0.0 ? t / (t + std::max(mean_albedo[w], 1e-3)) : 0.0;
  }
}

}  // namespace plumage
