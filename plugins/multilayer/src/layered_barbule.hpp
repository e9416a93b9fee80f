// structure_generator "layered_barbule": barbules whose local structure is a layer stack (types
// 1–4 of spec geometry-and-brdf §1.3). Every number comes from the YAML `structure:` section,
// declared once in layered_table() (layered_barbule.cpp); `model:` selects the interior. The
// outline (top and bottom surfaces) is core's barbule_outline.hpp.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "plumage/barbule_outline.hpp"
#include "plumage/param_table.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage::multilayer {

// A mixture of `guest` in `host` whose guest fraction varies along x as a rough profile
// (RoughSpec lo/hi hold the fraction range; correlation in nm).
struct MixtureSpec {
  Material host = Material::keratin();
  Material guest = Material::melanin();
  RoughnessSpec fraction;
};

struct Film {
  Material material;
  double thickness_nm = 0;
};

// The `structure:` section of a layered barbule, as read by layered_table().
struct LayeredParams {
  enum class Model { granule_gap, melanosome_rows, platelets, films };
  Model model = Model::films;
  OutlineSpec outline;
  double cortex_nm = 0;
  Material body = Material::keratin();
  double arc_step_nm = 10;
  // granule_gap (type 1): cortex | air gap | granules in air | lower cortex
  RoughnessSpec gap;
  MixtureSpec granules;
  std::optional<double> lower_cortex_nm;  // absent: cortex_nm
  // melanosome_rows (types 2–3)
  double diameter_nm = 0, jitter = 0.2, row_spacing_nm = 0, neck_fraction = 1.0 / 3.0;
  int rows = 1;
  MixtureSpec core;
  // platelets (type 4)
  int layers = 0;
  double first_layer_nm = 0, wall_nm = 0, bubble_nm = 0, blend = 0.2, spacer_nm = 0;
  double membrane_nm = 0, platelet_nm = 0, bubble_height_jitter_nm = 10;
  std::pair<double, double> bubble_jitter{0.95, 1.05}, spacer_jitter{0.95, 1.05};
  std::pair<double, double> length_jitter{2.0 / 3.0, 4.0 / 3.0}, gap_jitter{2.0 / 3.0, 4.0 / 3.0};
  std::pair<double, double> end_gap_nm{80.0, 120.0}, bubble_length_jitter{0.7, 1.3};
  std::vector<double> first_spacers{0.9, 0.95}, coverage{0.85, 0.9};
  // films (a worked example: conformal films under the cortex)
  std::vector<Film> films;
  double film_spacing_nm = 0;
};

// The generator's parameters, declared once: reading, defaults, ranges and docs.
const ParamTable<LayeredParams>& layered_table();

class LayeredBarbule final : public StructureGenerator {
 public:
  explicit LayeredBarbule(const ParamView& params);
  CrossSection generate(std::uint64_t instance_index) const override;

 private:
  using Model = LayeredParams::Model;

  void finish_outline(CrossSection& cs, Outline&& outline) const;
  void build_granule_gap(CrossSection& cs) const;
  void build_rows(CrossSection& cs) const;       // layered_rows.cpp
  void build_platelets(CrossSection& cs) const;  // layered_platelets.cpp
  void build_films(CrossSection& cs) const;

  LayeredParams p_;
};

}  // namespace plumage::multilayer
