// Pictures and checks of a feather material's BSDF (`plumage brdf plot|check`, issue 22: in the
// library so that a program can draw or check a material without the command).
//
// Hemisphere panels (paper Fig. 10): for an incident (θ_i, φ_i), the mean BRDF f̄ or instance
// f_k (paper Eqs. 16, 22) over the unit disk of (ω_o,x, ω_o,y). Pixel value: the spectrum
// f·cos θ_o over the material's wavelength bins (the cosine-weighted lobe L of spec §3, whose
// integral ∫ L dω over the hemisphere is the directional albedo; a pixel covers projected solid
// angle cos θ_o dω, so the albedo is the disk integral of L / cos θ_o) → XYZ as a reflectance
// under D65, bin i constant on [λ_i, λ_i + width] (spec §4.12) → linear sRGB × exposure → clip →
// sRGB transfer.
//
// White furnace: at every table entry (nodes with cos θ_i, cos φ_i > 0) and cell centre of every
// bin, A_r (the fitter's accurate hemisphere integral of the lobe the BSDF evaluates) + T ≤ 1;
// also the material's own albedo at the nodes before the BSDF's clamp, and how often that clamp
// (the safety net between nodes) acts.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "plumage/colour.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/feather_material.hpp"

namespace plumage {

struct IncidentAngles {
  double theta_deg = 0.0, phi_deg = 0.0;  // both in (−90°, 90°)
};

struct HemispherePlotOptions {
  std::vector<IncidentAngles> incidents;  // one row of panels each
  int instances = 2;                      // panels after the mean one, instances 0 … instances−1
  int size = 192;                         // pixels per panel side
  double exposure = 0.0;                  // > 0: linear exposure; 0: the 99.5th percentile of the
                                          // mean panels' luminance maps to 1
};

struct HemispherePanels {
  int size = 0, rows = 0, columns = 0;  // columns = 1 + instances
  std::vector<std::vector<Xyz>> xyz;    // [row · columns + column], row-major pixels, NaN outside the disk
  double exposure = 1.0;                // as given, or the automatic one
  bool automatic_exposure = false;
};

// The panels of a reflection-only BSDF of `material` (transmission albedo 0).
// The ranges `plumage brdf plot` and Material.hemisphere_panels accept: at least one incident
// direction, θ and φ in (−90°, 90°), 0..16 instances, 16..2048 pixels, exposure ≥ 0. ConfigError
// located at the command's flag (--incident, --instances, --size, --exposure).
void check_hemisphere_plot_options(const HemispherePlotOptions& options);
HemispherePanels hemisphere_panels(std::shared_ptr<const FeatherMaterial> material, const HemispherePlotOptions& options);

// One figure (share/plumage/plot_hemisphere.py): a row per incident direction, the mean then the
// instances, titled with the material's label, fidelity and the exposure. Written atomically.
void write_hemisphere_figure(const HemispherePanels& panels, const HemispherePlotOptions& options,
                             const FeatherMaterial& material, const std::filesystem::path& png);

struct FurnaceBin {
  double lambda_nm = 0.0;
  double transmission = 0.0;   // T_w the BSDF grants
  double worst_total = 0.0;    // max A_r + T over nodes and cell centres
  double material_raw = 0.0;   // max A_r before the BSDF's clamp, at the nodes
  int raw_over_one = 0;        // nodes whose unclamped A_r exceeds 1
  int clamped_nodes = 0, clamped_centres = 0;
};

struct FurnaceReport {
  std::vector<FurnaceBin> bins;
  std::size_t entries = 0;       // table entries and cell centres checked
  std::size_t nodes_per_bin = 0;  // grid², also the cell centres per bin
  double worst_total = 0.0, worst_raw = 0.0;
  int raw_over_one = 0, clamped_nodes = 0, clamped_centres = 0;
  bool passes() const { return worst_total <= 1.0; }
};

// The white furnace of the BSDF built from `material` with diffuse transmission albedo
// `transmission` (in [0, 1]).
FurnaceReport white_furnace(std::shared_ptr<const FeatherMaterial> material, double transmission);

}  // namespace plumage
