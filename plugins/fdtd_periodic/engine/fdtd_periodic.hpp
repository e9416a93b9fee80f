// plumage — periodic 2.5D FDTD engine for photonic-crystal barbules (issue 5).
//
// C++20 + Eigen3 + oneTBB (run_batch); of plumage core only the error types (plumage/error.hpp:
// FieldBlowUp is a plumage::NumericalError). Sources by phase: see sim.hpp.
//
// ---------------------------------------------------------------------------------------------
// FRAME (engine frame, right-handed):
//   x : along the crystal surface, periodic with period a_x (Bloch phase e^{i k_x a_x}),
//   y : rod axis (invariant direction), fields ∝ e^{i k_y y},
//   z : depth; z = 0 is the air/keratin top surface, z > 0 inside the crystal, air for z < 0.
//   Time convention e^{-iωt}; absorbing media have Im n > 0, Im ε > 0.
//   Units: lengths in µm, c = ε0 = μ0 = 1 (so η0 = 1 and every "H" below is η0·H), ω = 2π/λ[µm].
//
// RELATION TO THE SPEC'S LOCAL CRYSTAL FRAME (wave-simulation.md §3.1: x_l along the surface,
// y_l outward normal (into air), z_l = axis):   x_l = x,  y_l = −z,  z_l = y.
// This is a proper rotation, so E and H transform alike (to_local_frame()).
//
// ANGLES. θ = longitudinal angle out of the cross-section (xz) plane toward the axis, φ = azimuth
// in the xz plane measured from the outward normal (−z) toward +x. Unit vector toward the light
// (spec ω_i mapped to the engine frame):
//     ω_i = (cosθ sinφ, sinθ, −cosθ cosφ),     incident wavevector k_i = −k0 ω_i, so
//     k_x = −k0 cosθ sinφ,  k_y = −k0 sinθ,  k_z = +k0 cosθ cosφ  (> 0: travelling into the crystal).
// Polarisations (spec §1.3 mapped to the engine frame; both unit |E| = 1, H = k̂ × E):
//     pol 1: E = (−sinθ sinφ,  cosθ,  sinθ cosφ),   H = (−cosφ, 0, −sinφ)            (θ = 0: E = ŷ, "TM")
//     pol 2: E = ( cosφ,       0,     sinφ),        H = (−sinθ sinφ, cosθ, sinθ cosφ) (θ = 0: H = ŷ, "TE")
// A run is done at FIXED Bloch wavevector (k_x, k_y) (the engine's inputs are those of the
// incident field e^{i(k_x x + k_y y)}); every frequency ω > |k| then corresponds to its own angle
//     sinθ = −k_y/k0,  cosθ sinφ = −k_x/k0,  cosθ cosφ = k_z/k0,   k0 = ω.
//
// OUTPUT per frequency: reflected E and H of the specular order (n = 0) at the reference plane
// z = 0, for an incident field of pol 1 / pol 2 with unit amplitude and zero phase at the origin
// of that plane; efficiencies of every other propagating reflected order n (wavevector
// k_x + 2πn/a_x), with a flag when any exists; reflected and (optionally) transmitted power.
// ---------------------------------------------------------------------------------------------
#pragma once

#include <array>
#include <complex>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "plumage/error.hpp"

namespace plumage::fdtd {

using cplx = std::complex<double>;
using Vec3c = std::array<cplx, 3>;
constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------ materials
/// Lorentz pole Δε ω0² / (ω0² − ω² − iγω)  (e^{-iωt}; passive for Δε ≥ 0, γ ≥ 0).
struct LorentzPole {
    double omega0 = 0.0;
    double gamma = 0.0;
    double delta_eps = 0.0;
};

/// ε(ω) = eps_inf + Σ poles + i·eps_imag_ref·(omega_ref/ω).
/// The last term is a conductivity σ = eps_imag_ref·omega_ref: it is exact only at omega_ref and is
/// used by the "constant permittivity" mode (constant complex ε at one wavelength).
struct MaterialModel {
    std::string name;
    double eps_inf = 1.0;
    std::vector<LorentzPole> poles;
    double eps_imag_ref = 0.0;
    double omega_ref = 0.0;
    cplx eps(double omega) const;
};

/// Spec refractive indices (photonic-crystals.md), λ in µm.
cplx keratin_index(double lambda_um);
cplx melanin_index(double lambda_um);

/// Result of fitting a dispersive model to a tabulated index over [lambda_min, lambda_max].
struct FitReport {
    MaterialModel model;
    double max_abs_eps_error = 0.0;   ///< max |ε_fit − ε_spec| on a dense λ grid
    double max_abs_n_error = 0.0;     ///< max |n_fit − n_spec| (complex index)
    double rms_abs_eps_error = 0.0;
};
/// Broadband models fitted over 0.38–0.72 µm (fixed pole shapes, linear least squares for the
/// amplitudes; see NOTES.md).  Results are cached.
const FitReport& keratin_fit();
const FitReport& melanin_fit();
MaterialModel air_model();
/// Constant complex permittivity exact at λ_ref (ε∞ = Re ε, conductivity for Im ε).
MaterialModel constant_model(std::string name, cplx eps, double lambda_ref_um);

// ------------------------------------------------------------------ geometry
struct Slab {          ///< material in z0 <= z < z1 (all x)
    double z0, z1;
    int material;
};
struct Circle {        ///< rod/core/channel (periodic images in x are implied)
    double x, z, r;
    int material;
};
/// One period of the crystal. Materials are indices into `materials`. Painting order:
/// z < 0 → ambient; z ≥ 0 → substrate, then slabs, then circles (later ones win).
struct Cell {
    double ax = 0.19;
    std::vector<MaterialModel> materials;   ///< index 0 conventionally air
    int ambient = 0;
    int substrate = 1;
    std::vector<Slab> slabs;
    std::vector<Circle> circles;
    double structure_depth = 0.0;           ///< z of the deepest non-substrate feature
    int material_at(double x, double z) const;
};

// ------------------------------------------------------------------ parameters & results
/// Time discretisation of the Lorentz ADE  P̈ + γṖ + ω0² P = Δε ω0² E  (NOTES.md §3b).
///  Bilinear (default): ω0² P and the drive Δε ω0² E averaged as (X⁺ + 2X + X⁻)/4, damping by
///    (P⁺ − P⁻)/2dt; the discrete ε is the exact Lorentz ε at T = (2/dt) tan(ω dt/2), passive for
///    every real ω, so the grid is stable for every dt below the non-dispersive Courant limit with
///    the sites' ε∞ (semi-implicit: E⁺ is solved per site).
///  CentralDifference (engine revision ≤ 2): ω0² P and the drive at time n (explicit). Its
///    permittivity at the grid's Nyquist frequency is ε∞ − Σ Δε w²/(4 − w²), w = ω0 dt, which is
///    below 1 for keratin (ε∞ = 1.017): stable only for dt ≤ the smaller limit of
///    stable_time_step(); kept for the stability tests and to reproduce old tables.
enum class LorentzUpdate { Bilinear, CentralDifference };

struct SimParams {
    int nx = 38;                  ///< cells per period (h = a_x / nx; square cells)
    double courant = 0.95;        ///< fraction of the Courant limit used when dt <= 0
    double dt = 0.0;              ///< explicit time step (checked against the limit)
    LorentzUpdate lorentz_update = LorentzUpdate::Bilinear;
    bool allow_unstable_dt = false;   ///< testing only: skip the Courant refusal
    int pml_cells = 24;
    double pml_sigma_factor = 1.0;    ///< σ_max = factor · 0.8 (m+1) / h
    double pml_kappa_max = 1.0;
    double pml_alpha_max = 0.2;       ///< CPML α (1/µm), graded linearly to 0 at the inner edge
    int pml_order = 3;
    double air_above = 0.30;      ///< air between z = 0 and the top PML (µm)
    double source_z = -0.25;      ///< first (top) source sheet (µm, in air)
    double monitor_z = -0.06;     ///< reflection monitor plane (µm, in air, below the sheets)
    double substrate_below = 0.30;///< substrate between structure_depth and the bottom PML (µm)
    bool compute_transmission = false;
    double transmission_z = -1.0; ///< < 0: structure_depth + substrate_below/2
    int supersample = 8;          ///< subpixel-smoothing samples per axis (exact_fill = false)
    /// Fill fractions of mixed sites: true = exact chords × 8-point Gauss in z on every site;
    /// false = 9-probe mixed test and a supersample² point sample (NOTES.md §3).
    bool exact_fill = true;
    bool smoothing = true;
    /// Correct the Yee numerical dispersion of every non-ambient material for each run (fixed
    /// k_x, k_y, h, dt): ε∞ and pole amplitudes refitted over the valid band so that the grid's
    /// k_z equals the exact one (NOTES.md §3a). Off: the plain scheme (error ∝ (k h)²).
    bool dispersion_correction = true;
    double kz_min = 0.25;         ///< only frequencies with k_z/k0 ≥ kz_min are returned valid
    double source_min_smoothing = 0.02;   ///< lower bound of the source spectrum edge width (1/µm)
    /// Number of source sheets (1–4) with binomial weights (1), (1,−1), (1,−2,1), (1,−3,3,−1)
    /// spaced by source_sheet_spacing: a p-th difference of sheets radiates ∝ (1 − e^{ik_z d})^p / k_z,
    /// which removes the zero-group-velocity (k_z → 0, grazing) mode from the excitation.
    int source_sheets = 4;
    double source_sheet_spacing = 0.06;
    /// If true, the source spectrum's lower edge is placed between the air cut-off |k| and the
    /// lowest valid frequency (clean but long pulses near grazing); if false, a short pulse whose
    /// spectrum starts at the cut-off is used and the multi-sheet source suppresses the ringing.
    bool source_cut_edge = false;
    double max_time = 400.0;      ///< hard cap of simulated time (µm/c)
    double dft_tol = 3e-4;        ///< stop when the scattered DFTs change by < tol (relative to the incident, per ~1 µm/c, twice)
    /// Blow-up guard (checked every 10 steps): throw FieldBlowUp if a field is non-finite,
    /// if a main grid's energy exceeds factor × nx × its normalisation grid's energy so far, or
    /// if a normalisation grid's energy exceeds factor × its own source-phase maximum.
    double blowup_factor = 1e4;
    std::vector<double> smoothing_omegas;  ///< ω samples for fitting mixed cells (empty: band)
};

struct OrderEfficiency {
    int n;                       ///< order index (k_x + 2πn/a_x)
    double eff[2];               ///< reflected power fraction, pol 1 / pol 2
};

struct FreqResult {
    double omega = 0.0, lambda = 0.0;
    bool valid = false;           ///< propagating and k_z/k0 ≥ kz_min
    double sin_theta = 0, cos_theta = 0, sin_phi = 0, cos_phi = 0;
    Vec3c E[2], H[2];             ///< specular reflected field at z = 0 (engine frame), pol 1/2
    double R[2] = {0, 0};         ///< total reflected power fraction (all orders), pol 1/2
    double T[2] = {0, 0};         ///< transmitted power fraction (if compute_transmission)
    bool other_orders = false;    ///< any propagating reflected order n ≠ 0
    std::vector<OrderEfficiency> orders;   ///< n ≠ 0 propagating orders
};

struct RunStats {
    int steps = 0;
    double sim_time = 0.0;
    double dt = 0.0, h = 0.0;
    double dt_limit = 0.0;        ///< stable_time_step of the run (dt / dt_limit = Courant factor used)
    int nz = 0, nx = 0;
    double wall_seconds = 0.0;
    double cpu_seconds = 0.0;     ///< CPU time of the calling thread (robust to machine load)
    bool converged = false;
    /// Largest field energy of the main grids relative to nx × the energy their air-only
    /// normalisation grids had reached by then (a few in stable runs; the blow-up guard throws
    /// above blowup_factor).
    double energy_ratio = 0.0;
};

struct Spectrum {
    double kx = 0, ky = 0;
    std::vector<FreqResult> freqs;
    RunStats stats;
};

/// Courant limit for the 2D Yee grid with exact ∂y → i k_y:  dt ≤ 1/sqrt(2/h² + k_y²/4)
/// (c = 1, valid when every ε∞ ≥ 1).
double courant_limit(double h, double ky, double min_eps_inf = 1.0);

/// Permittivity the ADE realises at the grid's Nyquist frequency ω dt = π (lossless part; the
/// damping term vanishes there): ε∞ for Bilinear, ε∞ − Σ Δε w²/(4 − w²) (w = ω0 dt < 2, else
/// −∞) for CentralDifference. A homogeneous medium is stable iff dt²(8/h² + k_y²) ≤ 4 ε_N(dt)
/// (and ε_N of a mixed site is the convex mix of its materials').
double nyquist_eps(const MaterialModel& m, double dt, LorentzUpdate update);

/// Largest stable time step of a cell: the Courant limit with min(1, min ε∞) for Bilinear; for
/// CentralDifference also the largest dt with dt²(8/h² + k_y²) ≤ 4 ε_N(dt) for every material.
double stable_time_step(const Cell& cell, double h, double ky, LorentzUpdate update);

/// Field blow-up caught by the run-time energy guard (SimParams::blowup_factor): the run is
/// unstable. what() names the energies, the step, the time and dt as a fraction of the limit.
class FieldBlowUp : public plumage::NumericalError {
public:
    FieldBlowUp(const std::string& message, int step, double time_um, double dt, double dt_limit);
    int step;          ///< time step at which the guard fired
    double time_um;    ///< simulated time then (µm/c)
    double dt, dt_limit;
};

/// One broadband run at fixed (k_x, k_y): both source families (J_y and M_y sheets) plus their
/// 1-cell-wide normalisation runs, stepped in lockstep. Throws std::invalid_argument on a time
/// step above the Courant limit and FieldBlowUp on field blow-up.
Spectrum run_spectrum(const Cell& cell, double kx, double ky, const std::vector<double>& omegas,
                      const SimParams& params);

struct Job {
    double kx, ky;
};
/// Independent runs on at most `threads` oneTBB workers (results in job order; each run is
/// sequential, so the results do not depend on the thread count).
std::vector<Spectrum> run_batch(const Cell& cell, const std::vector<Job>& jobs,
                                const std::vector<double>& omegas, const SimParams& params,
                                int threads = 2);
/// As run_batch, but a job that throws leaves its Spectrum default and its exception in
/// errors[j] (the other jobs' results are kept), so a caller can rerun only the failed ones.
std::vector<Spectrum> run_batch_collect(const Cell& cell, const std::vector<Job>& jobs,
                                        const std::vector<double>& omegas, const SimParams& params,
                                        int threads, std::vector<std::exception_ptr>& errors);

/// Incident-direction helpers (engine frame).
void incident_basis(double sin_theta, double cos_theta, double sin_phi, double cos_phi,
                    Vec3c E[2], Vec3c H[2]);
/// (x, y, z) engine → (x_l, y_l, z_l) spec local crystal frame.
Vec3c to_local_frame(const Vec3c& v);

/// Diagnostic: PML reflection |r| in a homogeneous medium with grid step h (1 cell wide, a
/// single source sheet in the middle, up/down plane-wave decomposition with the numerical k_z at
/// two planes on each side; PML settings from params). Returns max over the valid frequencies
/// of {top, bottom} reflection magnitudes.
std::array<double, 2> measure_pml_reflection(const MaterialModel& medium, double h, double kx,
                                             double ky, const std::vector<double>& omegas,
                                             const SimParams& params);

}  // namespace plumage::fdtd
