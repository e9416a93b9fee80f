#include "multilayer_reflection.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "plumage/error.hpp"
#include "plumage/layer_profile.hpp"
#include "stack_solver.hpp"

namespace plumage::multilayer {

namespace {

// Refractive indices at one wavelength, with keratin and melanin (Eq. 1) evaluated once per
// wavelength rather than once per layer and request.
class IndexAtWavelength {
 public:
  void set_wavelength(double lambda_nm) {
    if (lambda_nm == lambda_nm_) return;
    lambda_nm_ = lambda_nm;
    keratin_ = Material::keratin().index(lambda_nm);
    melanin_ = Material::melanin().index(lambda_nm);
  }
  Complex operator()(const Material& m) const {
    switch (m.kind()) {
      case Material::Kind::air:
        return {1.0, 0.0};
      case Material::Kind::keratin:
        return keratin_;
      case Material::Kind::melanin:
        return melanin_;
      case Material::Kind::mixture:
        return (1.0 - m.fraction()) * (*this)(m.host()) + m.fraction() * (*this)(m.guest());
      case Material::Kind::constant:
        break;
    }
    return m.index(lambda_nm_);
  }
  double lambda_nm() const { return lambda_nm_; }

 private:
  double lambda_nm_ = -1.0;
  Complex keratin_, melanin_;
};

// cos α = cos θ·cos φ_local (LocalIncidence::cos_alpha, the same product), with cos θ kept for
// the next request: a solver's batch shares one θ (issue 26: one libm cos per request instead
// of two).
class CosAlpha {
 public:
  double operator()(const LocalIncidence& incidence) {
    if (incidence.theta_rad != theta_rad_) {
      theta_rad_ = incidence.theta_rad;
      cos_theta_ = std::cos(theta_rad_);
    }
    return cos_theta_ * std::cos(incidence.phi_local_rad);
  }

 private:
  double theta_rad_ = std::numeric_limits<double>::quiet_NaN();  // NaN ≠ every θ: first call computes
  double cos_theta_ = 0.0;
};

// sin²α in the ambient medium, which must not absorb.
double ambient_sin2(const Complex& ambient, double cos_alpha, const LayerProfile& p) {
  if (ambient.imag() != 0.0) {
    throw Error("multilayer: the ambient medium must not absorb (" + p.ambient.name() + ")");
  }
  return ambient.real() * ambient.real() * std::max(0.0, 1.0 - cos_alpha * cos_alpha);
}

const LayerProfile& profile_of(const LocalReflection::Request& r) {
  if (!r.profile) throw Error("multilayer: a reflection request carries no layer profile");
  return *r.profile;
}

// An input the recursion refuses (stack_solver.hpp) is reported with the request's stack and
// wavelength, so that a bad profile built by a solver can be traced.
[[noreturn]] void rethrow_with_context(const Error& e, const LocalReflection::Request& r) {
  char b[64];
  std::snprintf(b, sizeof b, " (lambda = %.6g nm, stack '", r.lambda_nm);
  std::string stack = describe(*r.profile);
  if (stack.size() > 300) stack = stack.substr(0, 297) + "...";
  throw Error(std::string(e.what()) + b + stack + "')");
}

}  // namespace

void MultilayerReflection::reflect(std::span<const Request> requests,
                                   std::span<JonesReflection> out) const {
  if (out.size() < requests.size()) throw Error("multilayer: output span shorter than requests");
  IndexAtWavelength index_of;
  CosAlpha cos_alpha;
  std::vector<Complex> index;
  std::vector<double> thickness;
  // One request through the scalar recursion.
  auto scalar = [&](const Request& r) {
    const LayerProfile& p = *r.profile;
    const std::size_t layers = p.layers.size();
    index_of.set_wavelength(r.lambda_nm);
    index.resize(layers + 2);
    thickness.resize(layers);
    index.front() = index_of(p.ambient);
    for (std::size_t j = 0; j < layers; ++j) {
      index[j + 1] = index_of(p.layers[j].material);
      thickness[j] = p.layers[j].thickness_nm;
    }
    index.back() = index_of(p.substrate);
    try {
      const StackReflection s =
          reflect_stack(index, thickness, r.lambda_nm, ambient_sin2(index.front(), cos_alpha(r.incidence), p));
      return JonesReflection{s.r_s, {0.0, 0.0}, {0.0, 0.0}, s.r_p};
    } catch (const Error& e) {
      rethrow_with_context(e, r);
    }
  };
  // Lane buffers: kLanes requests whose stacks have the same layer count go through the
  // vectorised recursion together; the rest through the scalar one.
  std::vector<Complex> eps;
  std::vector<double> lane_thickness;
  double k0[kLanes], sin2[kLanes];
  StackReflection lane_out[kLanes];

  std::size_t i = 0;
  while (i < requests.size()) {
    const std::size_t layers = profile_of(requests[i]).layers.size();
    std::size_t run = 1;
    while (run < kLanes && i + run < requests.size() &&
           profile_of(requests[i + run]).layers.size() == layers) {
      ++run;
    }
    if (run == kLanes) {
      eps.resize((layers + 2) * kLanes);
      lane_thickness.resize(layers * kLanes);
      for (std::size_t l = 0; l < kLanes; ++l) {
        const Request& r = requests[i + l];
        const LayerProfile& p = *r.profile;
        index_of.set_wavelength(r.lambda_nm);
        const Complex ambient = index_of(p.ambient);
        eps[l] = ambient * ambient;
        for (std::size_t j = 0; j < layers; ++j) {
          const Complex n = index_of(p.layers[j].material);
          eps[(j + 1) * kLanes + l] = n * n;
          lane_thickness[j * kLanes + l] = p.layers[j].thickness_nm;
        }
        const Complex sub = index_of(p.substrate);
        eps[(layers + 1) * kLanes + l] = sub * sub;
        k0[l] = 2.0 * 3.14159265358979323846 / r.lambda_nm;
        sin2[l] = ambient_sin2(ambient, cos_alpha(r.incidence), p);
      }
      try {
        reflect_stack_lanes(static_cast<int>(layers), eps.data(), lane_thickness.data(), k0, sin2, lane_out);
      } catch (const Error&) {
        // Refused input: the scalar path names the request (and throws for it).
        for (std::size_t l = 0; l < kLanes; ++l) out[i + l] = scalar(requests[i + l]);
        throw;
      }
      for (std::size_t l = 0; l < kLanes; ++l) {
        out[i + l] = JonesReflection{lane_out[l].r_s, {0.0, 0.0}, {0.0, 0.0}, lane_out[l].r_p};
      }
    } else {
      for (std::size_t l = 0; l < run; ++l) out[i + l] = scalar(requests[i + l]);
    }
    i += run;
  }
}

}  // namespace plumage::multilayer
