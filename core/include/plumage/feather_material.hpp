// A feather material: what a renderer needs of one species variant (paper §5, §7.1; spec
// geometry-and-brdf §4.3–4.9). Made by `plumage characterize` from simulated far fields, read by
// FeatherBsdf. File format (.plm): docs/formats.md.
//
// Per wavelength bin w and incident-grid node (i, j) ↔ (cos θ_i, cos φ_i) = (i, j)/grid, the
// eight fitted parameters of MaterialNode. Nodes with i = 0 or j = 0 (grazing) are extrapolated;
// the others come from fits (optionally smoothed, spec §4.7). Between nodes: bicubic Hermite
// patches with finite-difference derivatives (spec §4.7 step 3), evaluated by lookup().
//
// Incident directions with θ_i < 0 or φ_i < 0 are served by mirror symmetry (spec §4.9 step 1):
// only cos θ_i and cos φ_i enter the lookup; FeatherBsdf mirrors ω_o.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "plumage/lobe_model.hpp"

namespace plumage {

struct MaterialNode {
  double m_eff = 0.1;      // GGX roughness of the mean lobe, [0.001, 1]
  double phi_eff = 0.0;    // its effective incident azimuth φ_eff (rad)
  double f_eff = 0.0;      // its scale F_eff times cos θ_i cos φ_i (vanishes at grazing, §4.3)
  double m_sta = 0.1;      // the same three for the statistics (coherent) lobe, §4.4
  double phi_sta = 0.0;
  double f_sta = 0.0;      // F_sta times cos θ_i cos φ_i
  double pol_share = 0.5;  // r: share of the reflected energy in polarization 1 (§4.5)
  double correlation = 1;  // l / l0: noise correlation length in direction cosine, relative (§4.6)
};
inline constexpr int kMaterialParameters = 8;
// The parameters in file order (docs/formats.md), for loops and tables.
inline constexpr std::array<double MaterialNode::*, kMaterialParameters> kMaterialFields = {
    &MaterialNode::m_eff, &MaterialNode::phi_eff, &MaterialNode::f_eff, &MaterialNode::m_sta,
    &MaterialNode::phi_sta, &MaterialNode::f_sta, &MaterialNode::pol_share, &MaterialNode::correlation};
inline constexpr std::array<const char*, kMaterialParameters> kMaterialFieldNames = {
    "m_eff", "phi_eff", "f_eff", "m_sta", "phi_sta", "f_sta", "pol_share", "correlation"};

// Noise functions (spec §4.8): stationary Gaussian, zero mean, unit variance, with the measured
// autocorrelation, sampled at u_t = −1 + (2t + 1)/samples, t = 0 … samples − 1 (u ∈ [−1, 1] is
// scaled by l at evaluation). Instance k of a BRDF uses functions 2k mod count and 2k + 1 mod count.
struct NoisePool {
  int samples = 1024;
  double lag1 = 0.0;             // ρ(1), for variance-preserving linear interpolation
  std::vector<float> functions;  // count × samples, each function contiguous

  std::size_t count() const { return samples > 0 ? functions.size() / static_cast<std::size_t>(samples) : 0; }
  const float* function(std::size_t k) const { return functions.data() + (k % count()) * static_cast<std::size_t>(samples); }
};

struct FeatherMaterial {
  // Version 3 added `key` and `key_text`, version 2 `warnings`; versions 1 and 2 are still read
  // (without them).
  static constexpr std::uint32_t kFormatVersion = 3;

  std::string label;        // "species/variant"
  std::string config_hash;  // of the species config's bytes it was characterised from (informative)
  std::string fidelity;     // preview | production | …
  std::string warnings;     // the producing run's warnings (plumage/diagnostics.hpp), one per line; "" if none
  // What its numbers depend on (CharacterizeSettings::key_text, characterize_settings.hpp) and
  // its digest, the key a material store looks it up by; "" for materials made another way.
  std::string key;
  std::string key_text;
  double sigma = kLobeSigma;  // D_y spread of both lobes (spec §4.3)
  double l0 = 0.0;          // correlation length at the reference unit (400 nm, normal), direction cosine
  int grid = 20;            // cos θ_i, cos φ_i nodes 0 … grid
  std::vector<double> lambda_nm;    // bin starts; bin w covers [lambda_nm[w], lambda_nm[w] + bin_width_nm)
  double bin_width_nm = 6.0;
  std::vector<MaterialNode> nodes;  // [w][i][j], (grid + 1)² per wavelength bin
  NoisePool noise;

  std::size_t node_index(std::size_t w, int i, int j) const {
    return (w * static_cast<std::size_t>(grid + 1) + static_cast<std::size_t>(i)) * static_cast<std::size_t>(grid + 1) +
           static_cast<std::size_t>(j);
  }
  const MaterialNode& node(std::size_t w, int i, int j) const { return nodes[node_index(w, i, j)]; }
  MaterialNode& node(std::size_t w, int i, int j) { return nodes[node_index(w, i, j)]; }

  // Bin of a wavelength (floor binning, clamped to the table), spec §4.9 step 7.
  std::size_t wavelength_bin(double lambda_nm) const;
  // Parameters at (cos θ_i, cos φ_i) ∈ [0, 1]² for bin w: bicubic in the node grid (φ_eff and
  // φ_sta through their offsets from the nominal φ_i = acos(cos φ_i)); F's divided back by
  // cos θ_i cos φ_i (0 at exact grazing); m clamped to [0.001, 1], φ to [−π/2, π/2]; pol_share to
  // [0, 1]; correlation ≥ 0. Absolute correlation length = correlation · l0.
  MaterialNode lookup(std::size_t w, double cos_theta_i, double cos_phi_i) const;
  // Smallest *absolute* correlation length (correlation · l0, direction cosine) over the bins at
  // normal incidence. (The noise domain of spec §4.9 step 5 uses the relative value; FeatherBsdf
  // computes that itself.)
  double min_correlation_length() const;
};

// FeatherMaterial::lookup with the per-node Hermite data precomputed: for every node and field
// the value and the finite-difference slopes f_u, f_v, f_uv (φ fields as offsets from the node's
// acos(j/grid)), computed by the same expressions as lookup() and combined in the same order, so
// the result equals lookup()'s (bit for bit without FMA contraction; tested to 1e-12). One lookup
// reads 4 nodes × 32 contiguous doubles and calls acos once, instead of 8 fields × 4 corners ×
// 9 node reads with an acos per φ read (72 per lookup): the renderer's hottest function
// (plugins/pathtracer/NOTES.md, "Speed"). Built once per material (≈ 256 B per node).
class MaterialLookupTable {
 public:
  MaterialLookupTable() = default;
  explicit MaterialLookupTable(const FeatherMaterial& material);
  // The same contract and result as FeatherMaterial::lookup.
  MaterialNode lookup(std::size_t w, double cos_theta_i, double cos_phi_i) const;
  bool empty() const { return data_.empty(); }

  // What a lookup needs of (cos θ_i, cos φ_i) alone, shared by the wavelength bins of one
  // incident direction: the cell, the Hermite weights and the nominal φ_i.
  struct Point {
    double ct = 0.0, cp = 0.0;  // clamped to [0, 1]
    int i = 0, j = 0;
    std::array<double, 4> hu{}, hv{};
    double phi_nominal = 0.0;  // acos(cp)
  };
  Point locate(double cos_theta_i, double cos_phi_i) const;
  // lookup(w, ct, cp) = lookup(w, locate(ct, cp)).
  MaterialNode lookup(std::size_t w, const Point& point) const;

 private:
  static constexpr int kPerNode = 4 * kMaterialParameters;  // [field][f, f_u, f_v, f_uv]
  const double* node_data(std::size_t w, int i, int j) const {
    return data_.data() + ((w * static_cast<std::size_t>(grid_ + 1) + static_cast<std::size_t>(i)) *
                               static_cast<std::size_t>(grid_ + 1) +
                           static_cast<std::size_t>(j)) *
                              kPerNode;
  }
  int grid_ = 0;
  std::vector<double> data_;
};

// Atomic write (temporary file + rename) with a header, the format version and a checksum;
// read() verifies both and names the file in every error.
void write_feather_material(const std::filesystem::path& file, const FeatherMaterial& material);
FeatherMaterial read_feather_material(const std::filesystem::path& file);

// What a .plm says about itself before its tables (docs/formats.md): everything up to the node
// tables, read without reading them (a material store compares headers only). The checksum
// covers the whole file, so it is not verified here: read_feather_material does that.
struct FeatherMaterialHeader {
  std::uint32_t version = 0;
  std::string label, config_hash, fidelity, warnings, key, key_text;
  double sigma = 0.0, l0 = 0.0, bin_width_nm = 0.0;
  int grid = 0;
  std::vector<double> lambda_nm;
};
FeatherMaterialHeader read_feather_material_header(const std::filesystem::path& file);

}  // namespace plumage
