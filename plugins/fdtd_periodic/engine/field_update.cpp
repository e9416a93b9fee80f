// One field set and its time step (equations in sim.hpp): H from the curl of E, D from the curl
// of H, E from D through the constitutive relation (ε∞, Lorentz poles, conductivity). Bloch
// boundaries in x (neighbour across the cell edge times e^{±i k_x a_x}), ∂y → i k_y exactly.
#include "sim.hpp"

namespace plumage::fdtd::detail {

Sim::Sim(const Layout& lay, double dt_, double kx_, double ky_, int fam, int ks_, const Pulse& pl, SiteModel sm,
         std::vector<GlobalPole> gp, const SimParams& Pm, const std::vector<double>& om, int km,
         const std::vector<int>& orders, int kt_)
    : L(lay), dt(dt_), kx(kx_), ky(ky_), family(fam), ks(ks_), pulse(pl), sites(std::move(sm)),
      gpoles(std::move(gp)), omegas(om), kt(kt_) {
    const int N = L.nx * L.nz;
    for (auto* v : {&Ex, &Ey, &Ez, &Hx, &Hy, &Hz, &Dx, &Dy, &Dz, &pHx, &pHy, &pDx, &pDy}) v->assign(N, 0.0);
    zero_row.assign(L.nx, 0.0);
    bloch = std::exp(cplx(0.0, kx * L.ax));
    init_cpml(Pm);
    init_ade(Pm);
    init_source();
    init_monitors(km, orders);
}

void Sim::step() {
    update_H();
    const double tE = step_no * dt;          // time of E^n
    const double tH = tE + 0.5 * dt;         // time of H^{n+½}
    if (family == 1) inject_magnetic(tE);
    update_D();
    if (family == 0) inject_electric(tH);
    update_E();
    ++step_no;
    accumulate_dft();
}

// H update (n-½ → n+½) using E^n, row by row (E beyond the last row: the PEC's zero).
void Sim::update_H() {
    const int nx = L.nx, nz = L.nz;
    const double rh = 1.0 / L.h;
    const double dtr = dt * rh;
    for (int k = 0; k < nz; ++k) {
        const int r = k * nx;
        const double ib = ib_half[k] * dtr;
        cplx* __restrict hx = Hx.data() + r;
        cplx* __restrict hy = Hy.data() + r;
        cplx* __restrict hz = Hz.data() + r;
        const cplx* ex = Ex.data() + r;
        const cplx* ey = Ey.data() + r;
        const cplx* ez = Ez.data() + r;
        const cplx* ex1 = (k + 1 < nz) ? ex + nx : zero_row.data();
        const cplx* ey1 = (k + 1 < nz) ? ey + nx : zero_row.data();
        // z-derivative parts and k_y parts (no x neighbours)
        for (int i = 0; i < nx; ++i) {
            const cplx dEy = ey1[i] - ey[i];
            const cplx dEx = ex1[i] - ex[i];
            hx[i] += ib * dEy - dt * mul_i(ky, ez[i]);
            hy[i] -= ib * dEx;
            hz[i] += dt * mul_i(ky, ex[i]);
        }
        if (pml_half[k]) cpml_H_row(k, ex, ex1, ey, ey1);
        // x-derivative parts
        for (int i = 0; i + 1 < nx; ++i) {
            hy[i] += dtr * (ez[i + 1] - ez[i]);
            hz[i] -= dtr * (ey[i + 1] - ey[i]);
        }
        hy[nx - 1] += dtr * (ez[0] * bloch - ez[nx - 1]);
        hz[nx - 1] -= dtr * (ey[0] * bloch - ey[nx - 1]);
    }
}

// D update (n → n+1) using H^{n+½} (H before the first row: the PEC's zero).
void Sim::update_D() {
    const int nx = L.nx, nz = L.nz;
    const double rh = 1.0 / L.h;
    const cplx binv = 1.0 / bloch;
    const double dtr = dt * rh;
    for (int k = 0; k < nz; ++k) {
        const int r = k * nx;
        const double ib = ib_int[k] * dtr;
        cplx* __restrict dx = Dx.data() + r;
        cplx* __restrict dy = Dy.data() + r;
        cplx* __restrict dz = Dz.data() + r;
        const cplx* hx = Hx.data() + r;
        const cplx* hy = Hy.data() + r;
        const cplx* hz = Hz.data() + r;
        const cplx* hx0 = (k > 0) ? hx - nx : zero_row.data();
        const cplx* hy0 = (k > 0) ? hy - nx : zero_row.data();
        for (int i = 0; i < nx; ++i) {
            dx[i] += dt * mul_i(ky, hz[i]) - ib * (hy[i] - hy0[i]);
            dy[i] += ib * (hx[i] - hx0[i]);
            dz[i] -= dt * mul_i(ky, hx[i]);
        }
        if (pml_int[k]) cpml_D_row(k, hx, hx0, hy, hy0);
        dy[0] -= dtr * (hz[0] - hz[nx - 1] * binv);
        dz[0] += dtr * (hy[0] - hy[nx - 1] * binv);
        for (int i = 1; i < nx; ++i) {
            dy[i] -= dtr * (hz[i] - hz[i - 1]);
            dz[i] += dtr * (hy[i] - hy[i - 1]);
        }
    }
}

// Constitutive update E^{n+1} from D^{n+1}: Lorentz ADE (lorentz_ade.cpp), conductivity
// Ṗ_σ = σ E (trapezoidal, implicit per site), ε∞.
void Sim::update_E() {
    std::vector<cplx>* Es[3] = {&Ex, &Ey, &Ez};
    std::vector<cplx>* Ds[3] = {&Dx, &Dy, &Dz};
    const int N = L.nx * L.nz;
    for (int c = 0; c < 3; ++c) {
        auto& E = *Es[c];
        auto& D = *Ds[c];
        cplx* __restrict Pt = Ptot[c].data();
        if (!bilinear) advance_poles_central(c);
        const auto& ss = sites.sigma_sites[c];
        const auto& einv = einv_eff[c];
        tmpE.resize(ss.size());
        for (size_t q = 0; q < ss.size(); ++q) {
            const int s = ss[q].first;
            const double hs = 0.5 * ss[q].second * dt;
            const double einf = 1.0 / einv[s];
            cplx en = (D[s] - Pt[s] - Psig[c][q] - hs * E[s]) / (einf + hs);
            Psig[c][q] += hs * (en + E[s]);
            tmpE[q] = en;
        }
        cplx* __restrict Ep = E.data();
        const cplx* __restrict Dp = D.data();
        const double* __restrict ei = einv.data();
        for (int s = 0; s < N; ++s) Ep[s] = ei[s] * (Dp[s] - Pt[s]);
        for (size_t q = 0; q < ss.size(); ++q) E[ss[q].first] = tmpE[q];
        if (bilinear) advance_poles_bilinear(c);
    }
}

double Sim::energy() const {
    double e = 0;
    for (const auto* v : {&Ex, &Ey, &Ez, &Hx, &Hy, &Hz})
        for (const auto& x : *v) e += std::norm(x);
    return e;
}

}  // namespace plumage::fdtd::detail
