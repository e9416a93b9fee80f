// Time-step stability of the 2.5D Yee grid with Lorentz ADE media (NOTES.md §3b).
//
// In a homogeneous medium a Yee mode with spatial eigenvalue K² = K(k_x)² + K(k_z)² + k_y²
// (K(k) = (2/h) sin(kh/2), at most 8/h² + k_y²) obeys Ω² ε_disc(ω) = K², Ω = (2/dt) sin(ω dt/2).
// It is stable iff every root has real ω, i.e. the largest root Ω² stays ≤ 4/dt². For the
// central-difference ADE the largest root lies above ω0², where Ω² ε_disc(Ω²) increases
// monotonically, so the condition is K²_max ≤ (4/dt²) ε_disc(Nyquist) = (4/dt²) ε_N. For the
// bilinear ADE, ε_disc(ω) is the Lorentz ε at T = (2/dt) tan(ω dt/2) → ∞ at Nyquist, ε_N = ε∞.
#include "fdtd_periodic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plumage::fdtd {

double nyquist_eps(const MaterialModel& m, double dt, LorentzUpdate update) {
    double e = m.eps_inf;
    if (update == LorentzUpdate::Bilinear) return e;
    for (const auto& p : m.poles) {
        const double w = p.omega0 * dt;
        if (w >= 2.0) return -std::numeric_limits<double>::infinity();
        e -= p.delta_eps * w * w / (4.0 - w * w);
    }
    return e;
}

double stable_time_step(const Cell& cell, double h, double ky, LorentzUpdate update) {
    double min_einf = 1e300;
    for (const auto& m : cell.materials) min_einf = std::min(min_einf, m.eps_inf);
    // ε∞ < 1 (none of the fitted materials) lowers the limit by sqrt(ε∞).
    const double lim = courant_limit(h, ky) * std::sqrt(std::clamp(min_einf, 0.0, 1.0));
    if (update == LorentzUpdate::Bilinear) return lim;
    // dt² K²max ≤ 4 min(1, ε_N(dt)): the left side grows and ε_N falls with dt, so bisect.
    const double k2 = 8.0 / (h * h) + ky * ky;
    auto ok = [&](double dt) {
        double en = 1.0;
        for (const auto& m : cell.materials) en = std::min(en, nyquist_eps(m, dt, update));
        return dt * dt * k2 <= 4.0 * en;
    };
    double lo = 0.0, hi = lim;
    if (ok(hi)) return hi;
    for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
    }
    return lo;
}

}  // namespace plumage::fdtd
