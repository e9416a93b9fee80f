// The permittivity the Yee/ADE scheme realises, and the per-run correction of the materials
// against the Yee numerical dispersion (NOTES.md §3a, §3b).
#include <Eigen/Dense>
#include <cmath>

#include "sim.hpp"

namespace plumage::fdtd::detail {

// Response ω0²/(ω0² − ω̃² − iγ ν) of one pole as the ADE realises it at ω (time step dt):
// central difference: ω̃ = Ω = (2/dt) sin(ω dt/2), ν = sin(ω dt)/dt; bilinear: ω̃ = ν =
// T = (2/dt) tan(ω dt/2), i.e. the exact pole at the warped frequency T (NOTES.md §3b).
cplx discrete_pole(const LorentzPole& p, double w, double dt, LorentzUpdate update) {
    double wt, nu;
    if (update == LorentzUpdate::Bilinear) {
        wt = nu = 2.0 / dt * std::tan(0.5 * w * dt);
    } else {
        wt = 2.0 / dt * std::sin(0.5 * w * dt);
        nu = std::sin(w * dt) / dt;
    }
    return p.omega0 * p.omega0 / cplx(p.omega0 * p.omega0 - wt * wt, -p.gamma * nu);
}

// Discrete permittivity of a material model as the Yee/ADE scheme realises it at ω: the poles
// of discrete_pole, the trapezoidal conductivity i ε'' tan(ω_ref dt/2)/tan(ω dt/2).
cplx discrete_eps(const MaterialModel& m, double w, double dt, LorentzUpdate update) {
    cplx e = m.eps_inf;
    for (const auto& p : m.poles) e += p.delta_eps * discrete_pole(p, w, dt, update);
    if (m.eps_imag_ref != 0.0 && m.omega_ref > 0)
        e += cplx(0.0, m.eps_imag_ref * std::tan(0.5 * m.omega_ref * dt) / std::tan(0.5 * w * dt));
    return e;
}

// Dispersion-corrected copy of a material for one run (fixed k_x, k_y, grid step h, time step dt;
// NOTES.md §3a). In a homogeneous medium the Yee scheme propagates the order-0 harmonic with
//   K(k_x)² + K(k_z)² + k_y² = Ω² ε_disc(ω),   K(k) = (2/h) sin(k h/2)   (∂y → i k_y is exact),
// so k_z is too large by ~ k²h²/24 relative: a phase error that accumulates over the crystal's
// depth and red-shifts steep band edges (peacock-cyan, ~1 nm at h = 10 nm). The corrected model
// has ε∞, Δε_p (and ε'') changed, least squares over the run's valid band `ws`, so that
//   ε_disc'(ω) = [K(k_z)² + K(k_x)² + k_y²]/Ω²  with the exact k_z² = ε(ω) ω² − k_x² − k_y²,
// i.e. the grid's k_z equals the exact one (minimum-norm change when `ws` has one frequency: exact
// there). Pole shapes are kept; if a change would make an amplitude negative (not passive) the
// material is returned unchanged. The ambient is never corrected (the normalisation runs and the
// extraction use its numerical k_z already).
MaterialModel dispersion_corrected(const MaterialModel& m, double h, double dt, double kx, double ky,
                                   const std::vector<double>& ws, LorentzUpdate update) {
    const int np = static_cast<int>(m.poles.size());
    const bool sig = m.eps_imag_ref != 0.0 && m.omega_ref > 0;
    const int nu = 1 + np + (sig ? 1 : 0);
    const int J = static_cast<int>(ws.size());
    Eigen::MatrixXd A(2 * J, nu);
    Eigen::VectorXd b(2 * J);
    auto K2 = [h](cplx k) {
        const cplx s = (2.0 / h) * std::sin(0.5 * h * k);
        return s * s;
    };
    for (int j = 0; j < J; ++j) {
        const double w = ws[j];
        const double Om = 2.0 / dt * std::sin(0.5 * w * dt);
        const cplx kz = std::sqrt(m.eps(w) * w * w - kx * kx - ky * ky);
        const cplx target = (K2(kz) + K2(kx) + ky * ky) / (Om * Om);
        const cplx d = target - discrete_eps(m, w, dt, update);
        b(2 * j) = d.real();
        b(2 * j + 1) = d.imag();
        std::vector<cplx> col{1.0};
        for (const auto& p : m.poles) col.push_back(discrete_pole(p, w, dt, update));
        if (sig) col.push_back(cplx(0.0, std::tan(0.5 * m.omega_ref * dt) / std::tan(0.5 * w * dt)));
        for (int u = 0; u < nu; ++u) {
            A(2 * j, u) = col[u].real();
            A(2 * j + 1, u) = col[u].imag();
        }
    }
    const Eigen::VectorXd x = A.completeOrthogonalDecomposition().solve(b);
    MaterialModel c = m;
    c.eps_inf += x(0);
    for (int p = 0; p < np; ++p) c.poles[p].delta_eps += x(1 + p);
    if (sig) c.eps_imag_ref += x(1 + np);
    bool passive = c.eps_inf > 0 && c.eps_imag_ref >= 0;
    for (const auto& p : c.poles) passive = passive && p.delta_eps >= 0;
    return passive ? c : m;
}

Cell run_cell(const Cell& cell, const Setup& S, double kx, double ky, double wlo, double whi,
              const SimParams& P) {
    Cell out = cell;
    if (!P.dispersion_correction) return out;
    std::vector<double> ws;
    const int nfit = whi > wlo ? 24 : 1;
    for (int j = 0; j < nfit; ++j) ws.push_back(nfit == 1 ? whi : wlo + (whi - wlo) * j / (nfit - 1));
    for (size_t m = 0; m < out.materials.size(); ++m)
        if (static_cast<int>(m) != cell.ambient) {
            MaterialModel corr = dispersion_corrected(cell.materials[m], S.L.h, S.dt, kx, ky, ws, P.lorentz_update);
            // The refit lowers ε∞ slightly; keep the material only if dt stays stable with it.
            Cell probe;
            probe.materials = {corr};
            if (S.dt <= stable_time_step(probe, S.L.h, ky, P.lorentz_update) || P.allow_unstable_dt)
                out.materials[m] = corr;
        }
    return out;
}

}  // namespace plumage::fdtd::detail
