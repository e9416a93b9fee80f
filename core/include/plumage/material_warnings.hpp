// A material's warnings (FeatherMaterial::warnings) say where and how much (issue 23), and a
// render says whether its paths reach those directions.
//
// The text, one entry per warning code in code order (docs/formats.md, "Feather material"):
//   <code>: <summary>
//   <code> cells: <a>:<b0>-<b1>[,<b0>-<b1>…] <a>:…          (only codes raised per direction)
// The summary says in how many work units and groups the code was raised, the directions and how
// much (the units' share of the reflected energy, the worst measure of a raise). The cells line
// lists, per cos θ_i row a (cos θ_i = a/G), the cos φ_i columns b (cos φ_i = b/G) where the code
// was raised in any wavelength bin. Materials written before issue 23 have only the summary
// ("raised while computing N of M work groups, …") and no cells: they are read as codes that say
// nothing about directions.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace plumage {

struct MaterialWarning {
  std::string code;
  std::string summary;              // the text after "<code>: "
  int grid = 0;                     // G of the cells
  std::vector<std::uint8_t> cells;  // [(a − 1)·G + (b − 1)] = 1 where raised; empty: no directions
  bool directional() const { return !cells.empty(); }
  // Whether the incident direction with these cosines (the material's convention,
  // feather_bsdf.hpp: cos θ_i = |(x, z)|, cos φ_i = |z| / cos θ_i) is nearest to a cell where the
  // code was raised (rows and columns 0, the extrapolated grazing nodes, count as 1).
  bool contains(double cos_theta_i, double cos_phi_i) const;
};

// The entries of a material's warnings text; `grid` is the material's G. Lines that are neither
// an entry nor its cells (an older or foreign text) are kept as entries without cells.
std::vector<MaterialWarning> parse_material_warnings(std::string_view text, int grid);

// The cells line's value ("<a>:<b0>-<b1>,… …") and the directions in words ("theta_i >= 84.3 deg
// at every phi_i; |phi_i| >= 80.1 deg at theta_i 0.0-84.3 deg"), from cells as in
// MaterialWarning.
std::string format_cells(int grid, const std::vector<std::uint8_t>& cells);
std::string describe_cells(int grid, const std::vector<std::uint8_t>& cells);

// The human part of a material's warnings: every "<code>: <summary>" line, without cells lines.
std::string material_warning_summaries(std::string_view text);

// At render time: of one material's feather BSDF evaluations, the path-throughput-weighted share
// whose incident direction falls where `code` was raised (renderer.hpp RenderResult).
struct WarningShare {
  std::string material;  // SceneMaterial::name
  std::string code;
  std::string directions;  // describe_cells of the material's cells
  double weight_in = 0.0, weight_total = 0.0;
  std::uint64_t evaluations_in = 0, evaluations = 0;
  double share() const { return weight_total > 0.0 ? weight_in / weight_total : 0.0; }
};

}  // namespace plumage
