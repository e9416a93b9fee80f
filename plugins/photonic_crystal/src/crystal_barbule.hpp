// structure_generator "crystal_barbule" (barbule types 5–7). Parameter table: crystal_barbule.cpp.
#pragma once

#include <string>

#include "plumage/barbule_outline.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::photonic_crystal {

class CrystalBarbule final : public StructureGenerator {
 public:
  CrystalBarbule(const ParamView& params, const PluginContext& context);
  CrossSection generate(std::uint64_t instance_index) const override;
  static std::vector<ParamSpec> param_table();

 private:
  OutlineSpec outline_;
  std::string crystal_file_;
  CrystalCell cell_;
  Material body_ = Material::keratin();
  double regularity_ = 1.0;
  RoughSpec regularity_profile_;
  double min_gap_nm_ = 1.0;
  int rod_segments_ = 24;
  bool place_lattice_ = true;
};

}  // namespace plumage::photonic_crystal
