// The outer outline of a barbule cross section: rough top surface and bottom surface (spec
// geometry-and-brdf §1.1(b)–(c), §1.3). Shared by the structure generators; read from the
// `outline:` map of a `structure:` section:
//
//   outline:
//     shape: pillow              # elliptic_arc | pillow | flat
//     width_um: 25               # x-extent of the top
//     thickness_um: 4            # T: distance of the bottom below the top
//     spacing_nm: 30             # vertex spacing along the top (arc length)
//     edge_slope_deg: [18, 30]   # elliptic_arc: edge slope angle β ~ U[range]
//     cap_ratio: [2, 3]          # pillow: shoulder length / half thickness ~ U[range]
//     shoulder_end: 0.95         # pillow: the top stops at this fraction of the cap's half-axis
//     corner_um: 1.0             # flat: rounded corner zone at each end
//     corner_angle_deg: 30       # flat: the corner arc turns by this angle
//     interior_shoulder: 0.5     # pillow: fraction of the shoulder usable by interior structures
//     roughness: {correlation_um: 1.5, range_um: [-0.3, 0.3], permute: false}
//     bottom:
//       mode: mirror             # mirror (pillow) | arc (new elliptic arc) | parallel (top − T)
//       slope_factor: 0.9        # arc: edge slope tan β' = factor · tan β
//       width_fraction: 0.9      # arc: x-extent of the bottom / width
//       roughness: {correlation_um: 0.7, range_um: [-0.07, 0.07], permute: false}
//
// Random draws: sub-streams "outline.shape", "outline.top", "outline.bottom" of the instance seed.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/geometry.hpp"
#include "plumage/params.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

struct RoughnessSpec {
  RoughSpec rough;
  bool permute = false;
};

struct OutlineSpec {
  enum class Shape { elliptic_arc, pillow, flat } shape = Shape::pillow;
  enum class Bottom { mirror, arc, parallel } bottom = Bottom::mirror;
  double width_nm = 20000;
  double thickness_nm = 4000;
  double spacing_nm = 30;
  std::pair<double, double> edge_slope_deg{18.0, 30.0};
  std::pair<double, double> cap_ratio{2.0, 3.0};
  double shoulder_end = 0.95;
  double corner_nm = 1000;
  double corner_angle_deg = 30;
  double interior_shoulder = 0.5;
  RoughnessSpec roughness;
  double bottom_slope_factor = 0.9;
  double bottom_width_fraction = 0.9;
  RoughnessSpec bottom_roughness{{1000.0, 0.0, 0.0}, false};
};

// `thickness_required`: false when the generator computes T itself (then thickness_um is
// optional and ignored unless given).
OutlineSpec parse_outline_spec(const ParamView& node, bool thickness_required = true);
// Reads {correlation_um, range_um, permute} (range inverted or correlation ≤ 0: error).
RoughnessSpec parse_roughness(const ParamView& node);
// Rows for a plug-in's parameter table ("outline.width_um", ...).
std::vector<ParamSpec> outline_param_table();

struct Outline {
  Polyline top;
  std::vector<double> top_roughness;  // per top vertex
  Polyline bottom;
  double interior_half_width = 0;     // |x| ≤ this is clear of shoulders and corners
  double edge_slope_rad = 0;          // elliptic_arc: β drawn
};

// Builds the outline of one instance. `thickness_nm` < 0 uses spec.thickness_nm.
Outline make_outline(const OutlineSpec& spec, std::uint64_t seed, double thickness_nm = -1.0);

}  // namespace plumage
