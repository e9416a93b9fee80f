#include "multilayer_reflection.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
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

// ε = n² of every medium of each stack, its thicknesses and ambient index, per (profile, λ) of one
// batch (issue 26): a solver's batch asks for every node's stack once per incident azimuth, at
// one λ, and reading the media (a mixture's parts behind a pointer) and forming the squares was
// a third of the lane set-up. The first request of a (profile, λ) fills an entry; the others copy
// it. Same arithmetic as before, so the same bits. Per thread (reflect() is const and concurrent).
class StackPermittivities {
 public:
  struct Stack {
    std::size_t layers = 0;
    std::size_t eps = 0;        // eps_[eps … eps + layers + 1]: ambient, layers, substrate
    std::size_t thickness = 0;  // thickness_[thickness … thickness + layers − 1]
    Complex ambient_index;
    const LayerProfile* profile = nullptr;
    double lambda_nm = 0.0;
  };

  // Forgets the previous batch; room for `requests` distinct stacks without rehashing.
  void begin(std::size_t requests) {
    stacks_.clear(), eps_.clear(), thickness_.clear();
    std::size_t size = 16;
    while (size < 2 * requests) size *= 2;
    if (slot_.size() < size) slot_.assign(size, kEmpty), used_.clear();
    for (const std::size_t s : used_) slot_[s] = kEmpty;  // only the slots the last batch filled
    used_.clear();
    mask_ = size - 1;
  }

  std::uint32_t find_or_add(const LocalReflection::Request& r, IndexAtWavelength& index_of) {
    const LayerProfile& p = profile_of(r);
    const std::uint64_t key = reinterpret_cast<std::uintptr_t>(&p) ^ std::bit_cast<std::uint64_t>(r.lambda_nm);
    std::size_t s = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask_;
    for (; slot_[s] != kEmpty; s = (s + 1) & mask_) {
      const Stack& k = stacks_[slot_[s]];
      if (k.profile == &p && k.lambda_nm == r.lambda_nm) return slot_[s];
    }
    index_of.set_wavelength(r.lambda_nm);
    Stack k{p.layers.size(), eps_.size(), thickness_.size(), index_of(p.ambient), &p, r.lambda_nm};
    eps_.push_back(k.ambient_index * k.ambient_index);
    for (const Layer& layer : p.layers) {
      const Complex n = index_of(layer.material);
      eps_.push_back(n * n);
      thickness_.push_back(layer.thickness_nm);
    }
    const Complex sub = index_of(p.substrate);
    eps_.push_back(sub * sub);
    slot_[s] = static_cast<std::uint32_t>(stacks_.size());
    used_.push_back(s);
    stacks_.push_back(k);
    return slot_[s];
  }

  const Stack& stack(std::uint32_t i) const { return stacks_[i]; }
  const Complex* eps(const Stack& k) const { return eps_.data() + k.eps; }
  const double* thickness(const Stack& k) const { return thickness_.data() + k.thickness; }

 private:
  static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;
  std::vector<Stack> stacks_;
  std::vector<Complex> eps_;
  std::vector<double> thickness_;
  std::vector<std::uint32_t> slot_;  // open addressing, linear probing: index into stacks_
  std::vector<std::size_t> used_;
  std::size_t mask_ = 0;
};

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
  // The cache pays where stacks repeat at one λ (a solver's batch: one λ, each node's stack once
  // per incident azimuth); a batch of many wavelengths (`bench multilayer`: every request its
  // own (stack, λ)) fills the lanes straight from the profiles as before.
  bool one_wavelength = true;
  for (const Request& r : requests) one_wavelength &= r.lambda_nm == requests.front().lambda_nm;
  thread_local StackPermittivities cache;
  thread_local std::vector<std::uint32_t> stack_of;  // cache entry of every request
  if (one_wavelength) {
    cache.begin(requests.size());
    stack_of.resize(requests.size());
    for (std::size_t i = 0; i < requests.size(); ++i) stack_of[i] = cache.find_or_add(requests[i], index_of);
  }
  auto layers_of = [&](std::size_t i) {
    return one_wavelength ? cache.stack(stack_of[i]).layers : profile_of(requests[i]).layers.size();
  };
  std::vector<Complex> eps;
  std::vector<double> lane_thickness;
  double k0[kLanes], sin2[kLanes];
  StackReflection lane_out[kLanes];

  std::size_t i = 0;
  while (i < requests.size()) {
    const std::size_t layers = layers_of(i);
    std::size_t run = 1;
    while (run < kLanes && i + run < requests.size() && layers_of(i + run) == layers) {
      ++run;
    }
    if (run == kLanes) {
      eps.resize((layers + 2) * kLanes);
      lane_thickness.resize(layers * kLanes);
      for (std::size_t l = 0; l < kLanes; ++l) {
        const Request& r = requests[i + l];
        const LayerProfile& p = *r.profile;
        Complex ambient;
        if (one_wavelength) {
          const StackPermittivities::Stack& k = cache.stack(stack_of[i + l]);
          const Complex* stack_eps = cache.eps(k);
          const double* stack_thickness = cache.thickness(k);
          for (std::size_t j = 0; j < layers + 2; ++j) eps[j * kLanes + l] = stack_eps[j];
          for (std::size_t j = 0; j < layers; ++j) lane_thickness[j * kLanes + l] = stack_thickness[j];
          ambient = k.ambient_index;
        } else {
          index_of.set_wavelength(r.lambda_nm);
          ambient = index_of(p.ambient);
          eps[l] = ambient * ambient;
          for (std::size_t j = 0; j < layers; ++j) {
            const Complex n = index_of(p.layers[j].material);
            eps[(j + 1) * kLanes + l] = n * n;
            lane_thickness[j * kLanes + l] = p.layers[j].thickness_nm;
          }
          const Complex sub = index_of(p.substrate);
          eps[(layers + 1) * kLanes + l] = sub * sub;
        }
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
