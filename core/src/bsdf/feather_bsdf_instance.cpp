// BSDF instances (paper Eqs. 19–24; spec geometry-and-brdf §4.9 steps 4–6): the mean lobe f̄
// and the statistics lobe s̄ give, per polarization p, the intensity I_p = 2 r_p f̄, its
// coherent part S_p = min(2 r_p s̄, I_p) and the variance V_p = I_p − S_p. The field of
// instance k is √S_p + √(V_p/2)·(±n_Re + i n_Im) with two noise functions n of the pool, so
// E[f_k] = ½ Σ_p (S_p + V_p) = f̄ whenever the pool is zero-mean and unit-variance (Eq. 23).
#include <algorithm>
#include <cmath>

#include "plumage/feather_bsdf.hpp"

namespace plumage {

bool FeatherBsdf::noise_value(std::size_t function, double x, double l, double* value) const {
  const NoisePool& pool = material_->noise;
  const std::size_t count = pool.count();
  // No noise beyond l_min, shared by all wavelengths (spec §4.9 step 5).
  if (count == 0 || !(l > 0.0) || std::abs(x) > l_min_) return false;
  const double u = x / l;  // Eq. 24: the unit-domain coordinate
  // Where l(λ, ω_i) < l_min the query can leave the sampled domain; the reference pads with
  // zeros there, which would lower the variance and bias the instance: we fall back to f̄.
  if (std::abs(u) > 1.0) return false;
  const int n = pool.samples;
  const float* q = pool.function(function);
  const double pos = 0.5 * (u + 1.0) * n - 0.5;  // u_t = −1 + (2t + 1)/n ↔ pos = t
  if (pos <= 0.0) {
    *value = q[0];  // the half-sample rims: constant extension keeps unit variance
  } else if (pos >= n - 1) {
    *value = q[n - 1];
  } else {
    const int t = static_cast<int>(pos);
    const double s = pos - t, a = pool.lag1;
    // Variance-preserving interpolation (spec §4.9 step 5).
    *value = ((1.0 - s) * q[t] + s * q[t + 1]) / std::sqrt((1.0 - s) * (1.0 - s) + s * s + 2.0 * s * (1.0 - s) * a);
  }
  return true;
}

double FeatherBsdf::eval(double lambda_nm, const Direction& wi, const Direction& wo, std::uint64_t instance) const {
  return eval(incident(lambda_nm, wi), wo, instance);
}

double FeatherBsdf::eval(const Incident& in, const Direction& wo, std::uint64_t instance) const {
  if (!in.valid) return 0.0;
  const Direction o{wo.x * in.mirror_x, wo.y * in.mirror_y, wo.z * in.flip_z};
  if (!(o.z > 0.0) || !in.reflects) return eval(in, wo);  // transmission is not instanced
  const double mean = lobe_value(in.mean, in.theta_abs, o) / o.z;
  if (!(mean > 0.0)) return 0.0;
  // Noise coordinate in the world frame (Eq. 24), functions 2k and 2k + 1 of the pool.
  const std::size_t count = material_->noise.count();
  if (count == 0) return mean;
  const std::size_t k = static_cast<std::size_t>(instance % count);
  const double x = in.wi_x_world + wo.x;
  // The domain scale is the RELATIVE correlation length l/l0 (spec §4.9 steps 2 and 5): the
  // pool was synthesised on the x-grid of the reference unit (spacing 2/samples), where the
  // correlation length is l0, so elsewhere x ↔ u = x/(l/l0).
  const double l = in.p.correlation;
  double n_re = 0.0, n_im = 0.0;
  if (!noise_value((2 * k) % count, x, l, &n_re) || !noise_value((2 * k + 1) % count, x, l, &n_im)) return mean;
  const double stats = lobe_value(in.stats, in.theta_abs, o) / o.z;
  const double r1 = in.p.pol_share, r2 = 1.0 - r1;
  const double i1 = 2.0 * r1 * mean, i2 = 2.0 * r2 * mean;
  const double s1 = std::clamp(2.0 * r1 * stats, 0.0, i1), s2 = std::clamp(2.0 * r2 * stats, 0.0, i2);
  const double v1 = i1 - s1, v2 = i2 - s2;
  const double re1 = std::sqrt(s1) + std::sqrt(0.5 * v1) * n_re;
  const double re2 = std::sqrt(s2) - std::sqrt(0.5 * v2) * n_re;  // polarization 2: real part negated
  return 0.5 * (re1 * re1 + 0.5 * v1 * n_im * n_im + re2 * re2 + 0.5 * v2 * n_im * n_im);
}

}  // namespace plumage
