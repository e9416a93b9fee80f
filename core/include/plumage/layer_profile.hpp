// The planar layer stack under one surface point (paper §4.2): ambient, layers, substrate.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "plumage/materials.hpp"
#include "plumage/params.hpp"

namespace plumage {

struct Layer {
  Material material;
  double thickness_nm = 0.0;
};

struct LayerProfile {
  Material ambient = Material::air();
  std::vector<Layer> layers;  // top to bottom
  Material substrate = Material::air();

  double total_thickness_nm() const;
};

// From a config map:
//   ambient: air
//   layers:
//     - {material: keratin, thickness_nm: 300}
//     - {repeat: 6, layers: [{material: melanin, thickness_nm: 90}, {material: keratin, thickness_nm: 100}]}
//   substrate: air
LayerProfile parse_layer_profile(const ParamView& node);

// From a command-line string: "air | keratin 300 | {melanin 90 | keratin 100}*6 | air".
// The first entry is the ambient medium, the last the substrate; each layer is
// "<material> <thickness_nm>"; "{...}*N" repeats a group. Throws std::invalid_argument.
LayerProfile parse_stack_text(std::string_view text);

// "air | keratin 300 | air", with repeated groups written out.
std::string describe(const LayerProfile& profile);

}  // namespace plumage
