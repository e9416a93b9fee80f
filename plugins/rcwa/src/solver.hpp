// Fourier modal method (RCWA) for a sliced, x-periodic, y-invariant cell at conical incidence
// (issue 27). Time convention e^{-iωt} (conventions.hpp); frame of slicing.hpp (the FDTD engine's).
//
// Per slice (Moharam et al. 1995, conical; our sign conventions): with z' = k0 z, η0H, and the
// Floquet orders k_x,m = k_x + mλ/Λ (normalised by k0), ∂z'(e; h) = i [0 P; Q 0](e; h) for
// e = (E_x, E_y), h = (η0H_x, η0H_y), where
//   P = [[k_y K_x ε⁻¹, I − K_x ε⁻¹ K_x], [k_y² ε⁻¹ − I, −k_y ε⁻¹ K_x]],  ε⁻¹ = [[ε]]⁻¹ (E_z: Laurent),
//   Q = [[−k_y K_x, K_x² − [[ε]]], [A − k_y², k_y K_x]],  A = [[1/ε]]⁻¹ (Li 1996 inverse rule for
//   E_x, normal to the slice's interfaces) or [[ε]] (Laurent, li_rule off; slow TM convergence).
// Modes: PQ W = W Γ², Im γ ≥ 0 (forward decays), V = Q W Γ⁻¹; e = W(e^{iγz'}c⁺ + e^{−iγz'}c⁻),
// h = V(e^{iγz'}c⁺ − e^{−iγz'}c⁻). S-matrices of slices relative to an air gap and their Redheffer
// star products (Li 1997; Rumpf's symmetric form) — never transfer-matrix products.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "plumage/local_reflection.hpp"
#include "slicing.hpp"

namespace plumage::rcwa {

struct SolverSettings {
  int harmonics = 10;    // orders −M..M (2M + 1 Fourier harmonics)
  bool li_rule = true;   // inverse rule for E_x (false: Laurent's rule everywhere)
  // Diagnostics / checks only (the builder leaves both false): solve the 2n × 2n coupled mode
  // problem instead of the two decoupled n × n ones, and carry the full S-matrix recursion so that
  // EntryResult::transmitted is filled (otherwise only the reflection matrix is recursed).
  bool coupled_eigenproblem = false;
  bool transmission = false;
};

struct EntryResult {
  JonesReflection jones;           // specular order, (s, p) basis of local_reflection.hpp
  double reflected[2] = {0, 0};    // total reflected power (all orders), s / p incident
  double transmitted[2] = {0, 0};  // total transmitted power into the substrate (settings.transmission)
  double other_orders[2] = {0, 0}; // reflected power in propagating orders m ≠ 0, s / p incident
  bool has_other_orders = false;   // a propagating reflected order m ≠ 0 exists
};

// What depends on λ only, not on the incidence: ε of the materials and, per slice type with boxes,
// the Toeplitz matrix [[ε]], its inverse and A (Li's [[1/ε]]⁻¹, or [[ε]]). A table computes it once
// per wavelength (its 1000 angles share it); the same values as inside solve_entry.
struct WavelengthSetup {
  struct TypeMatrices {
    Eigen::MatrixXcd eps, eps_inv, a;
  };
  const SlicedCell* cell = nullptr;  // not owned: must outlive the setup
  double lambda_nm = 0;
  SolverSettings settings;
  std::vector<Complex> eps_of;      // per material of the cell
  std::vector<TypeMatrices> types;  // per slice type (empty matrices for host-only types)
};
WavelengthSetup prepare_wavelength(const SlicedCell& cell, double lambda_nm, const SolverSettings& settings);

// One table entry: θ and φ_local (rad) of local_reflection.hpp at the setup's λ; both polarizations.
EntryResult solve_entry(const WavelengthSetup& setup, double theta_rad, double phi_rad);

// The same from scratch: λ (nm), θ and φ_local (rad).
EntryResult solve_entry(const SlicedCell& cell, double lambda_nm, double theta_rad, double phi_rad,
                        const SolverSettings& settings);

// Richardson extrapolation in slices: the staircase error is ∝ 1/S² (NOTES.md §2), so with the
// same cell at S and 2S slices J ≈ (4 J(2S) − J(S))/3; powers are taken from the 2S solution.
EntryResult solve_entry_extrapolated(const SlicedCell& coarse, const SlicedCell& fine, double lambda_nm,
                                     double theta_rad, double phi_rad, const SolverSettings& settings);
EntryResult solve_entry_extrapolated(const WavelengthSetup& coarse, const WavelengthSetup& fine, double theta_rad,
                                     double phi_rad);

}  // namespace plumage::rcwa
