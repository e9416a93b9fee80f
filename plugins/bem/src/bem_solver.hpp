// ScatteringSolver "bem": full-wave 2.5D multi-region PMCHWT (spec wave-simulation.md §6).
//
// Incidence (parameter `incidence`):
//   beam        (default, barbules) exact 2.5D Gaussian beam (§6.7) with in-plane waist
//               s_b = s·cos φ_i, s = window_fraction·W, focused on the top surface at the centre
//               of the barbule, so that its footprint on the top is the approximate solver's window
//               exp(−x²/s²). FarField.incident_power = Φ_i of spec §1.7 (the approximate solver's
//               definition, window squared, lit top nodes), so reflectance densities compare 1:1.
//   plane_wave  (validation bodies) unit plane wave. FarField.incident_power = 1/(2η0) × 1 nm, so
//               FarField::reflectance_density(pol, k) = cos θ_i |𝓔|² / (1 nm) is the 2D
//               differential scattering width dσ/dφ_o in nm per radian (power scattered per unit
//               length and unit φ_o over the incident irradiance), for every direction of the full
//               circle. (Cylinder series: dσ/dΦ = (2/(π k0))(|T_co|² + |T_cross|²).)
// In both cases FarField.field holds 𝓔 (V·nm^{-1/2} for a 1 V/m wave) exactly as the
// approximate solver defines it (far_field.hpp).
#pragma once

#include <Eigen/Dense>
#include <memory>

#include "assembly.hpp"
#include "bem_options.hpp"
#include "gmres.hpp"
#include "hmatrix.hpp"
#include "hodlr.hpp"
#include "incident.hpp"
#include "mesh.hpp"
#include "plumage/scattering_solver.hpp"
#include "single_precision_lu.hpp"

namespace plumage::bem {

// The instance-only part: interfaces and the top-surface data of Φ_i.
struct BemPrepared final : ScatteringSolver::Prepared {
  Geometry geometry;
  Polyline top;
  Vec2 focus{0.0, 0.0};
  double extent = 0.0;  // largest distance of any interface point from the focus (nm)
  double width = 0.0;
};

std::shared_ptr<const BemPrepared> prepare_geometry(const CrossSection& section);

// System at one (λ, θ_i): mesh, media, and the factorised matrix.
struct System {
  double lambda_nm = 0, theta = 0, k0 = 0, beta = 0;
  Mesh mesh;
  std::vector<Medium> media;
  // method dense: Z is factorised in place (one N² matrix in memory); method gmres: Z is the
  // mat-vec operator and near_field its preconditioner; method hmatrix: hmatrix is the mat-vec
  // operator and near_field or dense_single its preconditioner.
  Eigen::MatrixXcd Z;
  std::unique_ptr<Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXcd>>> lu;
  std::unique_ptr<NearFieldLU> near_field;
  std::unique_ptr<HMatrix> hmatrix;
  std::unique_ptr<SinglePrecisionLU> dense_single;
  std::unique_ptr<HodlrLU> hodlr;
  double assembly_seconds = 0, factor_seconds = 0;
  double expand_seconds = 0;  // dense_single: H-matrix → dense float (part of factor_seconds)
  // Solves for every column of B (LU, or GMRES column by column); `iterations` gets the GMRES
  // iteration count per column (empty for LU).
  Eigen::MatrixXcd solve(const Eigen::MatrixXcd& B, const BemOptions& options, std::vector<int>* iterations = nullptr) const;
};
// Refuses (MemoryBudgetError) a system whose estimated peak with `rhs` right-hand sides and
// `far_directions` far-field directions (memory_estimate.hpp) exceeds options.max_memory or the
// process's budget, before anything is assembled.
std::unique_ptr<System> build_system(const Geometry& geometry, double lambda_nm, double theta,
                                     const BemOptions& options, int rhs = 2, int far_directions = 0);

// Raises bem.mesh_coarse / bem.near_touching (plumage/diagnostics.hpp) for a mesh at λ that the
// measurements of NOTES.md "Warnings (issue 9)" say cannot be trusted; build_system calls it.
void check_mesh(const Geometry& geometry, const Mesh& mesh, double lambda_nm, const BemOptions& options);

// Incident field of polarisation `pol` at azimuth φ_i as configured.
IncidentField incident_for(const BemPrepared& prep, const BemOptions& options, double k0, double theta,
                           double phi, int pol);
// Φ_i of spec §1.7 (per polarisation, identical for both).
double window_incident_power(const BemPrepared& prep, double window_fraction, double theta, double phi);

// Absorbed power per unit length over the incident irradiance |S_i| = 1/(2η0) from the currents on
// the air-side boundary (net inward Poynting flux of the total field): Re ∫ (M_z J̃_t* − M_t J̃_z*) dl.
double absorption_width(const Mesh& mesh, const Eigen::Ref<const Eigen::VectorXcd>& x);

class BemSolver final : public ScatteringSolver {
 public:
  explicit BemSolver(BemOptions options) : options_(options) {}
  std::shared_ptr<const Prepared> prepare(const CrossSection& section,
                                          std::shared_ptr<const LocalReflection> reflection) const override;
  std::vector<FarField> solve(const Prepared& prepared, double lambda_nm, double theta_i_rad,
                              std::span<const double> phi_i_rad,
                              std::span<const double> phi_o_rad) const override;
  MemoryEstimate estimate_memory(const CrossSection& section, double lambda_nm, std::size_t n_phi_i,
                                 std::size_t n_phi_o) const override;
  const BemOptions& options() const { return options_; }

 private:
  BemOptions options_;
};

}  // namespace plumage::bem
