#include "multilayer_reflection.hpp"

#include <cmath>
#include <vector>

#include "plumage/error.hpp"
#include "stack_solver.hpp"

namespace plumage::multilayer {

void MultilayerReflection::reflect(std::span<const Request> requests,
                                   std::span<JonesReflection> out) const {
  if (out.size() < requests.size()) throw Error("multilayer: output span shorter than requests");
  // Indices are resolved once per run of requests sharing a profile and a wavelength.
  std::vector<Complex> index;
  std::vector<double> thickness;
  const LayerProfile* resolved_profile = nullptr;
  double resolved_lambda = -1.0;
  double ambient_n2 = 1.0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const Request& request = requests[i];
    if (!request.profile) throw Error("multilayer: a reflection request carries no layer profile");
    if (request.profile != resolved_profile || request.lambda_nm != resolved_lambda) {
      const LayerProfile& p = *request.profile;
      index.resize(p.layers.size() + 2);
      thickness.resize(p.layers.size());
      index.front() = p.ambient.index(request.lambda_nm);
      for (std::size_t j = 0; j < p.layers.size(); ++j) {
        index[j + 1] = p.layers[j].material.index(request.lambda_nm);
        thickness[j] = p.layers[j].thickness_nm;
      }
      index.back() = p.substrate.index(request.lambda_nm);
      if (index.front().imag() != 0.0) {
        throw Error("multilayer: the ambient medium must not absorb (" + p.ambient.name() + ")");
      }
      ambient_n2 = index.front().real() * index.front().real();
      resolved_profile = request.profile;
      resolved_lambda = request.lambda_nm;
    }
    const double cos_a = request.incidence.cos_alpha();
    const double sin2 = ambient_n2 * std::max(0.0, 1.0 - cos_a * cos_a);
    const StackReflection r = reflect_stack(index, thickness, request.lambda_nm, sin2);
    out[i] = JonesReflection{r.r_s, {0.0, 0.0}, {0.0, 0.0}, r.r_p};
  }
}

}  // namespace plumage::multilayer
