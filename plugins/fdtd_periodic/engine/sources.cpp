// Sources: soft sheets of J_y (family 0) or M_y (family 1), each ∝ e^{i k_x x} (order 0 only),
// with a band-limited pulse (NOTES.md §2 "Source").
#include <algorithm>
#include <cmath>

#include "sim.hpp"

namespace plumage::fdtd::detail {

cplx Pulse::operator()(double t) const {
    double u = t - t0;
    double env = std::exp(-0.25 * s * s * u * u);
    if (std::abs(u) * (w2 - w1) < 1e-6) return env * (w2 - w1) / (2 * kPi);
    return env * (std::exp(cplx(0.0, -w1 * u)) - std::exp(cplx(0.0, -w2 * u))) / cplx(0.0, 2 * kPi * u);
}

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

// A p-th difference of sheets spaced d radiates ∝ (1 − e^{i k_z d})^p / k_z → 0 at the air
// cut-off k_z → 0: the zero-group-velocity (grazing) mode is not excited.
std::vector<std::pair<int, double>> source_sheets(int ks, double h, const SimParams& P) {
    static const double binom[4][4] = {{1, 0, 0, 0}, {1, -1, 0, 0}, {1, -2, 1, 0}, {1, -3, 3, -1}};
    std::vector<std::pair<int, double>> sheets;
    const int dk = std::max(1, static_cast<int>(std::lround(P.source_sheet_spacing / h)));
    for (int j = 0; j < P.source_sheets; ++j) sheets.push_back({ks + j * dk, binom[P.source_sheets - 1][j]});
    return sheets;
}

void Sim::init_source() {
    sheets = {{ks, 1.0}};
    src_phase.resize(L.nx);
    for (int i = 0; i < L.nx; ++i) {
        double x = (i + (family == 1 ? 0.5 : 0.0)) * L.h;
        src_phase[i] = std::exp(cplx(0.0, kx * x));
    }
}

void Sim::inject_magnetic(double tE) {
    const int nx = L.nx;
    const double rh = 1.0 / L.h;
    const double dtr = dt * rh;
    cplx g = pulse(tE) * dtr;
    for (const auto& [row, wt] : sheets)
        for (int i = 0; i < nx; ++i) Hy[row * nx + i] -= (wt * g) * src_phase[i];
}

void Sim::inject_electric(double tH) {
    const int nx = L.nx;
    const double rh = 1.0 / L.h;
    const double dtr = dt * rh;
    cplx g = pulse(tH) * dtr;
    for (const auto& [row, wt] : sheets)
        for (int i = 0; i < nx; ++i) Dy[row * nx + i] -= (wt * g) * src_phase[i];
}

}  // namespace plumage::fdtd::detail
