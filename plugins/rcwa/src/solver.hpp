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

// One table entry: λ (nm), θ and φ_local (rad) of local_reflection.hpp; both polarizations.
EntryResult solve_entry(const SlicedCell& cell, double lambda_nm, double theta_rad, double phi_rad,
                        const SolverSettings& settings);

// Richardson extrapolation in slices: the staircase error is ∝ 1/S² (NOTES.md §2), so with the
// same cell at S and 2S slices J ≈ (4 J(2S) − J(S))/3; powers are taken from the 2S solution.
EntryResult solve_entry_extrapolated(const SlicedCell& coarse, const SlicedCell& fine, double lambda_nm,
                                     double theta_rad, double phi_rad, const SolverSettings& settings);

}  // namespace plumage::rcwa
