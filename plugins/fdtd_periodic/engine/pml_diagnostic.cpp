// Diagnostic of the CPML: reflection |r| of the top and bottom PML in a homogeneous medium
// (1 cell wide, one source sheet in the middle, up/down plane-wave decomposition with the
// numerical k_z at two planes on each side).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sim.hpp"

namespace plumage::fdtd {

std::array<double, 2> measure_pml_reflection(const MaterialModel& medium, double h, double kx,
                                             double ky, const std::vector<double>& omegas,
                                             const SimParams& P0) {
    using namespace detail;
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
