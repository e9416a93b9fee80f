// Monitors and extraction (NOTES.md §2): one plane in air below the source sheets; every
// component projected on the Bloch harmonics e^{i(k_x + 2πn/a_x)x} (all propagating n) at its true
// x position and DFT'd at its true time (E at t_n, H at t_{n+½}); an optional x-resolved DFT in
// the substrate for T. Scattered = main − normalisation (order 0).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sim.hpp"

namespace plumage::fdtd {

// The incident polarisation basis (NOTES.md §1); here, beside the extraction that projects on it.
void incident_basis(double st, double ct, double sp, double cp, Vec3c E[2], Vec3c H[2]) {
    E[0] = {cplx(-st * sp), cplx(ct), cplx(st * cp)};
    H[0] = {cplx(-cp), cplx(0.0), cplx(-sp)};
    E[1] = {cplx(cp), cplx(0.0), cplx(sp)};
    H[1] = {cplx(-st * sp), cplx(ct), cplx(st * cp)};
}

Vec3c to_local_frame(const Vec3c& v) { return {v[0], -v[2], v[1]}; }

namespace detail {

void Sim::init_monitors(int km, const std::vector<int>& orders) {
    mon.km = km;
    mon.orders = orders;
    mon.dft.assign(6, std::vector<std::vector<cplx>>(orders.size(), std::vector<cplx>(omegas.size(), 0.0)));
    for (size_t o = 0; o < orders.size(); ++o) {
        double kn = kx + 2 * kPi * orders[o] / L.ax;
        for (int i = 0; i < L.nx; ++i) {
            phE.push_back(std::exp(cplx(0.0, -kn * i * L.h)) / double(L.nx));            // integer x
            phH.push_back(std::exp(cplx(0.0, -kn * (i + 0.5) * L.h)) / double(L.nx));    // half x
        }
    }
    if (kt >= 0)
        for (auto& t : tdft) t.assign(omegas.size(), std::vector<cplx>(L.nx, 0.0));
}

void Sim::accumulate_dft() {
    // E^{n} (now at step_no) at time step_no*dt; H^{n-½} at (step_no-½) dt.
    const int nx = L.nx;
    const double tE = step_no * dt;
    const double tH = tE - 0.5 * dt;
    const int km = mon.km;
    const std::vector<cplx>* comps[6] = {&Ex, &Ey, &Ez, &Hx, &Hy, &Hz};
    // x-position type per comp: Ex half, Ey int, Ez int, Hx int, Hy half, Hz half
    const bool halfx[6] = {true, false, false, false, true, true};
    const size_t nf = omegas.size();
    std::vector<cplx> fE(nf), fH(nf);
    for (size_t f = 0; f < nf; ++f) {
        fE[f] = std::exp(cplx(0.0, omegas[f] * tE)) * dt;
        fH[f] = std::exp(cplx(0.0, omegas[f] * tH)) * dt;
    }
    for (int c = 0; c < 6; ++c) {
        const auto& F = *comps[c];
        for (size_t o = 0; o < mon.orders.size(); ++o) {
            const cplx* ph = (halfx[c] ? phH.data() : phE.data()) + o * nx;
            cplx a = 0;
            for (int i = 0; i < nx; ++i) a += F[km * nx + i] * ph[i];
            auto& d = mon.dft[c][o];
            const auto& ff = (c < 3) ? fE : fH;
            for (size_t f = 0; f < nf; ++f) d[f] += a * ff[f];
        }
    }
    if (kt >= 0) {
        const std::vector<cplx>* tc[4] = {&Ex, &Ey, &Hx, &Hy};
        for (int c = 0; c < 4; ++c) {
            const auto& ff = (c < 2) ? fE : fH;
            for (size_t f = 0; f < nf; ++f)
                for (int i = 0; i < nx; ++i) tdft[c][f][i] += (*tc[c])[kt * nx + i] * ff[f];
        }
    }
}

double yee_kz(double omega, double kxn, double ky, double h, double dt, double eps) {
    double lhs = eps * std::pow(2.0 / dt * std::sin(omega * dt / 2), 2);
    double rhs = lhs - std::pow(2.0 / h * std::sin(kxn * h / 2), 2) - ky * ky;
    double s = rhs * h * h / 4;
    if (s <= 0 || s > 1) return std::nan("");
    return 2.0 / h * std::asin(std::sqrt(s));
}

namespace {

Vec3c cross(const std::array<double, 3>& a, const Vec3c& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3c transverse(const std::array<double, 3>& k, Vec3c v) {
    cplx d = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    for (int c = 0; c < 3; ++c) v[c] -= k[c] * d;
    return v;
}

// Transmitted power of the combination (ca, cb) of the two families at frequency f, from the
// x-resolved DFTs in the substrate (one-sided Poynting flux averaged over the period).
double transmitted_flux(const Sim& a, const Sim& b, cplx ca, cplx cb, std::size_t f) {
    double Ft = 0;
    for (int i = 0; i < a.L.nx; ++i) {
        cplx ex = ca * a.tdft[0][f][i] + cb * b.tdft[0][f][i];
        cplx ey = ca * a.tdft[1][f][i] + cb * b.tdft[1][f][i];
        cplx hx = ca * a.tdft[2][f][i] + cb * b.tdft[2][f][i];
        cplx hy = ca * a.tdft[3][f][i] + cb * b.tdft[3][f][i];
        Ft += (ex * std::conj(hy) - ey * std::conj(hx)).real();
    }
    return Ft / a.L.nx;
}

}  // namespace

// Incident (norm) and reflected (scattered) vectors are moved to z = 0 with the numerical Yee k̃_z
// of each component's own z and projected on the plane transverse to the analytic k̂; the 2×2
// matrix M_{p,f} = e_p · E_inc^f gives the combination of the two families that is a unit pol-p
// incident wave with zero phase at the origin; the same combination of the reflected harmonics
// gives E_r (and H_r = k̂_r × E_r). Other propagating orders: efficiency |E_n|² k_zn/k_z0. R from
// the one-sided discrete Poynting flux Re(Ex Hy* − Ey Hx*) (exactly conserved by the Yee scheme).
void extract_frequency(const std::vector<Sim>& sims, const Setup& S, const Cell& cell, double kx, double ky,
                       const SimParams& P, std::size_t f, FreqResult& r) {
    const Layout& L = S.L;
    const double h = L.h, dt = S.dt;
    const double zE = L.z0 + S.km * h;      // Ex, Ey, Hz rows
    const double zH = zE + 0.5 * h;         // Ez, Hx, Hy rows
    const double zc[6] = {zE, zE, zH, zH, zH, zE};
    const double w = sims[0].omegas[f];
    const double kz0 = std::sqrt(w * w - kx * kx - ky * ky);
    const double kzt0 = yee_kz(w, kx, ky, h, dt);
    const std::array<double, 3> ki = {kx / w, ky / w, kz0 / w};
    Vec3c Einc[2];
    std::vector<std::array<cplx, 6>> scat[2];   // per family, per order: 6 comps at monitor
    std::array<cplx, 6> incm[2];
    for (int fam = 0; fam < 2; ++fam) {
        const auto& m = sims[2 * fam].mon;
        const auto& n = sims[2 * fam + 1].mon;
        Vec3c e;
        for (int c = 0; c < 3; ++c) e[c] = n.dft[c][0][f] * std::exp(cplx(0.0, -kzt0 * zc[c]));
        Einc[fam] = transverse(ki, e);
        for (int c = 0; c < 6; ++c) incm[fam][c] = n.dft[c][0][f];
        scat[fam].resize(m.orders.size());
        for (size_t o = 0; o < m.orders.size(); ++o)
            for (int c = 0; c < 6; ++c)
                scat[fam][o][c] = m.dft[c][o][f] - (m.orders[o] == 0 ? n.dft[c][0][f] : cplx(0.0));
    }
    Vec3c eb[2], hb[2];
    incident_basis(r.sin_theta, r.cos_theta, r.sin_phi, r.cos_phi, eb, hb);
    Eigen::Matrix2cd M;
    for (int p = 0; p < 2; ++p)
        for (int fam = 0; fam < 2; ++fam)
            M(p, fam) = eb[p][0] * Einc[fam][0] + eb[p][1] * Einc[fam][1] + eb[p][2] * Einc[fam][2];
    Eigen::Matrix2cd Minv = M.inverse();
    const auto& orders_main = sims[0].mon.orders;
    for (int p = 0; p < 2; ++p) {
        cplx ca = Minv(0, p), cb = Minv(1, p);
        // incident flux (one-sided discrete Poynting, exact for the Yee scheme)
        std::array<cplx, 6> inc;
        for (int c = 0; c < 6; ++c) inc[c] = ca * incm[0][c] + cb * incm[1][c];
        double Finc = (inc[0] * std::conj(inc[4]) - inc[1] * std::conj(inc[3])).real();
        double Fref = 0;
        for (size_t o = 0; o < orders_main.size(); ++o) {
            std::array<cplx, 6> sc;
            for (int c = 0; c < 6; ++c) sc[c] = ca * scat[0][o][c] + cb * scat[1][o][c];
            double kxn = kx + 2 * kPi * orders_main[o] / cell.ax;
            double kzn2 = w * w - kxn * kxn - ky * ky;
            if (kzn2 <= 0) continue;
            double kzn = std::sqrt(kzn2);
            double kztn = yee_kz(w, kxn, ky, h, dt);
            if (!std::isfinite(kztn)) continue;
            Fref += (sc[0] * std::conj(sc[4]) - sc[1] * std::conj(sc[3])).real();
            const std::array<double, 3> kr = {kxn / w, ky / w, -kzn / w};
            Vec3c e;
            for (int c = 0; c < 3; ++c) e[c] = sc[c] * std::exp(cplx(0.0, kztn * zc[c]));
            e = transverse(kr, e);
            if (orders_main[o] == 0) {
                r.E[p] = e;
                r.H[p] = cross(kr, e);
            } else {
                double eff = (std::norm(e[0]) + std::norm(e[1]) + std::norm(e[2])) * kzn / kz0;
                auto it = std::find_if(r.orders.begin(), r.orders.end(),
                                       [&](const OrderEfficiency& q) { return q.n == orders_main[o]; });
                if (it == r.orders.end()) {
                    r.orders.push_back({orders_main[o], {0, 0}});
                    it = r.orders.end() - 1;
                }
                it->eff[p] = eff;
                r.other_orders = true;
            }
        }
        r.R[p] = -Fref / Finc;
        if (P.compute_transmission) r.T[p] = transmitted_flux(sims[0], sims[2], ca, cb, f) / Finc;
    }
}

}  // namespace detail
}  // namespace plumage::fdtd
