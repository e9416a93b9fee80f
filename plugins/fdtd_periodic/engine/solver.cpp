// 2.5D periodic FDTD solver (complex fields, fixed k_x Bloch phase and k_y), see NOTES.md.
//
// Yee positions in the (x, z) plane (i, k integers, h = a_x / nx):
//   Ex (i+½, k)   Ey (i, k)     Ez (i, k+½)
//   Hx (i, k+½)   Hy (i+½, k+½) Hz (i+½, k)
// Arrays are stored [k * nx + i] with the position above. E at t_n = n dt, H at t_{n+½}.
//   ∂t Hx = −(i k_y Ez − ∂̃z Ey)     ∂t Dx = i k_y Hz − ∂̃z Hy
//   ∂t Hy = −(∂̃z Ex − ∂x Ez)        ∂t Dy = ∂̃z Hx − ∂x Hz        − J_y (source family A)
//   ∂t Hz = −(∂x Ey − i k_y Ex)     ∂t Dz = ∂x Hy − i k_y Hx
//   (− M_y on Hy: source family B)   D = ε∞ E + Σ P_Lorentz + P_σ,   ∂̃z = CPML-stretched ∂z.
#include "fdtd_periodic.hpp"
#include "internal.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <sstream>
#include <thread>
#include <time.h>

namespace plumage::fdtd {

double courant_limit(double h, double ky, double min_eps_inf) {
    double lim = 1.0 / std::sqrt(2.0 / (h * h) + 0.25 * ky * ky);
    return lim * std::sqrt(std::max(1.0, min_eps_inf));
}

void incident_basis(double st, double ct, double sp, double cp, Vec3c E[2], Vec3c H[2]) {
    E[0] = {cplx(-st * sp), cplx(ct), cplx(st * cp)};
    H[0] = {cplx(-cp), cplx(0.0), cplx(-sp)};
    E[1] = {cplx(cp), cplx(0.0), cplx(sp)};
    H[1] = {cplx(-st * sp), cplx(ct), cplx(st * cp)};
}

Vec3c to_local_frame(const Vec3c& v) { return {v[0], -v[2], v[1]}; }

namespace {

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

inline cplx mul_i(double s, cplx v) { return {-s * v.imag(), s * v.real()}; }   // i·s·v

// ------------------------------------------------------------------ material layout
struct SiteModel {
    std::vector<double> eps_inf_inv[3];
    // per global pole g: list of (site, weight)
    std::vector<std::vector<std::pair<int, double>>> pole_sites[3];
    std::vector<std::pair<int, double>> sigma_sites[3];   // (site, σ_eff)
};

struct GlobalPole {
    int material;
    LorentzPole pole;
};

// weights w_m ≥ 0, Σ w = 1 minimising Σ_j |Σ_m w_m ε_m(ω_j) − target_j|²
std::vector<double> convex_fit(const std::vector<std::vector<cplx>>& eps_m, const std::vector<cplx>& target) {
    const int M = static_cast<int>(eps_m.size());
    const int J = static_cast<int>(target.size());
    std::vector<double> best(M, 0.0);
    double best_res = 1e300;
    for (int mask = 1; mask < (1 << M); ++mask) {
        std::vector<int> idx;
        for (int m = 0; m < M; ++m)
            if (mask & (1 << m)) idx.push_back(m);
        const int K = static_cast<int>(idx.size());
        std::vector<double> w(K, 0.0);
        if (K == 1) {
            w[0] = 1.0;
        } else {
            // w_last = 1 − Σ others; unknowns u = w[0..K-2]
            Eigen::MatrixXd A(2 * J, K - 1);
            Eigen::VectorXd b(2 * J);
            for (int j = 0; j < J; ++j) {
                cplx last = eps_m[idx[K - 1]][j];
                cplx rhs = target[j] - last;
                b(2 * j) = rhs.real();
                b(2 * j + 1) = rhs.imag();
                for (int q = 0; q < K - 1; ++q) {
                    cplx col = eps_m[idx[q]][j] - last;
                    A(2 * j, q) = col.real();
                    A(2 * j + 1, q) = col.imag();
                }
            }
            Eigen::VectorXd u = A.completeOrthogonalDecomposition().solve(b);
            double s = 0;
            for (int q = 0; q < K - 1; ++q) { w[q] = u(q); s += u(q); }
            w[K - 1] = 1.0 - s;
        }
        bool ok = true;
        for (double x : w)
            if (x < -1e-12) ok = false;
        if (!ok) continue;
        double res = 0;
        for (int j = 0; j < J; ++j) {
            cplx v = 0;
            for (int q = 0; q < K; ++q) v += w[q] * eps_m[idx[q]][j];
            res += std::norm(v - target[j]);
        }
        if (res < best_res - 1e-15) {
            best_res = res;
            std::fill(best.begin(), best.end(), 0.0);
            for (int q = 0; q < K; ++q) best[idx[q]] = std::max(0.0, w[q]);
        }
    }
    return best;
}

struct Layout {
    int nx, nz, npml;
    double h, ax, z0;      // z of row k = z0 + k h
    int row_of(double z) const { return static_cast<int>(std::lround((z - z0) / h)); }
};

// Fill fractions of the dual cell [x ± h/2] × [z ± h/2] of one E site: f[m] = area fraction of
// material m, and the first moment of Re ε about the site (gx, gz; its direction is the
// interface normal used by the anisotropic mix). z is split at every slab face, the ambient
// face z = 0 and every circle's top and bottom; on each piece `nq` Gauss–Legendre rows; on each
// row the x range is split at the chord ends of every circle (nearest periodic images), and the
// painted material is constant on each sub-interval (Cell::material_at at its midpoint). So
// straight faces are exact and curved ones converge fast in nq.
template <class EpsOf>
void dual_cell_fill(const Cell& cell, double x, double z, double h, int nq, EpsOf&& eps_of, std::vector<double>& f,
                    double& gx, double& gz) {
    static const double gl_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                   0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
    static const double gl_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                   0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    (void)nq;  // 8-point rule per z piece (the pieces already isolate every kink)
    const double x0 = x - 0.5 * h, x1 = x + 0.5 * h, z0 = z - 0.5 * h, z1 = z + 0.5 * h;
    std::vector<double> zb = {z0, z1};
    auto addz = [&](double v) { if (v > z0 && v < z1) zb.push_back(v); };
    addz(0.0);
    for (const auto& sl : cell.slabs) { addz(sl.z0); addz(sl.z1); }
    for (const auto& c : cell.circles) { addz(c.z - c.r); addz(c.z + c.r); }
    std::sort(zb.begin(), zb.end());
    std::vector<double> xb;
    const double inv_area = 1.0 / (h * h);
    for (size_t p = 0; p + 1 < zb.size(); ++p) {
        const double za = zb[p], zc = zb[p + 1];
        if (zc - za < 1e-15) continue;
        for (int q = 0; q < 8; ++q) {
            const double zq = 0.5 * (za + zc) + 0.5 * (zc - za) * gl_x[q];
            const double wz = 0.5 * (zc - za) * gl_w[q];
            xb.assign({x0, x1});
            for (const auto& c : cell.circles) {
                const double dz = zq - c.z;
                if (std::abs(dz) >= c.r) continue;
                const double half = std::sqrt(c.r * c.r - dz * dz);
                for (int img = -1; img <= 1; ++img) {
                    const double cx = c.x + img * cell.ax;
                    for (double e : {cx - half, cx + half})
                        if (e > x0 && e < x1) xb.push_back(e);
                }
            }
            std::sort(xb.begin(), xb.end());
            for (size_t a = 0; a + 1 < xb.size(); ++a) {
                const double xa = xb[a], xc = xb[a + 1];
                if (xc - xa <= 0) continue;
                const int m = cell.material_at(0.5 * (xa + xc), zq);
                const double wgt = wz * (xc - xa);
                f[m] += wgt * inv_area;
                const double ev = eps_of(m);
                gx += ev * wz * 0.5 * ((xc - x) * (xc - x) - (xa - x) * (xa - x));
                gz += ev * wgt * (zq - z);
            }
        }
    }
}

// Effective per-site material model of one grid (with subpixel smoothing).
SiteModel build_sites(const Cell& cell, const Layout& L, const SimParams& P, double dt,
                      const std::vector<GlobalPole>& gpoles, bool homogeneous_ambient) {
    const int nm = static_cast<int>(cell.materials.size());
    std::vector<double> omegas = P.smoothing_omegas;
    if (omegas.empty()) {
        bool constant = false;
        for (const auto& m : cell.materials)
            if (m.omega_ref > 0) { constant = true; omegas = {m.omega_ref}; break; }
        if (!constant)
            for (int j = 0; j < 7; ++j) omegas.push_back(2 * kPi / (0.4 + 0.05 * j));
    }
    std::vector<std::vector<cplx>> eps_tab(nm);
    for (int m = 0; m < nm; ++m)
        for (double w : omegas) eps_tab[m].push_back(cell.materials[m].eps(w));
    std::vector<double> sigma_m(nm);
    for (int m = 0; m < nm; ++m) {
        const auto& mm = cell.materials[m];
        sigma_m[m] = mm.eps_imag_ref != 0.0 ? mm.eps_imag_ref * (2.0 / dt) * std::tan(mm.omega_ref * dt / 2) : 0.0;
    }
    SiteModel S;
    const int N = L.nx * L.nz;
    for (int c = 0; c < 3; ++c) {
        S.eps_inf_inv[c].assign(N, 1.0);
        S.pole_sites[c].assign(gpoles.size(), {});
        for (int k = 0; k < L.nz; ++k) {
            for (int i = 0; i < L.nx; ++i) {
                double x = (i + (c == 0 ? 0.5 : 0.0)) * L.h;
                double z = L.z0 + (k + (c == 2 ? 0.5 : 0.0)) * L.h;
                std::vector<double> w(nm, 0.0);
                auto mat = [&](double xx, double zz) {
                    return homogeneous_ambient ? cell.ambient : cell.material_at(xx, zz);
                };
                int m0 = mat(x, z);
                // Fill fractions f_m and first moment (gx, gz) of ε over the dual cell, exact in
                // x (circle chords) and Gauss–Legendre in z between breakpoints (dual_cell_fill),
                // for every site: an 8 × 8 point sample on sites flagged by 9 probes quantised the
                // interface position to h/8 and made the resolution ladder non-monotone (NOTES.md §3).
                bool mixed = false;
                std::vector<double> f(nm, 0.0);
                double gx = 0, gz = 0;
                if (P.smoothing && !homogeneous_ambient && P.exact_fill) {
                    dual_cell_fill(cell, x, z, L.h, P.supersample,
                                   [&](int m) { return eps_tab[m][omegas.size() / 2].real(); }, f, gx, gz);
                    const auto top = std::max_element(f.begin(), f.end());
                    if (*top >= 1.0 - 1e-12) m0 = static_cast<int>(top - f.begin());
                    else mixed = true;
                } else if (P.smoothing && !homogeneous_ambient) {
                    // Sites flagged by 9 probes (centre, corners, edge midpoints of the dual
                    // cell), then an S × S point sample of the fill and of the first moment.
                    const double hh = 0.5 * L.h;
                    for (auto [sx, sz] : {std::pair{-hh, -hh}, {hh, -hh}, {-hh, hh}, {hh, hh},
                                          {0.0, -hh}, {0.0, hh}, {-hh, 0.0}, {hh, 0.0}})
                        if (mat(x + sx, z + sz) != m0) { mixed = true; break; }
                    const int S1 = std::max(2, P.supersample);
                    if (mixed)
                        for (int a = 0; a < S1; ++a)
                            for (int b = 0; b < S1; ++b) {
                                double ox = ((a + 0.5) / S1 - 0.5) * L.h, oz = ((b + 0.5) / S1 - 0.5) * L.h;
                                int m = mat(x + ox, z + oz);
                                f[m] += 1.0 / (S1 * S1);
                                double ev = eps_tab[m][omegas.size() / 2].real();
                                gx += ox * ev * L.h * L.h / (S1 * S1);
                                gz += oz * ev * L.h * L.h / (S1 * S1);
                            }
                }
                if (!mixed) {
                    w[m0] = 1.0;
                } else {
                    double gn = std::hypot(gx, gz);
                    double nd = 0.0;   // normal component along the field direction
                    bool have_normal = gn > 1e-9 * L.h * L.h * L.h;
                    if (c == 0 && have_normal) nd = gx / gn;
                    if (c == 2 && have_normal) nd = gz / gn;
                    std::vector<cplx> target(omegas.size());
                    for (size_t j = 0; j < omegas.size(); ++j) {
                        cplx mean = 0, meaninv = 0;
                        for (int m = 0; m < nm; ++m)
                            if (f[m] > 0) { mean += f[m] * eps_tab[m][j]; meaninv += f[m] / eps_tab[m][j]; }
                        target[j] = 1.0 / (nd * nd * meaninv + (1.0 - nd * nd) / mean);
                    }
                    if (c == 1 || nd == 0.0) {
                        w = f;   // tangential: arithmetic average, exact with the pole model
                    } else {
                        std::vector<int> present;
                        std::vector<std::vector<cplx>> sub;
                        for (int m = 0; m < nm; ++m)
                            if (f[m] > 0) { present.push_back(m); sub.push_back(eps_tab[m]); }
                        auto ws = convex_fit(sub, target);
                        for (size_t q = 0; q < present.size(); ++q) w[present[q]] = ws[q];
                    }
                }
                int s = k * L.nx + i;
                double einf = 0, sig = 0;
                for (int m = 0; m < nm; ++m) {
                    einf += w[m] * cell.materials[m].eps_inf;
                    sig += w[m] * sigma_m[m];
                }
                S.eps_inf_inv[c][s] = 1.0 / einf;
                if (sig != 0.0) S.sigma_sites[c].push_back({s, sig});
                for (size_t g = 0; g < gpoles.size(); ++g)
                    if (w[gpoles[g].material] > 0)
                        S.pole_sites[c][g].push_back({s, w[gpoles[g].material]});
            }
        }
    }
    return S;
}

// ------------------------------------------------------------------ one FDTD field set
// Source time function with a band-limited spectrum: the box [w1, w2] convolved with a Gaussian
// of width s, S(ω) = ½[erf((ω−w1)/s) − erf((ω−w2)/s)]; g(t) = e^{−s²τ²/4}(e^{−i w1 τ} − e^{−i w2 τ})/(2πiτ),
// τ = t − t0. The lower edge is placed halfway between the air cut-off |k| (zero-group-velocity
// "grazing" mode that would ring forever) and the lowest requested frequency.
struct Pulse {
    double w1, w2, s, t0;
    cplx operator()(double t) const {
        double u = t - t0;
        double env = std::exp(-0.25 * s * s * u * u);
        if (std::abs(u) * (w2 - w1) < 1e-6) return env * (w2 - w1) / (2 * kPi);
        return env * (std::exp(cplx(0.0, -w1 * u)) - std::exp(cplx(0.0, -w2 * u))) / cplx(0.0, 2 * kPi * u);
    }
    double end() const { return 2 * t0; }
};

Pulse make_pulse(double wlo, double whi, double wcut, double smin, bool cut_edge) {
    double band = whi - wlo;
    double s = std::max(0.25 * band, 0.05 * whi);
    double w1 = wlo - 2.75 * s;
    if (!cut_edge) {
        w1 = std::max(w1, wcut);
    } else if (wcut > 0 && w1 < wcut + 2.75 * s) {
        s = std::max(smin, (wlo - wcut) / 5.5);
        w1 = 0.5 * (wlo + wcut);
    }
    double w2 = whi + 2.75 * s;
    return Pulse{w1, w2, s, 8.0 / s};
}

struct Monitor {       // harmonic-projected DFTs at a plane (row km)
    int km;
    std::vector<int> orders;
    // dft[comp][order][freq]
    std::vector<std::vector<std::vector<cplx>>> dft;
};

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
    std::vector<std::vector<double>> c1, c2;          // per pole constants (c1, c2 scalars)
    std::vector<std::vector<cplx>> P[3], Pold[3];      // [comp][pole][site]: P, P⁻ (central) / s1, s2 (bilinear)
    std::vector<cplx> Ptot[3];                          // Σ P (central) / Σ s1 (bilinear)
    std::vector<std::vector<double>> W[3];                  // [comp][pole] dense c3·weight
    std::vector<std::pair<int, int>> rows[3];              // [comp][pole] row range
    std::vector<cplx> Psig[3];
    bool bilinear = true;
    std::vector<double> einv_eff[3];                        // 1/(ε∞ + Σ w c) (bilinear), else 1/ε∞
    std::vector<cplx> tmpE;
    std::vector<cplx> src_phase;
    std::vector<double> omegas;
    std::vector<cplx> phE, phH;   // harmonic projection phases
    Monitor mon;
    // x-resolved transmission DFT (Ex, Ey at row kt; Hx, Hy at kt+½)
    int kt = -1;
    std::vector<std::vector<cplx>> tdft[4];   // [comp][freq][i]
    int step_no = 0;
    double energy_ref = 0.0;

    Sim(const Layout& lay, double dt_, double kx_, double ky_, int fam, int ks_, const Pulse& pl,
        SiteModel sm, std::vector<GlobalPole> gp, const SimParams& Pm, const std::vector<double>& om,
        int km, const std::vector<int>& orders, int kt_)
        : L(lay), dt(dt_), kx(kx_), ky(ky_), family(fam), ks(ks_), pulse(pl), sites(std::move(sm)),
          gpoles(std::move(gp)), omegas(om), kt(kt_) {
        sheets = {{ks, 1.0}};
        const int N = L.nx * L.nz;
        for (auto* v : {&Ex, &Ey, &Ez, &Hx, &Hy, &Hz, &Dx, &Dy, &Dz, &pHx, &pHy, &pDx, &pDy}) v->assign(N, 0.0);
        bloch = std::exp(cplx(0.0, kx * L.ax));
        // CPML profiles
        const double d = L.npml * L.h;
        const double ztop = L.z0 + L.npml * L.h;
        const double zbot = L.z0 + (L.nz - 1 - L.npml) * L.h;
        const int m = Pm.pml_order;
        const double smax = Pm.pml_sigma_factor * 0.8 * (m + 1) / L.h;
        auto prof = [&](double z, double& ib, double& b, double& a, char& in) {
            double rho = 0;
            if (z < ztop) rho = (ztop - z) / d;
            if (z > zbot) rho = (z - zbot) / d;
            in = rho > 0;
            rho = std::min(rho, 1.0);
            double sg = smax * std::pow(rho, m);
            double kap = 1.0 + (Pm.pml_kappa_max - 1.0) * std::pow(rho, m);
            double al = in ? Pm.pml_alpha_max * (1.0 - rho) : 0.0;
            ib = 1.0 / kap;
            b = std::exp(-(sg / kap + al) * dt);
            a = (sg > 0) ? sg / (sg * kap + kap * kap * al) * (b - 1.0) : 0.0;
        };
        for (auto* v : {&ib_int, &b_int, &a_int, &ib_half, &b_half, &a_half}) v->assign(L.nz, 0.0);
        pml_int.assign(L.nz, 0);
        pml_half.assign(L.nz, 0);
        for (int k = 0; k < L.nz; ++k) {
            prof(L.z0 + k * L.h, ib_int[k], b_int[k], a_int[k], pml_int[k]);
            prof(L.z0 + (k + 0.5) * L.h, ib_half[k], b_half[k], a_half[k], pml_half[k]);
        }
        // ADE constants: P⁺ = a1 P + a2 P⁻ + c (drive), per pole (NOTES.md §3b).
        //  Bilinear: (P⁺ − 2P + P⁻)/dt² + γ(P⁺ − P⁻)/2dt + ω0²(P⁺ + 2P + P⁻)/4
        //            = Δε ω0² (E⁺ + 2E + E⁻)/4,  drive = E⁺ + 2E + E⁻ (E⁺ solved per site).
        //  CentralDifference: ω0² P and Δε ω0² E at time n, drive = E.
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
        // source phases
        src_phase.resize(L.nx);
        for (int i = 0; i < L.nx; ++i) {
            double x = (i + (family == 1 ? 0.5 : 0.0)) * L.h;
            src_phase[i] = std::exp(cplx(0.0, kx * x));
        }
        // monitor
        mon.km = km;
        mon.orders = orders;
        mon.dft.assign(6, std::vector<std::vector<cplx>>(orders.size(), std::vector<cplx>(om.size(), 0.0)));
        for (size_t o = 0; o < orders.size(); ++o) {
            double kn = kx + 2 * kPi * orders[o] / L.ax;
            for (int i = 0; i < L.nx; ++i) {
                phE.push_back(std::exp(cplx(0.0, -kn * i * L.h)) / double(L.nx));            // integer x
                phH.push_back(std::exp(cplx(0.0, -kn * (i + 0.5) * L.h)) / double(L.nx));    // half x
            }
        }
        if (kt >= 0)
            for (auto& t : tdft) t.assign(om.size(), std::vector<cplx>(L.nx, 0.0));
    }

    double time_E() const { return step_no * dt; }

    // One row of the H update; i0..i1 interior (east neighbour inside the row).
    void step() {
        const int nx = L.nx, nz = L.nz;
        const double rh = 1.0 / L.h;
        const cplx binv = 1.0 / bloch;
        const double dtr = dt * rh;
        // ---------------- H update (n-½ → n+½) using E^n
        for (int k = 0; k < nz; ++k) {
            const int r = k * nx;
            const bool pml = pml_half[k];
            const double ib = ib_half[k] * dtr, bb = b_half[k], aa = a_half[k] * rh;
            cplx* __restrict hx = Hx.data() + r;
            cplx* __restrict hy = Hy.data() + r;
            cplx* __restrict hz = Hz.data() + r;
            const cplx* ex = Ex.data() + r;
            const cplx* ey = Ey.data() + r;
            const cplx* ez = Ez.data() + r;
            static thread_local std::vector<cplx> zero;
            if ((int)zero.size() < nx) zero.assign(nx, 0.0);
            const cplx* ex1 = (k + 1 < nz) ? ex + nx : zero.data();
            const cplx* ey1 = (k + 1 < nz) ? ey + nx : zero.data();
            // z-derivative parts and k_y parts (no x neighbours)
            for (int i = 0; i < nx; ++i) {
                const cplx dEy = ey1[i] - ey[i];
                const cplx dEx = ex1[i] - ex[i];
                hx[i] += ib * dEy - dt * mul_i(ky, ez[i]);
                hy[i] -= ib * dEx;
                hz[i] += dt * mul_i(ky, ex[i]);
            }
            if (pml) {
                cplx* px = pHx.data() + r;
                cplx* py = pHy.data() + r;
                for (int i = 0; i < nx; ++i) {
                    px[i] = bb * px[i] + aa * (ey1[i] - ey[i]);
                    py[i] = bb * py[i] + aa * (ex1[i] - ex[i]);
                    hx[i] += dt * px[i];
                    hy[i] -= dt * py[i];
                }
            }
            // x-derivative parts
            for (int i = 0; i + 1 < nx; ++i) {
                hy[i] += dtr * (ez[i + 1] - ez[i]);
                hz[i] -= dtr * (ey[i + 1] - ey[i]);
            }
            hy[nx - 1] += dtr * (ez[0] * bloch - ez[nx - 1]);
            hz[nx - 1] -= dtr * (ey[0] * bloch - ey[nx - 1]);
        }
        const double tE = step_no * dt;          // time of E^n
        const double tH = tE + 0.5 * dt;         // time of H^{n+½}
        if (family == 1) {
            cplx g = pulse(tE) * dtr;
            for (const auto& [row, wt] : sheets)
                for (int i = 0; i < nx; ++i) Hy[row * nx + i] -= (wt * g) * src_phase[i];
        }
        // ---------------- D update (n → n+1) using H^{n+½}
        for (int k = 0; k < nz; ++k) {
            const int r = k * nx;
            const bool pml = pml_int[k];
            const double ib = ib_int[k] * dtr, bb = b_int[k], aa = a_int[k] * rh;
            cplx* __restrict dx = Dx.data() + r;
            cplx* __restrict dy = Dy.data() + r;
            cplx* __restrict dz = Dz.data() + r;
            const cplx* hx = Hx.data() + r;
            const cplx* hy = Hy.data() + r;
            const cplx* hz = Hz.data() + r;
            static thread_local std::vector<cplx> zero;
            if ((int)zero.size() < nx) zero.assign(nx, 0.0);
            const cplx* hx0 = (k > 0) ? hx - nx : zero.data();
            const cplx* hy0 = (k > 0) ? hy - nx : zero.data();
            for (int i = 0; i < nx; ++i) {
                dx[i] += dt * mul_i(ky, hz[i]) - ib * (hy[i] - hy0[i]);
                dy[i] += ib * (hx[i] - hx0[i]);
                dz[i] -= dt * mul_i(ky, hx[i]);
            }
            if (pml) {
                cplx* px = pDx.data() + r;
                cplx* py = pDy.data() + r;
                for (int i = 0; i < nx; ++i) {
                    px[i] = bb * px[i] + aa * (hy[i] - hy0[i]);
                    py[i] = bb * py[i] + aa * (hx[i] - hx0[i]);
                    dx[i] -= dt * px[i];
                    dy[i] += dt * py[i];
                }
            }
            dy[0] -= dtr * (hz[0] - hz[nx - 1] * binv);
            dz[0] += dtr * (hy[0] - hy[nx - 1] * binv);
            for (int i = 1; i < nx; ++i) {
                dy[i] -= dtr * (hz[i] - hz[i - 1]);
                dz[i] += dtr * (hy[i] - hy[i - 1]);
            }
        }
        if (family == 0) {
            cplx g = pulse(tH) * dtr;
            for (const auto& [row, wt] : sheets)
                for (int i = 0; i < nx; ++i) Dy[row * nx + i] -= (wt * g) * src_phase[i];
        }
        // ---------------- constitutive update (Lorentz ADE, conductivity, ε∞)
        // Bilinear: P(z) = c (1 + z⁻¹)² / (1 − a1 z⁻¹ − a2 z⁻²) E(z) in transposed direct form,
        //   P⁺ = c E⁺ + s1,  s1 ← 2c E⁺ + a1 P⁺ + s2,  s2 ← c E⁺ + a2 P⁺  (P ↦ s1, Pold ↦ s2),
        // so E⁺ = (D⁺ − Σ s1)/(ε∞ + Σ c) needs only the stored Ptot = Σ s1 (no E⁻ array).
        // Central difference: P⁺ = a1 P + a2 P⁻ + c E, Ptot = Σ P, then E⁺ = (D⁺ − Ptot)/ε∞.
        std::vector<cplx>* Es[3] = {&Ex, &Ey, &Ez};
        std::vector<cplx>* Ds[3] = {&Dx, &Dy, &Dz};
        const int N = nx * nz;
        for (int c = 0; c < 3; ++c) {
            auto& E = *Es[c];
            auto& D = *Ds[c];
            cplx* __restrict Pt = Ptot[c].data();
            if (!bilinear)
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
            if (bilinear)
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
        ++step_no;
        accumulate_dft();
    }

    void accumulate_dft() {
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

    double energy() const {
        double e = 0;
        for (const auto* v : {&Ex, &Ey, &Ez, &Hx, &Hy, &Hz})
            for (const auto& x : *v) e += std::norm(x);
        return e;
    }
};

// Numerical (Yee) k_z in a medium with permittivity eps for harmonic kxn; returns NaN if evanescent.
double yee_kz(double omega, double kxn, double ky, double h, double dt, double eps = 1.0) {
    double lhs = eps * std::pow(2.0 / dt * std::sin(omega * dt / 2), 2);
    double rhs = lhs - std::pow(2.0 / h * std::sin(kxn * h / 2), 2) - ky * ky;
    double s = rhs * h * h / 4;
    if (s <= 0 || s > 1) return std::nan("");
    return 2.0 / h * std::asin(std::sqrt(s));
}

Vec3c cross(const std::array<double, 3>& a, const Vec3c& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3c transverse(const std::array<double, 3>& k, Vec3c v) {
    cplx d = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    for (int c = 0; c < 3; ++c) v[c] -= k[c] * d;
    return v;
}

struct Setup {
    Layout L;
    double dt;
    double lim;   // stability limit (stable_time_step) of this run
    int ks, km, kt;
    std::vector<std::pair<int, double>> sheets;
};

Setup make_setup(const Cell& cell, double ky, const SimParams& P) {
    if (P.nx < 1) throw std::invalid_argument("fdtd: nx must be >= 1");
    Setup S;
    S.L.nx = P.nx;
    S.L.ax = cell.ax;
    S.L.h = cell.ax / P.nx;
    S.L.npml = P.pml_cells;
    const double h = S.L.h;
    int n_air = static_cast<int>(std::ceil(P.air_above / h - 1e-9));
    int n_ss = static_cast<int>(std::ceil((cell.structure_depth + P.substrate_below) / h - 1e-9));
    S.L.z0 = -(n_air + P.pml_cells) * h;
    S.L.nz = P.pml_cells + n_air + n_ss + P.pml_cells + 1;
    // Stability limit from the Courant condition and, for the central-difference ADE, the
    // Lorentz poles (stability.cpp, NOTES.md §3b).
    const double lim = stable_time_step(cell, h, ky, P.lorentz_update);
    S.lim = lim;
    if (P.dt > 0) {
        if (P.dt > lim && !P.allow_unstable_dt) {
            std::ostringstream os;
            os.precision(10);
            os << "fdtd: time step dt = " << P.dt << " exceeds the Courant limit " << lim
               << " (c = 1, h = " << h << " um, k_y = " << ky << " /um: dt <= 1/sqrt(2/h^2 + k_y^2/4)";
            if (P.lorentz_update == LorentzUpdate::CentralDifference)
                os << ", lowered so that dt^2 (8/h^2 + k_y^2) <= 4 eps_Nyquist of every material";
            os << ")";
            throw std::invalid_argument(os.str());
        }
        S.dt = P.dt;
    } else {
        if (!(P.courant > 0 && P.courant <= 1.0))
            throw std::invalid_argument("fdtd: courant factor must be in (0, 1]");
        S.dt = P.courant * lim;
    }
    S.ks = S.L.row_of(P.source_z);
    S.km = S.L.row_of(P.monitor_z);
    if (P.source_sheets < 1 || P.source_sheets > 4) throw std::invalid_argument("fdtd: source_sheets must be 1..4");
    {
        static const double binom[4][4] = {{1, 0, 0, 0}, {1, -1, 0, 0}, {1, -2, 1, 0}, {1, -3, 3, -1}};
        const int dk = std::max(1, static_cast<int>(std::lround(P.source_sheet_spacing / h)));
        for (int j = 0; j < P.source_sheets; ++j) S.sheets.push_back({S.ks + j * dk, binom[P.source_sheets - 1][j]});
    }
    S.km = std::max(S.km, S.sheets.back().first + 1);
    if (S.ks <= P.pml_cells || S.L.z0 + S.km * h >= 0)
        throw std::invalid_argument("fdtd: need top PML < source_z < monitor_z < 0 inside the air region");
    double zt = P.transmission_z >= 0 ? P.transmission_z : cell.structure_depth + P.substrate_below / 2;
    S.kt = P.compute_transmission ? S.L.row_of(zt) : -1;
    if (S.kt >= S.L.nz - P.pml_cells - 1) throw std::invalid_argument("fdtd: transmission plane inside PML");
    return S;
}

std::vector<GlobalPole> global_poles(const Cell& cell) {
    std::vector<GlobalPole> g;
    for (size_t m = 0; m < cell.materials.size(); ++m)
        for (const auto& p : cell.materials[m].poles) g.push_back({static_cast<int>(m), p});
    return g;
}

}  // namespace

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

// ------------------------------------------------------------------ broadband run
Spectrum run_spectrum(const Cell& cell, double kx, double ky, const std::vector<double>& omegas,
                      const SimParams& P) {
    auto wall0 = std::chrono::steady_clock::now();
    const double cpu0 = thread_cpu_seconds();
    Setup S = make_setup(cell, ky, P);
    const Layout& L = S.L;
    Spectrum out;
    out.kx = kx;
    out.ky = ky;
    const size_t nf = omegas.size();
    out.freqs.resize(nf);
    double wlo = 1e300, whi = 0;
    for (size_t f = 0; f < nf; ++f) {
        auto& r = out.freqs[f];
        double w = omegas[f];
        r.omega = w;
        r.lambda = 2 * kPi / w;
        double kz2 = w * w - kx * kx - ky * ky;
        if (kz2 <= 0) continue;
        double kz = std::sqrt(kz2);
        r.sin_theta = -ky / w;
        r.cos_theta = std::sqrt(std::max(0.0, 1.0 - r.sin_theta * r.sin_theta));
        r.sin_phi = -kx / (w * r.cos_theta);
        r.cos_phi = kz / (w * r.cos_theta);
        r.valid = kz / w >= P.kz_min;
        if (r.valid) { wlo = std::min(wlo, w); whi = std::max(whi, w); }
    }
    out.stats.h = L.h;
    out.stats.dt = S.dt;
    out.stats.dt_limit = S.lim;
    out.stats.nz = L.nz;
    out.stats.nx = L.nx;
    if (whi == 0) return out;   // nothing propagating

    // diffraction orders propagating in air at the highest frequency
    std::vector<int> orders = {0};
    const double G = 2 * kPi / cell.ax;
    for (int n = 1; n * G - std::abs(kx) < whi; ++n)
        for (int sgn : {-1, 1})
            if (std::abs(kx + sgn * n * G) < whi) orders.push_back(sgn * n);
    Pulse pulse = make_pulse(wlo, whi, std::hypot(kx, ky), P.source_min_smoothing, P.source_cut_edge);
    const double t_src_end = pulse.end();

    // Numerical-dispersion correction of every non-ambient material for this run (k_x, k_y, h,
    // dt), fitted over the valid band (dispersion_corrected above).
    Cell run_cell = cell;
    if (P.dispersion_correction) {
        std::vector<double> ws;
        const int nfit = whi > wlo ? 24 : 1;
        for (int j = 0; j < nfit; ++j) ws.push_back(nfit == 1 ? whi : wlo + (whi - wlo) * j / (nfit - 1));
        for (size_t m = 0; m < run_cell.materials.size(); ++m)
            if (static_cast<int>(m) != cell.ambient) {
                MaterialModel corr = dispersion_corrected(cell.materials[m], L.h, S.dt, kx, ky, ws, P.lorentz_update);
                // The refit lowers ε∞ slightly; keep the material only if dt stays stable with it.
                Cell probe;
                probe.materials = {corr};
                if (S.dt <= stable_time_step(probe, L.h, ky, P.lorentz_update) || P.allow_unstable_dt)
                    run_cell.materials[m] = corr;
            }
    }
    auto gp = global_poles(run_cell);
    SiteModel sm_main = build_sites(run_cell, L, P, S.dt, gp, false);
    Layout Ln = L;
    Ln.nx = 1;
    Ln.ax = L.h;
    Cell air_cell = run_cell;
    SiteModel sm_norm = build_sites(air_cell, Ln, P, S.dt, gp, true);

    std::vector<Sim> sims;
    sims.reserve(4);
    for (int fam = 0; fam < 2; ++fam) {
        sims.emplace_back(L, S.dt, kx, ky, fam, S.ks, pulse, sm_main, gp, P, omegas, S.km, orders, S.kt);
        sims.emplace_back(Ln, S.dt, kx, ky, fam, S.ks, pulse, sm_norm, gp, P, omegas, S.km,
                          std::vector<int>{0}, -1);
        sims[sims.size() - 2].sheets = S.sheets;
        sims.back().sheets = S.sheets;
    }
    // main loop
    const int check_every = std::max(10, static_cast<int>(std::lround(1.0 / S.dt)));  // ~1 µm/c
    const int energy_every = 10;
    std::vector<cplx> last;
    int quiet = 0;
    bool converged = false;
    std::vector<double> emax(4, 0.0);
    // Reference energy of each main grid: nx × the largest energy its air-only normalisation grid
    // (same source, 1 cell wide) has had so far. A passive structure cannot hold more field energy
    // than was injected (up to the ε weighting, the source's work against the returning reflection
    // and the part of the pulse the short air grid never holds at once: ratio 4–22 measured in
    // stable runs, NOTES "Warnings (issue 9)"), and the normalisation grid is stable whenever the
    // main one is (air, no x Nyquist mode), so this reference stays clean even when the main grid
    // grows during the source phase — where the main grid's own source-phase maximum is already
    // polluted by the growth.
    std::vector<double> eref(2, 0.0);
    double ratio_max = 0.0;
    int steps = 0;
    auto blow_up = [&](double e, double ref, const char* what) {
        std::ostringstream os;
        os << "fdtd: field blow-up detected (energy " << e << " vs. " << what << " " << ref << ") at step "
           << steps << ", t = " << steps * S.dt << " um/c; the run is unstable (time step dt = " << S.dt
           << " = " << S.dt / S.lim << " of the stability limit " << S.lim << ")";
        throw std::runtime_error(os.str());
    };
    while (true) {
        for (auto& s : sims) s.step();
        ++steps;
        const double t = steps * S.dt;
        if (steps % energy_every == 0) {
            for (size_t q = 0; q < sims.size(); ++q) {
                const double e = sims[q].energy();
                if (!std::isfinite(e)) blow_up(e, emax[q], "source-phase maximum");
                if (q % 2 == 1) {
                    eref[q / 2] = std::max(eref[q / 2], e * L.nx);
                    if (t > t_src_end && emax[q] > 0 && e > P.blowup_factor * emax[q])
                        blow_up(e, emax[q], "source-phase maximum");
                } else if (eref[q / 2] > 0) {
                    ratio_max = std::max(ratio_max, e / eref[q / 2]);
                    if (e > P.blowup_factor * eref[q / 2])
                        blow_up(e, eref[q / 2], "nx x normalisation-run energy");
                }
                if (t <= t_src_end) emax[q] = std::max(emax[q], e);
            }
        }
        if (t > t_src_end && steps % check_every == 0) {
            // scattered specular DFTs (Ex, Ey, Hx, Hy) relative to the incident ones
            std::vector<cplx> cur;
            double change = 0;
            for (int fam = 0; fam < 2; ++fam) {
                const auto& m = sims[2 * fam].mon;
                const auto& n = sims[2 * fam + 1].mon;
                for (int c : {0, 1, 3, 4})
                    for (size_t f = 0; f < nf; ++f) {
                        if (!out.freqs[f].valid) continue;
                        double inc = std::abs(n.dft[0][0][f]) + std::abs(n.dft[1][0][f]) +
                                     std::abs(n.dft[3][0][f]) + std::abs(n.dft[4][0][f]);
                        cplx v = (m.dft[c][0][f] - n.dft[c][0][f]) / std::max(inc, 1e-300);
                        for (size_t o = 1; o < m.orders.size(); ++o) v += std::abs(m.dft[c][o][f]) / std::max(inc, 1e-300);
                        cur.push_back(v);
                    }
            }
            if (last.size() == cur.size())
                for (size_t q = 0; q < cur.size(); ++q) change = std::max(change, std::abs(cur[q] - last[q]));
            else
                change = 1e300;
            last = cur;
            quiet = (change < P.dft_tol) ? quiet + 1 : 0;
            if (quiet >= 2) { converged = true; break; }
        }
        if (t > std::max(P.max_time, t_src_end + 10.0)) break;
    }
    out.stats.steps = steps;
    out.stats.sim_time = steps * S.dt;
    out.stats.converged = converged;
    out.stats.energy_ratio = ratio_max;

    // ---------------- post-processing
    const double h = L.h, dt = S.dt;
    const double zE = L.z0 + S.km * h;      // Ex, Ey, Hz rows
    const double zH = zE + 0.5 * h;         // Ez, Hx, Hy rows
    const double zc[6] = {zE, zE, zH, zH, zH, zE};
    for (size_t f = 0; f < nf; ++f) {
        auto& r = out.freqs[f];
        if (!r.valid) continue;
        const double w = omegas[f];
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
            if (P.compute_transmission) {
                double Ft = 0;
                const auto& a = sims[0];
                const auto& b = sims[2];
                for (int i = 0; i < L.nx; ++i) {
                    cplx ex = ca * a.tdft[0][f][i] + cb * b.tdft[0][f][i];
                    cplx ey = ca * a.tdft[1][f][i] + cb * b.tdft[1][f][i];
                    cplx hx = ca * a.tdft[2][f][i] + cb * b.tdft[2][f][i];
                    cplx hy = ca * a.tdft[3][f][i] + cb * b.tdft[3][f][i];
                    Ft += (ex * std::conj(hy) - ey * std::conj(hx)).real();
                }
                r.T[p] = Ft / L.nx / Finc;
            }
        }
    }
    out.stats.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    out.stats.cpu_seconds = thread_cpu_seconds() - cpu0;
    return out;
}

std::vector<Spectrum> run_batch(const Cell& cell, const std::vector<Job>& jobs,
                                const std::vector<double>& omegas, const SimParams& params, int threads) {
    std::vector<std::exception_ptr> errs;
    auto out = run_batch_collect(cell, jobs, omegas, params, threads, errs);
    for (auto& e : errs)
        if (e) std::rethrow_exception(e);
    return out;
}

std::vector<Spectrum> run_batch_collect(const Cell& cell, const std::vector<Job>& jobs,
                                        const std::vector<double>& omegas, const SimParams& params, int threads,
                                        std::vector<std::exception_ptr>& errs) {
    std::vector<Spectrum> out(jobs.size());
    errs.assign(jobs.size(), nullptr);
    std::mutex mu;
    size_t next = 0;
    auto worker = [&] {
        while (true) {
            size_t j;
            {
                std::lock_guard<std::mutex> lk(mu);
                if (next >= jobs.size()) return;
                j = next++;
            }
            try {
                out[j] = run_spectrum(cell, jobs[j].kx, jobs[j].ky, omegas, params);
            } catch (...) {
                errs[j] = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
    return out;
}

// ------------------------------------------------------------------ PML diagnostic
std::array<double, 2> measure_pml_reflection(const MaterialModel& medium, double h, double kx,
                                             double ky, const std::vector<double>& omegas,
                                             const SimParams& P0) {
    SimParams P = P0;
    P.nx = 1;
    Cell cell;
    cell.materials = {medium};
    cell.ambient = cell.substrate = 0;
    if (!(h > 0)) throw std::invalid_argument("measure_pml_reflection: h must be > 0");
    cell.ax = h;
    cell.structure_depth = 0.0;
    P.air_above = 0.6;
    P.substrate_below = 0.6;
    Layout L;
    L.nx = 1;
    L.ax = h;
    L.h = h;
    L.npml = P.pml_cells;
    const int nin = static_cast<int>(std::ceil(1.2 / h));
    L.nz = 2 * P.pml_cells + nin + 1;
    L.z0 = -(P.pml_cells + nin / 2) * h;
    double dt = P.dt > 0 ? P.dt : P.courant * stable_time_step(cell, h, ky, P.lorentz_update);
    const int ks = L.row_of(0.0);
    const int dk = static_cast<int>(std::lround(0.12 / h));
    const int rows[4] = {ks - 2 * dk - 5, ks - dk - 5, ks + dk + 5, ks + 2 * dk + 5};
    double wlo = 1e300, whi = 0;
    for (double w : omegas) {
        double er = medium.eps(w).real();
        double kz2 = w * w * er - kx * kx - ky * ky;
        if (kz2 > 0 && std::sqrt(kz2 / er) / w >= P.kz_min) { wlo = std::min(wlo, w); whi = std::max(whi, w); }
    }
    if (whi == 0) return {0, 0};
    Pulse pulse = make_pulse(wlo, whi, std::hypot(kx, ky) / std::sqrt(medium.eps(wlo).real()),
                             P.source_min_smoothing, true);
    auto gp = global_poles(cell);
    SiteModel sm = build_sites(cell, L, P, dt, gp, true);
    Sim s(L, dt, kx, ky, 0, ks, pulse, sm, gp, P, omegas, rows[0], std::vector<int>{0}, -1);
    const int nsteps = static_cast<int>(std::ceil(std::min(P.max_time, pulse.end() + 60.0) / dt));
    std::vector<std::vector<cplx>> dft(4, std::vector<cplx>(omegas.size(), 0.0));
    for (int n = 0; n < nsteps; ++n) {
        s.step();
        double t = s.step_no * dt;
        for (int q = 0; q < 4; ++q)
            for (size_t f = 0; f < omegas.size(); ++f)
                dft[q][f] += s.Ey[rows[q]] * std::exp(cplx(0.0, omegas[f] * t));
    }
    std::array<double, 2> worst = {0, 0};
    for (size_t f = 0; f < omegas.size(); ++f) {
        double w = omegas[f];
        cplx eps = medium.eps(w);
        double kz = yee_kz(w, kx, ky, h, dt, eps.real());
        if (!std::isfinite(kz) || std::sqrt(w * w * eps.real() - kx * kx - ky * ky) / (w * std::sqrt(eps.real())) < P.kz_min)
            continue;
        for (int side = 0; side < 2; ++side) {
            int r1 = rows[2 * side], r2 = rows[2 * side + 1];
            double z1 = L.z0 + r1 * h, z2 = L.z0 + r2 * h;
            // E = d e^{ikz} + u e^{-ikz}
            Eigen::Matrix2cd A;
            A << std::exp(cplx(0, kz * z1)), std::exp(cplx(0, -kz * z1)), std::exp(cplx(0, kz * z2)),
                std::exp(cplx(0, -kz * z2));
            Eigen::Vector2cd b(dft[2 * side][f], dft[2 * side + 1][f]);
            Eigen::Vector2cd du = A.colPivHouseholderQr().solve(b);
            double rr = side == 0 ? std::abs(du(0)) / std::abs(du(1))    // top: down / up
                                  : std::abs(du(1)) / std::abs(du(0));   // bottom: up / down
            worst[side] = std::max(worst[side], rr);
        }
    }
    return worst;
}

}  // namespace plumage::fdtd
