// Photonic-crystal reflection table (issue 5; spec wave-simulation.md §3, our own format).
//
// A grid over the vacuum wavelength λ (nm), cos θ (θ the longitudinal angle) and the local
// cos φ (φ_local the azimuth from the local outward normal), all ascending, storing per entry the
// 2×2 Jones reflection of the specular order in the (s, p) basis of local_reflection.hpp:
//   a_s = E·ŝ,  a_p = η0 H·ŝ,  ŝ = ω_i × n̂/|ω_i × n̂| (ŷ at exactly normal incidence),
// referenced to the crystal's top surface at the query point. Entries hold φ_local ≥ 0 only.
//
// Query rules (ReflectionTable::query):
//  * back-facing (cos θ·cos φ_local ≤ 0): zero;
//  * grazing (cos θ → 0 or cos φ_local → 0): exactly diag(−1, −1) (total reflection with
//    r = −1, the multilayer's limit); a table whose axes do not start at 0 is extended by this
//    analytic node, so values between 0 and the first node blend smoothly into the limit;
//  * mirror x → −x for φ_local < 0 (the crystal cells are mirror-symmetric): ŝ → −M ŝ and
//    η0H → −M η0H (axial), so a_s → −a_s, a_p → a_p for incident and reflected alike:
//    J(θ, −φ) = D J(θ, φ) D with D = diag(−1, 1), i.e. ss, pp unchanged, sp, ps negated;
//  * interpolation: cubic Hermite (Catmull-Rom with non-uniform spacing) in cos θ
//    and cos φ, linear in λ (clamped at the λ ends), component-wise on Re and Im;
//  * passivity: an interpolated J whose largest singular value exceeds 1 (cubic overshoot near
//    the grazing node; the (E·ŝ, η0H·ŝ) basis is power-normalised) is scaled back to 1.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "plumage/conventions.hpp"
#include "plumage/local_reflection.hpp"

namespace plumage {

// The grid a table builder fills (ascending axes; cos values in (0, 1]).
struct TableGrid {
  std::vector<double> lambda_nm;
  std::vector<double> cos_theta;
  std::vector<double> cos_phi;

  // Uniform grid: n_lambda wavelengths in [lo, hi], cos θ = k/n_theta (k = 1..n_theta),
  // cos φ = k/n_phi (k = 1..n_phi) — the reference implementation's grids.
  static TableGrid uniform(double lambda_lo_nm, double lambda_hi_nm, int n_lambda, int n_theta,
                           int n_phi);
};

struct TableMetadata {
  std::string crystal;         // crystal name (e.g. mallard-green)
  double period_nm = 0.0;      // lattice period along the surface
  std::string config_hash;     // content hash of the crystal config (fnv1a_hex)
  double resolution_nm = 0.0;  // grid step of the producing solver
  std::string producer;        // e.g. "plumage 0.x fdtd_periodic 1.0.0 fidelity=preview"
  std::string notes;           // warnings (other propagating orders, extrapolated entries, ...)
};

class ReflectionTable {
 public:
  ReflectionTable() = default;
  ReflectionTable(TableGrid grid, TableMetadata meta);  // all entries zero

  const TableGrid& grid() const { return grid_; }
  const TableMetadata& metadata() const { return meta_; }
  TableMetadata& metadata() { return meta_; }

  JonesReflection& at(std::size_t il, std::size_t it, std::size_t ip) {
    return data_[index(il, it, ip)];
  }
  const JonesReflection& at(std::size_t il, std::size_t it, std::size_t ip) const {
    return data_[index(il, it, ip)];
  }
  const std::vector<JonesReflection>& entries() const { return data_; }

  // Interpolated Jones reflection (rules above). λ outside the grid is clamped.
  JonesReflection query(double lambda_nm, double theta_rad, double phi_local_rad) const;
  JonesReflection query(double lambda_nm, const LocalIncidence& inc) const {
    return query(lambda_nm, inc.theta_rad, inc.phi_local_rad);
  }

  // FNV-1a (hex) of axes and entries: identifies the physical content.
  std::string content_hash() const;

  // Binary file "PLMRTAB" (docs/formats.md), written atomically.
  void save(const std::filesystem::path& file) const;
  static ReflectionTable load(const std::filesystem::path& file);

 private:
  std::size_t index(std::size_t il, std::size_t it, std::size_t ip) const {
    return (il * grid_.cos_theta.size() + it) * grid_.cos_phi.size() + ip;
  }
  JonesReflection query_first_quadrant(double lambda_nm, double cos_theta, double cos_phi) const;

  TableGrid grid_;
  TableMetadata meta_;
  std::vector<JonesReflection> data_;
  std::vector<double> ext_cos_theta_, ext_cos_phi_;  // axes with the analytic node at 0 prepended
};

// Largest singular value of a Jones matrix: its largest power reflectance over polarizations.
double largest_singular_value(const JonesReflection& j);

// Jones matrix of the grazing limit: diag(−1, −1).
inline JonesReflection grazing_jones() { return {{-1.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, {-1.0, 0.0}}; }

}  // namespace plumage
