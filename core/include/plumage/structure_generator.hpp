// Extension point: procedural barbule cross sections (paper §3, spec geometry-and-brdf §1).
// Implementations: "layered_barbule" (plugins/multilayer, types 1–4), "crystal_barbule"
// (plugins/photonic_crystal, types 5–7), "validation_shape" (core: circles, coated circles,
// flat slabs with exact solutions).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "plumage/cross_section.hpp"
#include "plumage/plugin.hpp"
#include "plumage/random.hpp"

namespace plumage {

class StructureGenerator : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "structure_generator";

  // Instance `instance_index` of the bound (species, variant). Deterministic: the same index
  // gives the same cross section, bit for bit, on any machine and thread count. Thread-safe.
  virtual CrossSection generate(std::uint64_t instance_index) const = 0;

  // Names the (species, variant) the instances belong to; called by the species loader before
  // any generate(). Seeds derive from these names (random.hpp).
  void bind(std::string species, std::string variant) {
    species_ = std::move(species);
    variant_ = std::move(variant);
  }
  const std::string& species() const { return species_; }
  const std::string& variant() const { return variant_; }
  std::uint64_t seed_of(std::uint64_t instance_index) const {
    return instance_seed(species_, variant_, instance_index);
  }
  std::string label() const { return variant_.empty() ? species_ : species_ + "/" + variant_; }

 protected:
  // A CrossSection with generator, label, instance and seed filled in.
  CrossSection start(std::string_view generator_type, std::uint64_t instance_index) const {
    CrossSection cs;
    cs.generator = std::string(generator_type);
    cs.label = label();
    cs.instance = instance_index;
    cs.seed = seed_of(instance_index);
    return cs;
  }

 private:
  std::string species_ = "unnamed";
  std::string variant_;
};

}  // namespace plumage
