// LocalReflection "multilayer": the planar stack under each surface point (paper §4.2).
//
// Parameters: none. The stack comes with each request (LayerProfile), built by the solver from
// the cross section's reduced layer model, or from a config's nominal_stack.
#pragma once

#include "plumage/local_reflection.hpp"

namespace plumage::multilayer {

class MultilayerReflection final : public LocalReflection {
 public:
  void reflect(std::span<const Request> requests, std::span<JonesReflection> out) const override;
};

}  // namespace plumage::multilayer
