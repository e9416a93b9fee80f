// One broadband run at fixed Bloch wavevector (NOTES.md §2): grid layout and time step, the four
// field sets (main and 1-cell air-only normalisation grids of both source families) stepped in
// lockstep, the run-time blow-up guard, the stop rule, then the extraction per frequency.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <time.h>

#include "sim.hpp"

namespace plumage::fdtd {

FieldBlowUp::FieldBlowUp(const std::string& message, int step_, double time_um_, double dt_, double dt_limit_)
    : NumericalError(message), step(step_), time_um(time_um_), dt(dt_), dt_limit(dt_limit_) {}

double courant_limit(double h, double ky, double min_eps_inf) {
    double lim = 1.0 / std::sqrt(2.0 / (h * h) + 0.25 * ky * ky);
    return lim * std::sqrt(std::max(1.0, min_eps_inf));
}

namespace detail {

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

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
    S.sheets = source_sheets(S.ks, h, P);
    S.km = std::max(S.km, S.sheets.back().first + 1);
    if (S.ks <= P.pml_cells || S.L.z0 + S.km * h >= 0)
        throw std::invalid_argument("fdtd: need top PML < source_z < monitor_z < 0 inside the air region");
    double zt = P.transmission_z >= 0 ? P.transmission_z : cell.structure_depth + P.substrate_below / 2;
    S.kt = P.compute_transmission ? S.L.row_of(zt) : -1;
    if (S.kt >= S.L.nz - P.pml_cells - 1) throw std::invalid_argument("fdtd: transmission plane inside PML");
    return S;
}

namespace {

// Angles of every frequency at this (k_x, k_y) and which are valid (propagating with
// k_z/k0 ≥ kz_min); returns the valid band [wlo, whi] (whi = 0: nothing propagates).
std::pair<double, double> init_frequencies(Spectrum& out, const std::vector<double>& omegas, double kx, double ky,
                                           const SimParams& P) {
    out.freqs.resize(omegas.size());
    double wlo = 1e300, whi = 0;
    for (size_t f = 0; f < omegas.size(); ++f) {
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
    return {wlo, whi};
}

// Diffraction orders propagating in air at the highest frequency.
std::vector<int> propagating_orders(double ax, double kx, double whi) {
    std::vector<int> orders = {0};
    const double G = 2 * kPi / ax;
    for (int n = 1; n * G - std::abs(kx) < whi; ++n)
        for (int sgn : {-1, 1})
            if (std::abs(kx + sgn * n * G) < whi) orders.push_back(sgn * n);
    return orders;
}

// The four field sets: [2 fam] main grid, [2 fam + 1] its 1-cell-wide air-only normalisation
// grid with the same z layout and dt (the order-0 harmonic has identical discrete dynamics).
std::vector<Sim> make_sims(const Cell& cell, const Setup& S, double kx, double ky, const std::vector<double>& omegas,
                           const std::vector<int>& orders, const Pulse& pulse, const SimParams& P) {
    const Layout& L = S.L;
    auto gp = global_poles(cell);
    SiteModel sm_main = build_sites(cell, L, P, S.dt, gp, false);
    Layout Ln = L;
    Ln.nx = 1;
    Ln.ax = L.h;
    SiteModel sm_norm = build_sites(cell, Ln, P, S.dt, gp, true);
    std::vector<Sim> sims;
    sims.reserve(4);
    for (int fam = 0; fam < 2; ++fam) {
        sims.emplace_back(L, S.dt, kx, ky, fam, S.ks, pulse, sm_main, gp, P, omegas, S.km, orders, S.kt);
        sims.emplace_back(Ln, S.dt, kx, ky, fam, S.ks, pulse, sm_norm, gp, P, omegas, S.km,
                          std::vector<int>{0}, -1);
        sims[sims.size() - 2].sheets = S.sheets;
        sims.back().sheets = S.sheets;
    }
    return sims;
}

// Blow-up guard, checked every 10 steps: non-finite energy; a main grid's energy above
// blowup_factor × its reference; a normalisation grid's above blowup_factor × its own
// source-phase maximum (after the source). The reference of each main grid is nx × the largest
// energy its air-only normalisation grid (same source, 1 cell wide) has had so far. A passive
// structure cannot hold more field energy than was injected (up to the ε weighting, the source's
// work against the returning reflection and the part of the pulse the short air grid never holds
// at once: ratio 4–22 measured in stable runs, NOTES "Warnings (issue 9)"), and the normalisation
// grid is stable whenever the main one is (air, no x Nyquist mode), so this reference stays clean
// even when the main grid grows during the source phase — where the main grid's own source-phase
// maximum is already polluted by the growth.
class EnergyGuard {
public:
    EnergyGuard(const Setup& S, double t_src_end, double factor) : S_(S), t_src_end_(t_src_end), factor_(factor) {}

    void check(const std::vector<Sim>& sims, int steps) {
        const double t = steps * S_.dt;
        for (size_t q = 0; q < sims.size(); ++q) {
            const double e = sims[q].energy();
            if (!std::isfinite(e)) blow_up(e, emax_[q], "source-phase maximum", steps);
            if (q % 2 == 1) {
                eref_[q / 2] = std::max(eref_[q / 2], e * S_.L.nx);
                if (t > t_src_end_ && emax_[q] > 0 && e > factor_ * emax_[q])
                    blow_up(e, emax_[q], "source-phase maximum", steps);
            } else if (eref_[q / 2] > 0) {
                ratio_max_ = std::max(ratio_max_, e / eref_[q / 2]);
                if (e > factor_ * eref_[q / 2]) blow_up(e, eref_[q / 2], "nx x normalisation-run energy", steps);
            }
            if (t <= t_src_end_) emax_[q] = std::max(emax_[q], e);
        }
    }
    double ratio_max() const { return ratio_max_; }

private:
    [[noreturn]] void blow_up(double e, double ref, const char* what, int steps) const {
        std::ostringstream os;
        os << "fdtd: field blow-up detected (energy " << e << " vs. " << what << " " << ref << ") at step "
           << steps << ", t = " << steps * S_.dt << " um/c; the run is unstable (time step dt = " << S_.dt
           << " = " << S_.dt / S_.lim << " of the stability limit " << S_.lim << ")";
        throw FieldBlowUp(os.str(), steps, steps * S_.dt, S_.dt, S_.lim);
    }

    const Setup& S_;
    double t_src_end_, factor_;
    std::vector<double> emax_ = std::vector<double>(4, 0.0), eref_ = std::vector<double>(2, 0.0);
    double ratio_max_ = 0.0;
};

// Scattered specular DFTs (Ex, Ey, Hx, Hy) of the valid frequencies relative to the incident
// ones, plus the magnitudes of the other orders: what the stop rule watches.
std::vector<cplx> scattered_dfts(const std::vector<Sim>& sims, const std::vector<FreqResult>& freqs) {
    std::vector<cplx> cur;
    for (int fam = 0; fam < 2; ++fam) {
        const auto& m = sims[2 * fam].mon;
        const auto& n = sims[2 * fam + 1].mon;
        for (int c : {0, 1, 3, 4})
            for (size_t f = 0; f < freqs.size(); ++f) {
                if (!freqs[f].valid) continue;
                double inc = std::abs(n.dft[0][0][f]) + std::abs(n.dft[1][0][f]) + std::abs(n.dft[3][0][f]) +
                             std::abs(n.dft[4][0][f]);
                cplx v = (m.dft[c][0][f] - n.dft[c][0][f]) / std::max(inc, 1e-300);
                for (size_t o = 1; o < m.orders.size(); ++o) v += std::abs(m.dft[c][o][f]) / std::max(inc, 1e-300);
                cur.push_back(v);
            }
    }
    return cur;
}

// The lockstep time loop. Stop: after the source, every ~1 µm/c, the scattered DFTs must change
// by < dft_tol twice in a row; hard cap max(max_time, source end + 10 µm/c).
void march(std::vector<Sim>& sims, const Setup& S, double t_src_end, const SimParams& P, Spectrum& out) {
    const int check_every = std::max(10, static_cast<int>(std::lround(1.0 / S.dt)));  // ~1 µm/c
    const int energy_every = 10;
    std::vector<cplx> last;
    int quiet = 0;
    bool converged = false;
    EnergyGuard guard(S, t_src_end, P.blowup_factor);
    int steps = 0;
    while (true) {
        for (auto& s : sims) s.step();
        ++steps;
        const double t = steps * S.dt;
        if (steps % energy_every == 0) guard.check(sims, steps);
        if (t > t_src_end && steps % check_every == 0) {
            const std::vector<cplx> cur = scattered_dfts(sims, out.freqs);
            double change = 0;
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
    out.stats.energy_ratio = guard.ratio_max();
}

}  // namespace
}  // namespace detail

Spectrum run_spectrum(const Cell& cell, double kx, double ky, const std::vector<double>& omegas,
                      const SimParams& P) {
    using namespace detail;
    auto wall0 = std::chrono::steady_clock::now();
    const double cpu0 = thread_cpu_seconds();
    Setup S = make_setup(cell, ky, P);
    const Layout& L = S.L;
    Spectrum out;
    out.kx = kx;
    out.ky = ky;
    const auto [wlo, whi] = init_frequencies(out, omegas, kx, ky, P);
    out.stats.h = L.h;
    out.stats.dt = S.dt;
    out.stats.dt_limit = S.lim;
    out.stats.nz = L.nz;
    out.stats.nx = L.nx;
    if (whi == 0) return out;   // nothing propagating

    const std::vector<int> orders = propagating_orders(cell.ax, kx, whi);
    Pulse pulse = make_pulse(wlo, whi, std::hypot(kx, ky), P.source_min_smoothing, P.source_cut_edge);
    // Numerical-dispersion correction of every non-ambient material for this run (dispersion.cpp).
    const Cell corrected = run_cell(cell, S, kx, ky, wlo, whi, P);
    std::vector<Sim> sims = make_sims(corrected, S, kx, ky, omegas, orders, pulse, P);
    march(sims, S, pulse.end(), P, out);
    for (size_t f = 0; f < omegas.size(); ++f)
        if (out.freqs[f].valid) extract_frequency(sims, S, cell, kx, ky, P, f, out.freqs[f]);
    out.stats.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    out.stats.cpu_seconds = thread_cpu_seconds() - cpu0;
    return out;
}

}  // namespace plumage::fdtd
