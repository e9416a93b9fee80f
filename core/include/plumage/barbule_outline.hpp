// The outer outline of a barbule cross section: rough top surface and bottom surface (spec
// geometry-and-brdf §1.1(b)–(c), §1.3). Shared by the structure generators, which read it from
// the `outline:` map of their `structure:` section with outline_table() (its rows are the docs:
// `plumage plugins describe layered_barbule`, docs/parameters.md), e.g.
//
//   outline:
//     shape: pillow
//     width_um: 25
//     thickness_um: 4
//     roughness: {correlation_um: 1.5, range_um: [-0.3, 0.3]}
//     bottom: {mode: mirror, roughness: {correlation_um: 0.7, range_um: [-0.07, 0.07]}}
//
// Random draws: sub-streams "outline.shape", "outline.top", "outline.bottom" of the instance seed.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/geometry.hpp"
#include "plumage/param_table.hpp"
#include "plumage/params.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

struct RoughnessSpec {
  RoughSpec rough;
  bool permute = false;
};

struct BottomSpec {
  enum class Mode { mirror, arc, parallel };
  std::optional<Mode> mode;  // absent: by the top's shape (bottom_mode)
  double slope_factor = 0.9;
  double width_fraction = 0.9;
  RoughnessSpec roughness;  // default: smooth
};

struct OutlineSpec {
  enum class Shape { elliptic_arc, pillow, flat } shape = Shape::pillow;
  double width_nm = 20000;
  double thickness_nm = 4000;
  bool thickness_given = false;  // thickness_um was in the file
  double spacing_nm = 30;
  std::pair<double, double> edge_slope_deg{18.0, 30.0};
  std::pair<double, double> cap_ratio{2.0, 3.0};
  double shoulder_end = 0.95;
  double corner_nm = 1000;
  double corner_angle_deg = 30;
  double interior_shoulder = 0.5;
  RoughnessSpec roughness;
  BottomSpec bottom;
};

// The bottom's mode: as given, else mirror under a pillow top, arc under an elliptic arc,
// parallel under a flat top.
BottomSpec::Mode bottom_mode(const OutlineSpec& spec);

// The parameters of `{correlation_um, range_um, permute}` (a rough profile in µm).
const ParamTable<RoughnessSpec>& roughness_table();
// The parameters of the `outline:` map. Read it with parse_outline_spec, which adds the checks
// that involve several values.
const ParamTable<OutlineSpec>& outline_table();

// `thickness_required`: false when the generator computes T itself (then thickness_um is
// optional and ignored unless given). Throws ConfigError naming the field.
OutlineSpec parse_outline_spec(const ParamView& node, bool thickness_required = true);

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
