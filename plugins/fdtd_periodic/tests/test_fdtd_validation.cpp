// Slow checks (CTest label "validation"): resolution ladder of a real crystal cell and the
// production timing used for the table-time estimate in NOTES.md.
#include <catch2/catch.hpp>

#include "fdtd_periodic.hpp"
#include "spec_cells.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

using namespace plumage::fdtd;
using plumage::fdtd_testing::spec_cell;

namespace {
std::vector<double> omegas_band() {
    std::vector<double> w;
    for (double l = 0.40; l <= 0.70 + 1e-9; l += 0.02) w.push_back(2 * kPi / l);
    return w;
}
double max_diff(const Spectrum& a, const Spectrum& b) {
    double d = 0;
    for (size_t f = 0; f < a.freqs.size(); ++f) {
        if (!a.freqs[f].valid || !b.freqs[f].valid) continue;
        for (int p = 0; p < 2; ++p)
            for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.freqs[f].E[p][c] - b.freqs[f].E[p][c]));
    }
    return d;
}
}  // namespace

TEST_CASE("resolution ladder of mallard-green (oblique, conical)", "[validation][ladder]") {
    Cell c = spec_cell("mallard-green");
    const double k0 = 2 * kPi / 0.55, th = 20 * kPi / 180, ph = 30 * kPi / 180;
    const double kx = -k0 * std::cos(th) * std::sin(ph), ky = -k0 * std::sin(th);
    const auto om = omegas_band();
    SimParams P;
    P.nx = 76;   // reference h = 2.5 nm
    Spectrum ref = run_spectrum(c, kx, ky, om, P);
    std::printf("ladder reference nx=76 (h=%.2f nm): %d steps, %.1f s\n", ref.stats.h * 1e3, ref.stats.steps,
                ref.stats.wall_seconds);
    double d38 = 1;
    for (int nx : {19, 25, 38, 50}) {
        for (bool smooth : {true, false}) {
            if (!smooth && nx != 19 && nx != 38) continue;
            SimParams Q;
            Q.nx = nx;
            Q.smoothing = smooth;
            Spectrum s = run_spectrum(c, kx, ky, om, Q);
            double d = max_diff(s, ref);
            if (nx == 38 && smooth) d38 = d;
            std::printf("ladder nx=%d (h=%.2f nm) smoothing=%d: max |dE| vs nx=76 = %.2e (%d steps, %.1f s)\n",
                        nx, s.stats.h * 1e3, int(smooth), d, s.stats.steps, s.stats.wall_seconds);
        }
    }
    CHECK(d38 < 0.02);
}

TEST_CASE("production timing: batch of broadband runs on 2 threads", "[validation][timing]") {
    Cell c = spec_cell("mallard-green");
    std::vector<Job> jobs;
    for (double kabs : {0.0, 4.0, 8.0, 10.0, 12.0, 14.0}) jobs.push_back({-kabs * 0.7071, -kabs * 0.7071});
    // k-grid estimate for the 50 λ × 20 cosθ × 50 cosφ table: quadrant |k| <= 2π/0.4 with Δk = 0.5/µm
    const double nruns = 0.25 * kPi * std::pow(2 * kPi / 0.4 / 0.5, 2);
    for (int nx : {19, 38}) {
        SimParams P;
        P.nx = nx;
        auto t0 = std::chrono::steady_clock::now();
        auto res = run_batch(c, jobs, omegas_band(), P, 2);
        double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        double sum = 0;
        for (const auto& s : res) {
            int nv = 0;
            for (const auto& f : s.freqs) nv += f.valid;
            std::printf("timing nx=%d |k|=%.1f: %d valid freqs, %d steps (%.0f um/c), wall %.1f s, cpu %.1f s, "
                        "converged=%d\n", nx, std::hypot(s.kx, s.ky), nv, s.stats.steps, s.stats.sim_time,
                        s.stats.wall_seconds, s.stats.cpu_seconds, int(s.stats.converged));
            sum += s.stats.cpu_seconds;
            for (const auto& f : s.freqs)
                if (f.valid) {
                    CHECK(std::isfinite(f.R[0]));
                    CHECK(f.R[0] <= 1.0 + 1e-3);
                    CHECK(f.R[1] <= 1.0 + 1e-3);
                }
        }
        std::printf("timing nx=%d: batch wall %.1f s on 2 threads, mean cpu %.2f s per run; estimated table "
                    "(%.0f runs) = %.1f min on 2 dedicated cores\n", nx, wall, sum / res.size(), nruns,
                    nruns * sum / res.size() / 2 / 60);
        CHECK(wall > 0);
    }
}
