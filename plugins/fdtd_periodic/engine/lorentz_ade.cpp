// Lorentz poles in the time domain: P̈_p + γ_p Ṗ_p + ω_p² P_p = Δε_p ω_p² E per site and pole,
// with the site's weight w_p of the pole's material (NOTES.md §3b). Two schemes:
//  Bilinear (default): (P⁺ − 2P + P⁻)/dt² + γ(P⁺ − P⁻)/2dt + ω0²(P⁺ + 2P + P⁻)/4
//                      = Δε ω0² (E⁺ + 2E + E⁻)/4, E⁺ solved per site (semi-implicit);
//  CentralDifference: ω0² P and Δε ω0² E at time n (explicit).
#include <algorithm>

#include "sim.hpp"

namespace plumage::fdtd::detail {

void Sim::init_ade(const SimParams& Pm) {
    const int N = L.nx * L.nz;
    // ADE constants: P⁺ = a1 P + a2 P⁻ + c (drive), per pole; drive = E⁺ + 2E + E⁻ (bilinear)
    // or E (central difference).
    bilinear = Pm.lorentz_update == LorentzUpdate::Bilinear;
    for (const auto& g : gpoles) {
        const double w2 = g.pole.omega0 * g.pole.omega0 * dt * dt, gd = 0.5 * g.pole.gamma * dt;
        if (bilinear) {
            const double den = 1.0 + gd + 0.25 * w2;
            c1.push_back({(2.0 - 0.5 * w2) / den, -(1.0 - gd + 0.25 * w2) / den,
                          0.25 * g.pole.delta_eps * w2 / den});
        } else {
            const double den = 1.0 + gd;
            c1.push_back({(2.0 - w2) / den, -(1.0 - gd) / den, g.pole.delta_eps * w2 / den});
        }
    }
    for (int c = 0; c < 3; ++c) {
        Ptot[c].assign(N, 0.0);
        P[c].resize(gpoles.size());
        Pold[c].resize(gpoles.size());
        W[c].resize(gpoles.size());
        rows[c].resize(gpoles.size());
        // Each pole's arrays cover only the rows that hold its material (dense, weight 0 elsewhere).
        for (size_t g = 0; g < gpoles.size(); ++g) {
            const auto& sl = sites.pole_sites[c][g];
            int r0 = L.nz, r1 = 0;
            for (const auto& [site, w] : sl) {
                r0 = std::min(r0, site / L.nx);
                r1 = std::max(r1, site / L.nx + 1);
            }
            if (r1 <= r0) r0 = r1 = 0;
            rows[c][g] = {r0, r1};
            const int M = (r1 - r0) * L.nx;
            P[c][g].assign(M, 0.0);
            Pold[c][g].assign(M, 0.0);
            W[c][g].assign(M, 0.0);
            for (const auto& [site, w] : sl) W[c][g][site - r0 * L.nx] = w * c1[g][2];
        }
        Psig[c].assign(sites.sigma_sites[c].size(), 0.0);
        // Bilinear: E⁺ = (D⁺ − Σ known part of P⁺)/(ε∞ + Σ_p w_p c_p) per site.
        einv_eff[c] = sites.eps_inf_inv[c];
        if (bilinear) {
            std::vector<double> extra(N, 0.0);
            for (size_t g = 0; g < gpoles.size(); ++g) {
                const int off = rows[c][g].first * L.nx;
                for (size_t q = 0; q < W[c][g].size(); ++q) extra[off + q] += W[c][g][q];
            }
            for (int s = 0; s < N; ++s) einv_eff[c][s] = 1.0 / (1.0 / einv_eff[c][s] + extra[s]);
        }
    }
}

// Central difference, before E⁺: P⁺ = a1 P + a2 P⁻ + c E, Ptot = Σ P (then E⁺ = (D⁺ − Ptot)/ε∞).
void Sim::advance_poles_central(int c) {
    const int nx = L.nx;
    const std::vector<cplx>& E = c == 0 ? Ex : c == 1 ? Ey : Ez;
    cplx* __restrict Pt = Ptot[c].data();
    for (size_t g = 0; g < gpoles.size(); ++g) {
        const double a1 = c1[g][0], a2 = c1[g][1];
        const int off = rows[c][g].first * nx;
        const int M = static_cast<int>(P[c][g].size());
        cplx* __restrict Pg = P[c][g].data();
        cplx* __restrict Po = Pold[c][g].data();
        const double* __restrict Wg = W[c][g].data();
        const cplx* __restrict Eo = E.data() + off;
        cplx* __restrict Pto = Pt + off;
        for (int q = 0; q < M; ++q) {
            const cplx pn = a1 * Pg[q] + a2 * Po[q] + Wg[q] * Eo[q];
            Pto[q] += pn - Pg[q];
            Po[q] = Pg[q];
            Pg[q] = pn;
        }
    }
}

// Bilinear, after E⁺: P(z) = c (1 + z⁻¹)² / (1 − a1 z⁻¹ − a2 z⁻²) E(z) in transposed direct form,
//   P⁺ = c E⁺ + s1,  s1 ← 2c E⁺ + a1 P⁺ + s2,  s2 ← c E⁺ + a2 P⁺  (P ↦ s1, Pold ↦ s2),
// so E⁺ = (D⁺ − Σ s1)/(ε∞ + Σ c) needs only the stored Ptot = Σ s1 (no E⁻ array).
void Sim::advance_poles_bilinear(int c) {
    const int nx = L.nx;
    const std::vector<cplx>& E = c == 0 ? Ex : c == 1 ? Ey : Ez;
    cplx* __restrict Pt = Ptot[c].data();
    for (size_t g = 0; g < gpoles.size(); ++g) {
        const double a1 = c1[g][0], a2 = c1[g][1];
        const int off = rows[c][g].first * nx;
        const int M = static_cast<int>(P[c][g].size());
        cplx* __restrict s1 = P[c][g].data();
        cplx* __restrict s2 = Pold[c][g].data();
        const double* __restrict Wg = W[c][g].data();
        const cplx* __restrict En = E.data() + off;
        cplx* __restrict Pto = Pt + off;
        for (int q = 0; q < M; ++q) {
            const cplx we = Wg[q] * En[q];
            const cplx pn = we + s1[q];
            const cplx s1n = 2.0 * we + a1 * pn + s2[q];
            s2[q] = we + a2 * pn;
            Pto[q] += s1n - s1[q];
            s1[q] = s1n;
        }
    }
}

}  // namespace plumage::fdtd::detail
