// Materials of the Yee sites: cell painting, sub-pixel fill fractions and the anisotropic mix of
// mixed sites (NOTES.md §3, §3a).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sim.hpp"

namespace plumage::fdtd {

int Cell::material_at(double x, double z) const {
    if (z < 0.0) return ambient;
    int m = substrate;
    for (const auto& s : slabs)
        if (z >= s.z0 && z < s.z1) m = s.material;
    for (const auto& c : circles) {
        double dx = x - c.x;
        dx -= ax * std::floor(dx / ax + 0.5);   // nearest periodic image
        double dz = z - c.z;
        if (dx * dx + dz * dz < c.r * c.r) m = c.material;
    }
    return m;
}

namespace detail {

namespace {

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

// Fill fractions of the dual cell [x ± h/2] × [z ± h/2] of one E site: f[m] = area fraction of
// material m, and the first moment of Re ε about the site (gx, gz; its direction is the
// interface normal used by the anisotropic mix). z is split at every slab face, the ambient
// face z = 0 and every circle's top and bottom; on each piece 8 Gauss–Legendre rows; on each
// row the x range is split at the chord ends of every circle (nearest periodic images), and the
// painted material is constant on each sub-interval (Cell::material_at at its midpoint). So
// straight faces are exact and curved ones converge fast (the pieces already isolate every kink).
template <class EpsOf>
void dual_cell_fill(const Cell& cell, double x, double z, double h, EpsOf&& eps_of, std::vector<double>& f,
                    double& gx, double& gz) {
    static const double gl_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                   0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
    static const double gl_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                   0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
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

// Frequencies at which mixed sites are fitted, and every material's ε there.
struct MixTable {
    std::vector<double> omegas;
    std::vector<std::vector<cplx>> eps;   // [material][omega]
    double eps_mid(int m) const { return eps[m][omegas.size() / 2].real(); }
};

MixTable mix_table(const Cell& cell, const SimParams& P) {
    MixTable t;
    t.omegas = P.smoothing_omegas;
    if (t.omegas.empty()) {
        bool constant = false;
        for (const auto& m : cell.materials)
            if (m.omega_ref > 0) { constant = true; t.omegas = {m.omega_ref}; break; }
        if (!constant)
            for (int j = 0; j < 7; ++j) t.omegas.push_back(2 * kPi / (0.4 + 0.05 * j));
    }
    t.eps.resize(cell.materials.size());
    for (size_t m = 0; m < cell.materials.size(); ++m)
        for (double w : t.omegas) t.eps[m].push_back(cell.materials[m].eps(w));
    return t;
}

// Fill fractions f_m and first moment (gx, gz) of ε over the dual cell of the site at (x, z);
// false when the site is not mixed (then m0 is its material). exact_fill: exact in x (circle
// chords) and Gauss–Legendre in z between breakpoints (dual_cell_fill), on every site; else an
// S × S point sample on sites flagged by 9 probes (centre, corners, edge midpoints), which
// quantises the interface position to h/S and made the resolution ladder non-monotone (NOTES §3).
bool fill_of_site(const Cell& cell, const MixTable& mix, const SimParams& P, double h, double x, double z,
                  int& m0, std::vector<double>& f, double& gx, double& gz) {
    if (P.exact_fill) {
        dual_cell_fill(cell, x, z, h, [&](int m) { return mix.eps_mid(m); }, f, gx, gz);
        const auto top = std::max_element(f.begin(), f.end());
        if (*top >= 1.0 - 1e-12) {
            m0 = static_cast<int>(top - f.begin());
            return false;
        }
        return true;
    }
    bool mixed = false;
    const double hh = 0.5 * h;
    for (auto [sx, sz] : {std::pair{-hh, -hh}, {hh, -hh}, {-hh, hh}, {hh, hh},
                          {0.0, -hh}, {0.0, hh}, {-hh, 0.0}, {hh, 0.0}})
        if (cell.material_at(x + sx, z + sz) != m0) { mixed = true; break; }
    const int S1 = std::max(2, P.supersample);
    if (mixed)
        for (int a = 0; a < S1; ++a)
            for (int b = 0; b < S1; ++b) {
                double ox = ((a + 0.5) / S1 - 0.5) * h, oz = ((b + 0.5) / S1 - 0.5) * h;
                int m = cell.material_at(x + ox, z + oz);
                f[m] += 1.0 / (S1 * S1);
                double ev = mix.eps_mid(m);
                gx += ox * ev * h * h / (S1 * S1);
                gz += oz * ev * h * h / (S1 * S1);
            }
    return mixed;
}

// Weights w_m of a mixed site for component c (0 x, 1 y, 2 z): E_y (along the rods, always
// tangential) the arithmetic mean Σ f_m ε_m — exact in the pole model; E_x, E_z the Kottke-type
// mix 1/ε_eff = n_d²⟨1/ε⟩ + (1−n_d²)/⟨ε⟩ at the mix frequencies, represented as a convex
// combination Σ w_m ε_m(ω) so that the site keeps passive ADE poles.
std::vector<double> mixed_weights(const MixTable& mix, int c, double h, const std::vector<double>& f, double gx,
                                  double gz) {
    const int nm = static_cast<int>(f.size());
    std::vector<double> w(nm, 0.0);
    double gn = std::hypot(gx, gz);
    double nd = 0.0;   // normal component along the field direction
    bool have_normal = gn > 1e-9 * h * h * h;
    if (c == 0 && have_normal) nd = gx / gn;
    if (c == 2 && have_normal) nd = gz / gn;
    std::vector<cplx> target(mix.omegas.size());
    for (size_t j = 0; j < mix.omegas.size(); ++j) {
        cplx mean = 0, meaninv = 0;
        for (int m = 0; m < nm; ++m)
            if (f[m] > 0) { mean += f[m] * mix.eps[m][j]; meaninv += f[m] / mix.eps[m][j]; }
        target[j] = 1.0 / (nd * nd * meaninv + (1.0 - nd * nd) / mean);
    }
    if (c == 1 || nd == 0.0) return f;   // tangential: arithmetic average, exact with the pole model
    std::vector<int> present;
    std::vector<std::vector<cplx>> sub;
    for (int m = 0; m < nm; ++m)
        if (f[m] > 0) { present.push_back(m); sub.push_back(mix.eps[m]); }
    auto ws = convex_fit(sub, target);
    for (size_t q = 0; q < present.size(); ++q) w[present[q]] = ws[q];
    return w;
}

}  // namespace

std::vector<GlobalPole> global_poles(const Cell& cell) {
    std::vector<GlobalPole> g;
    for (size_t m = 0; m < cell.materials.size(); ++m)
        for (const auto& p : cell.materials[m].poles) g.push_back({static_cast<int>(m), p});
    return g;
}

SiteModel build_sites(const Cell& cell, const Layout& L, const SimParams& P, double dt,
                      const std::vector<GlobalPole>& gpoles, bool homogeneous_ambient) {
    const int nm = static_cast<int>(cell.materials.size());
    const MixTable mix = mix_table(cell, P);
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
                int m0 = homogeneous_ambient ? cell.ambient : cell.material_at(x, z);
                bool mixed = false;
                std::vector<double> f(nm, 0.0);
                double gx = 0, gz = 0;
                if (P.smoothing && !homogeneous_ambient) mixed = fill_of_site(cell, mix, P, L.h, x, z, m0, f, gx, gz);
                if (!mixed) w[m0] = 1.0;
                else w = mixed_weights(mix, c, L.h, f, gx, gz);
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

}  // namespace detail
}  // namespace plumage::fdtd
