// structure_generator "crystal_barbule" (barbule types 5–7). Parameter table: crystal_barbule.cpp.
#pragma once

#include <optional>
#include <string>

#include "plumage/barbule_outline.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/param_table.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::photonic_crystal {

// The `structure:` section of a crystal barbule, as read by crystal_barbule_table().
struct CrystalBarbuleParams {
  std::string crystal;
  OutlineSpec outline;
  std::optional<Material> body;  // absent: the crystal's host
  double regularity = 1.0;
  double regularity_correlation_nm = 500.0;
  double regularity_half_range = 0.1;
  double min_gap_nm = 1.0;
  int rod_segments = 24;
  bool exact_lattice = true;
};

const ParamTable<CrystalBarbuleParams>& crystal_barbule_table();

class CrystalBarbule final : public StructureGenerator {
 public:
  CrystalBarbule(const ParamView& params, const PluginContext& context);
  CrossSection generate(std::uint64_t instance_index) const override;

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
