// Tests of plugins/bem/numerics/hankel: Arb reference on dense grids, Wronskian, regularised kernels,
// and the 2.5D Green's function identity of spec wave-simulation.md §6.11 item 5.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "numerics/hankel.hpp"

using plumage::bem::cplx;
namespace bem = plumage::bem;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

#ifdef PLUMAGE_BEM_HAVE_ARB
#include "arb_ref.hpp"
using plumage::bem::testing::arb_bessel;

namespace {

struct MaxErr {
    double h = 0.0, jy = 0.0;
    cplx zh{}, zjy{};
    int n = 0;
};

// Checks H0, H1 (relative) and J0, J1, Y0, Y1 (relative to max(|J|,|Y|) of that order, i.e. an
// absolute error near the real zeros) at z against Arb; records maxima per region.
void check_point(cplx z, MaxErr* regions, double tol_h, double tol_jy) {
    const bem::H01 h = bem::hankel1_01(z);
    const bem::JY01 jy = bem::bessel_jy01(z);
    const auto r0 = arb_bessel(0, z);
    const auto r1 = arb_bessel(1, z);
    const int reg = bem::detail::hankel_region(z);
    MaxErr& m = regions[reg];
    ++m.n;
    if (std::abs(r0.h) > 1e-280 && std::abs(r1.h) > 1e-280) {  // skip underflow (|H| ~ e^{-Im z})
        const double e = std::max(std::abs(h.h0 - r0.h) / std::abs(r0.h), std::abs(h.h1 - r1.h) / std::abs(r1.h));
        if (e > m.h) {
            m.h = e;
            m.zh = z;
        }
        INFO("z = " << z.real() << " + " << z.imag() << "i, region " << reg);
        REQUIRE(e <= tol_h);
    }
    const double env0 = std::max(std::abs(r0.j), std::abs(r0.y)), env1 = std::max(std::abs(r1.j), std::abs(r1.y));
    if (env0 < 1e280 && env1 < 1e280) {
        const double e = std::max({std::abs(jy.j0 - r0.j) / env0, std::abs(jy.y0 - r0.y) / env0,
                                   std::abs(jy.j1 - r1.j) / env1, std::abs(jy.y1 - r1.y) / env1});
        if (e > m.jy) {
            m.jy = e;
            m.zjy = z;
        }
        INFO("z = " << z.real() << " + " << z.imag() << "i, region " << reg);
        REQUIRE(e <= tol_jy);
    }
}

void report(const char* title, const MaxErr* r) {
    const char* names[4] = {"series", "table<10", "table<20", "asymptotic"};
    std::printf("%s\n", title);
    for (int k = 0; k < 4; ++k)
        std::printf("  %-10s n=%5d  max rel err H0/H1 = %.2e at (%.4g, %.4g)   max err J,Y / max(|J|,|Y|) = %.2e\n",
                    names[k], r[k].n, r[k].h, r[k].zh.real(), r[k].zh.imag(), r[k].jy);
}
}  // namespace

TEST_CASE("H0, H1, J0, J1, Y0, Y1 against Arb: melanin band 0 <= Im z <= 0.3 Re z, 1e-8 <= |z| <= 3000",
          "[hankel][arb]") {
    MaxErr regions[4];
    const int nr = 700, na = 7;
    for (int i = 0; i < nr; ++i) {
        const double r = std::exp(std::log(1e-8) + (std::log(3000.0) - std::log(1e-8)) * (i + 0.5) / nr);
        for (int a = 0; a < na; ++a) {
            const double th = std::atan(0.3) * a / (na - 1);
            check_point(std::polar(r, th), regions, 1e-12, 1e-12);
        }
    }
    report("melanin band (arg z in [0, atan 0.3]):", regions);
}

TEST_CASE("Purely real z, dense grid including the zeros of J and Y", "[hankel][arb]") {
    MaxErr regions[4];
    // uniform in [0.01, 40] (zeros are dense there), log beyond
    for (int i = 0; i < 2000; ++i) check_point(cplx(0.01 + 40.0 * i / 2000.0 + 1e-3 * std::sin(i), 0.0), regions, 1e-12, 1e-12);
    for (int i = 0; i < 300; ++i) check_point(cplx(std::exp(std::log(40.0) + std::log(100.0) * i / 300.0), 0.0), regions, 1e-12, 1e-12);
    report("real axis:", regions);
}

TEST_CASE("Whole first and fourth quadrant, |z| <= 60 (robustness beyond the melanin band)", "[hankel][arb]") {
    MaxErr regions[4];
    for (int i = 0; i < 120; ++i) {
        const double r = std::exp(std::log(1e-3) + (std::log(60.0) - std::log(1e-3)) * (i + 0.5) / 120);
        for (int a = 0; a < 13; ++a) {
            const double th = -1.5 + 3.0 * a / 12;
            check_point(std::polar(r, th), regions, 1e-12, 1e-12);
        }
    }
    report("|arg z| <= 1.5, |z| <= 60:", regions);
}

#endif  // PLUMAGE_BEM_HAVE_ARB

TEST_CASE("Wronskian J1 Y0 - J0 Y1 = 2/(pi z)", "[hankel]") {
    double worst = 0.0;
    for (int i = 0; i < 400; ++i) {
        const double r = std::exp(std::log(1e-6) + (std::log(2500.0) - std::log(1e-6)) * (i + 0.5) / 400);
        for (int a = 0; a < 5; ++a) {
            const cplx z = std::polar(r, std::atan(0.3) * a / 4);
            if (z.imag() > 30) continue;  // J, Y ~ e^{Im z}: the cancellation would dominate
            const bem::JY01 f = bem::bessel_jy01(z);
            const cplx w = f.j1 * f.y0 - f.j0 * f.y1;
            const cplx ref = 2.0 / (kPi * z);
            const double scale = std::abs(f.j1 * f.y0) + std::abs(f.j0 * f.y1);
            const double err = std::abs(w - ref);
            worst = std::max(worst, err / scale);
            INFO("z = " << z);
            REQUIRE(err <= 1e-14 * scale + 1e-13 * std::abs(ref));
        }
    }
    std::printf("Wronskian: max |W - 2/(pi z)| / (|J1 Y0| + |J0 Y1|) = %.2e\n", worst);
}

#ifdef PLUMAGE_BEM_HAVE_ARB
namespace {
// Arb reference for the regularised kernels: (i/4)H0(gR) + ln R/(2pi) and -(i g/4)(H1(gR) + 2i/(pi g R)).
void arb_green_reg(cplx g, double R, cplx& G, cplx& dG) {
    acb_t ag, az, nu0, nu1, j, y, h, t, l;
    acb_init(ag); acb_init(az); acb_init(nu0); acb_init(nu1); acb_init(j); acb_init(y); acb_init(h); acb_init(t); acb_init(l);
    acb_set_d_d(ag, g.real(), g.imag());
    acb_set_si(nu0, 0);
    acb_set_si(nu1, 1);
    // J + iY cancels like e^{-2 Im z}: add ~2.9 Im(gR) bits
    const slong prec = 192 + static_cast<slong>(3.0 * std::fabs(g.imag() * R));
    acb_set_d(t, R);
    acb_mul(az, ag, t, prec);
    // G
    acb_hypgeom_bessel_jy(j, y, nu0, az, prec);
    acb_mul_onei(h, y);
    acb_add(h, h, j, prec);       // H0
    acb_mul_onei(h, h);
    acb_mul_2exp_si(h, h, -2);    // (i/4) H0
    acb_set_d(l, R);
    acb_log(l, l, prec);
    acb_const_pi(t, prec);
    acb_mul_2exp_si(t, t, 1);
    acb_div(l, l, t, prec);       // ln R / (2 pi)
    acb_add(h, h, l, prec);
    G = plumage::bem::testing::acb_to_cd(h);
    // dG
    acb_hypgeom_bessel_jy(j, y, nu1, az, prec);
    acb_mul_onei(h, y);
    acb_add(h, h, j, prec);       // H1
    acb_const_pi(t, prec);
    acb_mul(t, t, az, prec);
    acb_inv(t, t, prec);
    acb_mul_2exp_si(t, t, 1);     // 2/(pi z)
    acb_mul_onei(t, t);
    acb_add(h, h, t, prec);       // H1 + 2i/(pi z)
    acb_mul(h, h, ag, prec);
    acb_mul_onei(h, h);
    acb_neg(h, h);
    acb_mul_2exp_si(h, h, -2);    // -(i g/4)(...)
    dG = plumage::bem::testing::acb_to_cd(h);
    acb_clear(ag); acb_clear(az); acb_clear(nu0); acb_clear(nu1); acb_clear(j); acb_clear(y); acb_clear(h); acb_clear(t); acb_clear(l);
}
}  // namespace

TEST_CASE("Regularised kernels G_reg and dG_reg", "[hankel][arb]") {
    const double k0 = 2.0 * kPi / 0.4;
    const cplx ns[] = {cplx(1.0, 0.0), cplx(1.56, 0.0), cplx(1.8, 0.56), cplx(1.2, 0.3)};
    double worst_g = 0.0, worst_dg = 0.0;
    for (const cplx n : ns) {
        const double s = std::sin(0.7);
        cplx g = k0 * std::sqrt(n * n - s * s);
        if (g.imag() < 0) g = -g;
        // R = 0 closed form
        const cplx g0 = bem::green2d_reg(g, 0.0);
        const cplx ref0 = cplx(0.0, 0.25) - (std::log(g / 2.0) + bem::kEulerGamma) / (2.0 * kPi);
        REQUIRE(std::abs(g0 - ref0) <= 1e-15 * std::abs(ref0));
        REQUIRE(bem::green2d_reg_deriv(g, 0.0) == cplx(0.0, 0.0));
        for (int i = 0; i < 120; ++i) {
            const double R = std::exp(std::log(1e-12) + (std::log(40.0) - std::log(1e-12)) * (i + 0.5) / 120);
            cplx G, dG;
            arb_green_reg(g, R, G, dG);
            const bem::GreenReg v = bem::green2d_reg_both(g, R);
            // G_reg is O(1) (and may pass near zero for large R): absolute error relative to max(|G|, |(i/4)H0|, 1e-2)
            const double sg = std::max({std::abs(G), 0.25 * std::abs(bem::hankel1_0(g * R)), 1e-2});
            const double sdg = std::max(std::abs(dG), 0.25 * std::abs(g) * std::abs(bem::hankel1_1(g * R)));
            const double eg = std::abs(v.g - G) / sg, edg = std::abs(v.dg - dG) / sdg;
            worst_g = std::max(worst_g, eg);
            worst_dg = std::max(worst_dg, edg);
            INFO("n = " << n << " R = " << R);
            REQUIRE(eg <= 1e-12);
            REQUIRE(edg <= 1e-12);
            // consistency with the split G = -ln R/(2 pi) + G_reg
            const bem::Green full = bem::green2d(g, R);
            if (R > 1e-3) {
                // (the split cancels when |G| << |ln R|/(2 pi): compare on the scale of the terms)
                REQUIRE(std::abs(full.g - (v.g - std::log(R) / (2 * kPi))) <=
                        1e-13 * (std::abs(full.g) + std::abs(std::log(R)) / (2 * kPi)));
                REQUIRE(std::abs(full.dg - (v.dg - 1.0 / (2 * kPi * R))) <= 1e-13 * (std::abs(full.dg) + 1.0 / (2 * kPi * R)));
            }
        }
        // hankel1_1_reg(z) = H1 + 2i/(pi z) -> 0 like z ln z
        const cplx zt = g * 1e-9;
        REQUIRE(std::abs(bem::hankel1_1_reg(zt)) < 1e-6);
    }
    std::printf("regularised kernels: max err G_reg %.2e, dG_reg %.2e (R in [1e-12, 40] um, lambda 0.4 um)\n", worst_g,
                worst_dg);
}

#endif  // PLUMAGE_BEM_HAVE_ARB

namespace {
// 2.5D Green's function by direct quadrature: int e^{ikR}/(4 pi R) e^{i beta u} du, R = sqrt(rho^2 + u^2),
// with u = rho sinh t:  (1/4pi) int e^{i rho (k cosh t + beta sinh t)} dt.  Im k > 0 makes it decay
// like exp(-Im k rho cosh t).  Composite 16-point Gauss-Legendre with panels short in phase.
cplx green_by_quadrature(cplx k, double beta, double rho) {
    static const double xg[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                 0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
    static const double wg[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                 0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
    // truncation: Im k rho cosh T = 40
    const double T = std::acosh(std::max(1.0, 40.0 / (k.imag() * rho)));
    cplx sum = 0.0;
    double t0 = -T;
    while (t0 < T) {
        // phase rate ~ rho (|k| sinh|t| + |beta| cosh t); keep <= 1.5 rad per panel
        const double ta = std::fabs(t0) > std::fabs(std::min(T, t0 + 1.0)) ? std::fabs(t0) : std::fabs(std::min(T, t0 + 1.0));
        const double rate = rho * (std::abs(k) * std::sinh(ta) + std::fabs(beta) * std::cosh(ta)) + 1.0;
        const double h = std::min({1.5 / rate, 0.25, T - t0});
        const double c = t0 + 0.5 * h, hw = 0.5 * h;
        for (int q = 0; q < 8; ++q) {
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                const double t = c + sgn * hw * xg[q];
                sum += hw * wg[q] * std::exp(cplx(0.0, 1.0) * rho * (k * std::cosh(t) + beta * std::sinh(t)));
            }
        }
        t0 += h;
    }
    return sum / (4.0 * kPi);
}
}  // namespace

TEST_CASE("2.5D Green's function identity (spec 6.11 item 5), complex k", "[hankel][green]") {
    const double k0 = 2.0 * kPi / 0.5;
    const cplx ns[] = {cplx(1.8, 0.1), cplx(1.56, 0.05), cplx(1.0, 0.08), cplx(1.7, 0.5)};
    const double thetas[] = {0.0, 0.4, 1.2};
    const double rhos[] = {0.02, 0.3, 1.5};
    double worst = 0.0;
    for (const cplx n : ns)
        for (const double th : thetas)
            for (const double rho : rhos) {
                const cplx k = k0 * n;
                const double beta = -k0 * std::sin(th);
                cplx g = std::sqrt(k * k - beta * beta);
                if (g.imag() < 0) g = -g;
                const cplx ref = cplx(0.0, 0.25) * bem::hankel1_0(g * rho);
                const cplx num = green_by_quadrature(k, beta, rho);
                const double e = std::abs(num - ref) / std::abs(ref);
                worst = std::max(worst, e);
                INFO("n = " << n << " theta = " << th << " rho = " << rho);
                REQUIRE(e <= 1e-10);
            }
    std::printf("Green's function identity: max rel. difference %.2e\n", worst);
}

TEST_CASE("internal sin/cos", "[hankel]") {
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const double x = (i % 2 ? 10.0 : 1e5) * std::sin(1.2345 * i) * (i % 3 ? 1.0 : -1.0);
        double s, c;
        bem::detail::fast_sincos(x, s, c);
        const long double ls = sinl(static_cast<long double>(x)), lc = cosl(static_cast<long double>(x));
        worst = std::max({worst, static_cast<double>(fabsl(s - ls)), static_cast<double>(fabsl(c - lc))});
    }
    REQUIRE(worst <= 2.5e-16);
}
