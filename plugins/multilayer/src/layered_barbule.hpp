// structure_generator "layered_barbule" (barbule types 1–4). Parameter table: layered_barbule.cpp.
#pragma once

#include <utility>
#include <vector>

#include "plumage/barbule_outline.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::multilayer {

// A mixture of `guest` in `host` whose guest fraction varies along x as a rough profile
// (RoughSpec lo/hi hold the fraction range; correlation in nm).
struct MixtureSpec {
  Material host = Material::keratin();
  Material guest = Material::melanin();
  RoughnessSpec fraction;
};

class LayeredBarbule final : public StructureGenerator {
 public:
  explicit LayeredBarbule(const ParamView& params);
  CrossSection generate(std::uint64_t instance_index) const override;
  static std::vector<ParamSpec> param_table();

 private:
  enum class Model { granule_gap, melanosome_rows, platelets, films };
  struct Film {
    Material material;
    double thickness_nm;
  };

  void finish_outline(CrossSection& cs, Outline&& outline) const;
  void build_granule_gap(CrossSection& cs) const;
  void build_rows(CrossSection& cs) const;
  void build_platelets(CrossSection& cs) const;
  void build_films(CrossSection& cs) const;

  Model model_ = Model::films;
  OutlineSpec outline_;
  double cortex_nm_ = 0;
  Material body_ = Material::keratin();
  double arc_step_ = 10;
  // granule_gap
  RoughnessSpec gap_;
  MixtureSpec granules_;
  double lower_cortex_nm_ = 0;
  // melanosome_rows
  double diameter_nm_ = 0, jitter_ = 0, row_spacing_nm_ = 0, neck_fraction_ = 1.0 / 3.0;
  int rows_ = 1;
  MixtureSpec core_;
  // platelets
  int layers_ = 0;
  double first_layer_nm_ = 0, wall_nm_ = 0, bubble_nm_ = 0, blend_ = 0.2, spacer_nm_ = 0;
  double membrane_nm_ = 0, platelet_nm_ = 0, bubble_height_jitter_nm_ = 0;
  std::pair<double, double> bubble_jitter_, spacer_jitter_, length_jitter_, gap_jitter_;
  std::pair<double, double> end_gap_nm_, bubble_length_jitter_;
  std::vector<double> first_spacers_, coverage_;
  // films
  std::vector<Film> films_;
  double film_spacing_nm_ = 0;
};

}  // namespace plumage::multilayer
