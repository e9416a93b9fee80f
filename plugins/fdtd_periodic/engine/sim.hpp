// Internal to the engine: the pieces of one broadband run that its phases share. The phases live
// in their own files, as MEEP splits step.cpp / boundaries.cpp / sources.cpp / dft.cpp:
//   subpixel.cpp      material of every Yee site (sub-pixel fill fractions, anisotropic mix)
//   dispersion.cpp    the permittivity the ADE realises; the per-run dispersion correction
//   sources.cpp       the source pulse and sheets and their injection
//   field_update.cpp  one time step: H and D from the curls, E from the constitutive relation
//   lorentz_ade.cpp   the two Lorentz ADE schemes (bilinear, central difference)
//   cpml.cpp          CPML profiles and their ψ updates
//   monitors.cpp      harmonic-projected DFT monitors; extraction of E_r, H_r, R, T
//   driver.cpp        run_spectrum: grid layout, lockstep time loop, blow-up guard, stop rule
//   batch.cpp         independent runs on oneTBB
//   pml_diagnostic.cpp  measure_pml_reflection
//
// Yee positions in the (x, z) plane (i, k integers, h = a_x / nx):
//   Ex (i+½, k)   Ey (i, k)     Ez (i, k+½)
//   Hx (i, k+½)   Hy (i+½, k+½) Hz (i+½, k)
// Arrays are stored [k * nx + i] with the position above. E at t_n = n dt, H at t_{n+½}.
//   ∂t Hx = −(i k_y Ez − ∂̃z Ey)     ∂t Dx = i k_y Hz − ∂̃z Hy
//   ∂t Hy = −(∂̃z Ex − ∂x Ez)        ∂t Dy = ∂̃z Hx − ∂x Hz        − J_y (source family A)
//   ∂t Hz = −(∂x Ey − i k_y Ex)     ∂t Dz = ∂x Hy − i k_y Hx
//   (− M_y on Hy: source family B)   D = ε∞ E + Σ P_Lorentz + P_σ,   ∂̃z = CPML-stretched ∂z.
#pragma once

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "fdtd_periodic.hpp"

namespace plumage::fdtd::detail {

inline cplx mul_i(double s, cplx v) { return {-s * v.imag(), s * v.real()}; }   // i·s·v

// CPU time of the calling thread (robust to machine load; a oneTBB task runs on one thread).
double thread_cpu_seconds();

// ------------------------------------------------------------------ grid layout
struct Layout {
    int nx, nz, npml;
    double h, ax, z0;      // z of row k = z0 + k h
    int row_of(double z) const { return static_cast<int>(std::lround((z - z0) / h)); }
};

// The layout and time step of one run and the rows of its source, monitor and transmission plane.
struct Setup {
    Layout L;
    double dt;
    double lim;   // stability limit (stable_time_step) of this run
    int ks, km, kt;
    std::vector<std::pair<int, double>> sheets;   // (row, binomial weight) of the source sheets
};
// Throws std::invalid_argument on a time step above the stability limit or a bad layout.
Setup make_setup(const Cell& cell, double ky, const SimParams& P);

// ------------------------------------------------------------------ materials per site
struct GlobalPole {
    int material;
    LorentzPole pole;
};
std::vector<GlobalPole> global_poles(const Cell& cell);

// Effective material of every E site of one grid, per component c = x, y, z.
struct SiteModel {
    std::vector<double> eps_inf_inv[3];
    // per global pole g: list of (site, weight)
    std::vector<std::vector<std::pair<int, double>>> pole_sites[3];
    std::vector<std::pair<int, double>> sigma_sites[3];   // (site, σ_eff)
};
// Sub-pixel smoothing (NOTES.md §3, §3a); homogeneous_ambient: every site is the ambient (the
// air-only normalisation grids).
SiteModel build_sites(const Cell& cell, const Layout& L, const SimParams& P, double dt,
                      const std::vector<GlobalPole>& gpoles, bool homogeneous_ambient);

// ------------------------------------------------------------------ grid dispersion of materials
// Response of one pole / of a material as the ADE realises it at ω (time step dt), NOTES.md §3b.
cplx discrete_pole(const LorentzPole& p, double w, double dt, LorentzUpdate update);
cplx discrete_eps(const MaterialModel& m, double w, double dt, LorentzUpdate update);
// Dispersion-corrected copy of a material for one run (NOTES.md §3a), fitted over `ws`.
MaterialModel dispersion_corrected(const MaterialModel& m, double h, double dt, double kx, double ky,
                                   const std::vector<double>& ws, LorentzUpdate update);
// The cell of one run: every non-ambient material dispersion-corrected over the valid band
// [wlo, whi] when P.dispersion_correction (and dt stays stable with it), else `cell` itself.
Cell run_cell(const Cell& cell, const Setup& S, double kx, double ky, double wlo, double whi,
              const SimParams& P);

// ------------------------------------------------------------------ source
// Source time function with a band-limited spectrum: the box [w1, w2] convolved with a Gaussian
// of width s, S(ω) = ½[erf((ω−w1)/s) − erf((ω−w2)/s)]; g(t) = e^{−s²τ²/4}(e^{−i w1 τ} − e^{−i w2 τ})/(2πiτ),
// τ = t − t0. The lower edge is placed halfway between the air cut-off |k| (zero-group-velocity
// "grazing" mode that would ring forever) and the lowest requested frequency.
struct Pulse {
    double w1, w2, s, t0;
    cplx operator()(double t) const;
    double end() const { return 2 * t0; }
};
Pulse make_pulse(double wlo, double whi, double wcut, double smin, bool cut_edge);
// Rows and binomial weights (1), (1,−1), (1,−2,1), (1,−3,3,−1) of the source sheets from row ks.
std::vector<std::pair<int, double>> source_sheets(int ks, double h, const SimParams& P);

// ------------------------------------------------------------------ monitors
struct Monitor {       // harmonic-projected DFTs at a plane (row km)
    int km;
    std::vector<int> orders;
    // dft[comp][order][freq]
    std::vector<std::vector<std::vector<cplx>>> dft;
};

// Numerical (Yee) k_z in a medium with permittivity eps for harmonic kxn; returns NaN if evanescent.
double yee_kz(double omega, double kxn, double ky, double h, double dt, double eps = 1.0);

// ------------------------------------------------------------------ one field set
// The fields of one grid driven by one source family (0: J_y sheets, 1: M_y sheets).
class Sim {
public:
    Layout L;
    double dt, kx, ky;
    int family;   // 0: J_y sheet, 1: M_y sheet
    cplx bloch;   // e^{i kx ax}
    int ks;       // source row
    std::vector<std::pair<int, double>> sheets;   // (row, weight) of the source sheets
    Pulse pulse;
    std::vector<cplx> Ex, Ey, Ez, Hx, Hy, Hz, Dx, Dy, Dz;
    std::vector<cplx> pHx, pHy, pDx, pDy;   // CPML ψ
    std::vector<double> ib_int, b_int, a_int, ib_half, b_half, a_half;   // 1/κ, b, a per row
    std::vector<char> pml_int, pml_half;
    SiteModel sites;
    std::vector<GlobalPole> gpoles;
    std::vector<std::vector<double>> c1;               // per pole constants (a1, a2, c)
    std::vector<std::vector<cplx>> P[3], Pold[3];      // [comp][pole][site]: P, P⁻ (central) / s1, s2 (bilinear)
    std::vector<cplx> Ptot[3];                          // Σ P (central) / Σ s1 (bilinear)
    std::vector<std::vector<double>> W[3];                  // [comp][pole] dense c3·weight
    std::vector<std::pair<int, int>> rows[3];              // [comp][pole] row range
    std::vector<cplx> Psig[3];
    bool bilinear = true;
    std::vector<double> einv_eff[3];                        // 1/(ε∞ + Σ w c) (bilinear), else 1/ε∞
    std::vector<cplx> tmpE;
    std::vector<cplx> zero_row;                             // the field beyond the PEC rows
    std::vector<cplx> src_phase;
    std::vector<double> omegas;
    std::vector<cplx> phE, phH;   // harmonic projection phases
    Monitor mon;
    // x-resolved transmission DFT (Ex, Ey at row kt; Hx, Hy at kt+½)
    int kt = -1;
    std::vector<std::vector<cplx>> tdft[4];   // [comp][freq][i]
    int step_no = 0;

    Sim(const Layout& lay, double dt_, double kx_, double ky_, int fam, int ks_, const Pulse& pl,
        SiteModel sm, std::vector<GlobalPole> gp, const SimParams& Pm, const std::vector<double>& om,
        int km, const std::vector<int>& orders, int kt_);

    // One time step: H^{n-½} → H^{n+½}, D and E^n → E^{n+1}, then the monitors (field_update.cpp).
    void step();
    double energy() const;

    // field_update.cpp
    void update_H();
    void update_D();
    void update_E();
    // cpml.cpp: profiles, and the ψ parts of the z derivatives in row k of the PML
    void init_cpml(const SimParams& Pm);
    void cpml_H_row(int k, const cplx* ex, const cplx* ex1, const cplx* ey, const cplx* ey1);
    void cpml_D_row(int k, const cplx* hx, const cplx* hx0, const cplx* hy, const cplx* hy0);
    // lorentz_ade.cpp: constants and polarisation arrays; the two ADE schemes of component c
    void init_ade(const SimParams& Pm);
    void advance_poles_central(int c);
    void advance_poles_bilinear(int c);
    // sources.cpp
    void init_source();
    void inject_magnetic(double tE);    // family 1: − M_y on Hy at t_n
    void inject_electric(double tH);    // family 0: − J_y on Dy at t_{n+½}
    // monitors.cpp
    void init_monitors(int km, const std::vector<int>& orders);
    void accumulate_dft();
};

// Per-frequency extraction (monitors.cpp): E_r, H_r, order efficiencies, R and T of frequency f
// from the four grids' DFTs (main and normalisation of both families).
void extract_frequency(const std::vector<Sim>& sims, const Setup& S, const Cell& cell, double kx, double ky,
                       const SimParams& P, std::size_t f, FreqResult& r);

}  // namespace plumage::fdtd::detail
