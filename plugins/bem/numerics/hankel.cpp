// plumage — 2.5D BEM numerics: Bessel/Hankel functions of order 0 and 1 for complex argument.
// See hankel.hpp for the methods and NOTES.md for measured accuracy and speed.

#include "hankel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace plumage::bem {

namespace {

constexpr double kInvPi = 0.318309886183790671537767526745028724;
constexpr double kTwoOverPi = 0.636619772367581343075535053490057448;
constexpr double kInvSqrtPi = 0.564189583547756286948079451560772586;
constexpr double kInv2Pi = 0.159154943091895335768883763372514362;

// Region boundaries.
constexpr double kSeriesBound = 5.0;  // series if |z| + |Im z| <= kSeriesBound
constexpr double kTab1R = 10.0;       // fine table for |z| < kTab1R
constexpr double kTab2R = 20.0;       // coarse table for |z| < kTab2R, asymptotic beyond
constexpr double kTab1H = 0.5;        // cell sides
constexpr double kTab2H = 1.0;
constexpr int kNT = 18;  // Taylor terms per cell

// ---------------------------------------------------------------------------------------------
// Small complex helpers (std::complex operator* goes through __muldc3 without -ffast-math).
struct C {
    double re, im;
};
inline C mul(C a, C b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
inline C add(C a, C b) { return {a.re + b.re, a.im + b.im}; }
inline C fma_c(C acc, C t, C c) {  // acc * t + c
    return {acc.re * t.re - acc.im * t.im + c.re, acc.re * t.im + acc.im * t.re + c.im};
}
inline C scale(C a, double s) { return {a.re * s, a.im * s}; }
inline C inv(C a) {
    const double d = 1.0 / (a.re * a.re + a.im * a.im);
    return {a.re * d, -a.im * d};
}
inline C of(cplx z) { return {z.real(), z.imag()}; }
inline cplx to(C z) { return {z.re, z.im}; }

// sin and cos of a double, |x| <= 1e5 via Cody-Waite reduction and the fdlibm kernels
// (max error ~1 ulp, checked in the tests against std::sin/std::cos); libm beyond.
inline void fast_sincos(double x, double& s, double& c) {
    if (!(std::fabs(x) <= 1e5)) {
        s = std::sin(x);
        c = std::cos(x);
        return;
    }
    constexpr double kTwoOverPiD = 6.36619772367581382433e-01;
    constexpr double pio2_1 = 1.57079632673412561417e+00;   // first 33 bits of pi/2
    constexpr double pio2_2 = 6.07710050630396597660e-11;   // next 33 bits
    constexpr double pio2_3 = 2.02226624871116645580e-21;   // next 33 bits
    const double k = std::nearbyint(x * kTwoOverPiD);
    const double r = ((x - k * pio2_1) - k * pio2_2) - k * pio2_3;
    const double z = r * r;
    constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                     S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                     S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
    constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                     C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                     C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
    const double sp = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    const double sr = r + r * z * (S1 + z * sp);
    const double cp = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    const double hz = 0.5 * z;
    const double w = 1.0 - hz;
    const double cr = w + (((1.0 - w) - hz) + z * cp);
    const long q = static_cast<long>(k) & 3;
    switch (q) {
        case 0: s = sr; c = cr; break;
        case 1: s = cr; c = -sr; break;
        case 2: s = -sr; c = -cr; break;
        default: s = -cr; c = sr; break;
    }
}

// E(z) = sqrt(2/(pi z)) e^{i(z - pi/4)} for Re z >= 0, z != 0, given r = |z|; also returns 1/z.
// One division: with s = sqrt((r + x)/2) (> 0 for Re z >= 0), sqrt(z) = s + i y/(2s),
// 1/sqrt(z) = (s^2 - i y/2)/(r s), 1/r = s/(r s), 1/z = conj(z)/r^2.
inline C hankel_prefactor(C z, double r, C* invz) {
    const double s2 = 0.5 * (r + z.re);
    const double s = std::sqrt(s2);
    const double d = 1.0 / (r * s);
    const C isq = {s2 * d, -0.5 * z.im * d};
    const double ir = s * d;
    const double ir2 = ir * ir;
    *invz = {z.re * ir2, -z.im * ir2};
    const double ey = std::exp(-z.im);
    double sx, cx;
    fast_sincos(z.re, sx, cx);
    // (1 - i)/sqrt(pi) * isq * e^{-y} (cos x + i sin x)
    C e = {ey * cx, ey * sx};
    e = mul(e, isq);
    return {kInvSqrtPi * (e.re + e.im), kInvSqrtPi * (e.im - e.re)};
}

// ---------------------------------------------------------------------------------------------
// Ascending series.
constexpr int kSerMax = 34;
struct SeriesCoefs {
    std::array<double, kSerMax> j0{}, s0{}, j1{}, s1{};
    std::array<double, kSerMax> tmax{};  // use K terms if |t| <= tmax[K]
    SeriesCoefs() {
        double fact = 1.0;  // k!
        double harm = 0.0;  // H_k
        for (int k = 0; k < kSerMax; ++k) {
            if (k > 0) {
                fact *= k;
                harm += 1.0 / k;
            }
            const double sgn = (k % 2 == 0) ? 1.0 : -1.0;
            const double f2 = fact * fact;
            const double ff1 = fact * fact * (k + 1);  // k!(k+1)!
            j0[k] = sgn / f2;
            s0[k] = -sgn * harm / f2;  // (-1)^{k+1} H_k/(k!)^2
            j1[k] = sgn / ff1;
            s1[k] = sgn * (2.0 * harm + 1.0 / (k + 1)) / ff1;  // (H_k + H_{k+1})(-1)^k/(k!(k+1)!)
        }
        // Truncation: first omitted term |t|^K/(K!)^2 <= 2^-62 (relative to the O(1)..O(e^|z|) scale).
        double lf = 0.0;  // ln K!
        for (int K = 1; K < kSerMax; ++K) {
            lf += std::log(static_cast<double>(K));
            tmax[K] = std::exp((2.0 * lf - 62.0 * std::log(2.0)) / K);
        }
        tmax[0] = 0.0;
    }
};
const SeriesCoefs& series_coefs() {
    static const SeriesCoefs c;
    return c;
}

struct SeriesParts {
    C j0, j1;      // J0, J1
    C omj0;        // 1 - J0
    C ps0;         // sum_{k>=1} (-1)^{k+1} H_k t^k/(k!)^2
    C ps1;         // sum_k (H_k + H_{k+1}) (-t)^k/(k!(k+1)!)
};

inline SeriesParts series_parts(C z) {
    const SeriesCoefs& sc = series_coefs();
    const C t = scale(mul(z, z), 0.25);
    const double at = std::sqrt(t.re * t.re + t.im * t.im);
    int K = 2;
    while (K < kSerMax - 1 && at > sc.tmax[K]) ++K;
    // Horner in t.
    C pj0 = {sc.j0[K - 1], 0.0}, pj1 = {sc.j1[K - 1], 0.0}, ps0 = {sc.s0[K - 1], 0.0},
      ps1 = {sc.s1[K - 1], 0.0};
    for (int k = K - 2; k >= 1; --k) {
        pj0 = fma_c(pj0, t, {sc.j0[k], 0.0});
        pj1 = fma_c(pj1, t, {sc.j1[k], 0.0});
        ps0 = fma_c(ps0, t, {sc.s0[k], 0.0});
        ps1 = fma_c(ps1, t, {sc.s1[k], 0.0});
    }
    SeriesParts p;
    // here pj0 = sum_{k>=1} j0[k] t^{k-1}; ps0 likewise (s0[0] = 0)
    p.omj0 = scale(mul(pj0, t), -1.0);
    p.j0 = {1.0 - p.omj0.re, -p.omj0.im};
    p.ps0 = mul(ps0, t);
    pj1 = fma_c(pj1, t, {sc.j1[0], 0.0});
    ps1 = fma_c(ps1, t, {sc.s1[0], 0.0});
    const C zh = scale(z, 0.5);
    p.j1 = mul(zh, pj1);
    p.ps1 = mul(zh, ps1);  // includes the z/2 factor
    return p;
}

inline C log_half(C z) {  // ln(z/2), principal branch
    return {std::log(0.5 * std::sqrt(z.re * z.re + z.im * z.im)), std::atan2(z.im, z.re)};
}

// ---------------------------------------------------------------------------------------------
// Asymptotic series.
constexpr int kAsyMax = 40;
struct AsyCoefs {
    std::array<C, kAsyMax> c0{}, c1{};  // i^k a_k(nu)
    std::array<double, kAsyMax> rmin{};  // use N terms (0..N-1) if |z| >= rmin[N]
    AsyCoefs() {
        double a0 = 1.0, a1 = 1.0;
        C ik = {1.0, 0.0};
        for (int k = 0; k < kAsyMax; ++k) {
            c0[k] = scale(ik, a0);
            c1[k] = scale(ik, a1);
            const double b = std::max(std::fabs(a0), std::fabs(a1));
            rmin[k] = (k == 0) ? 1e300 : std::pow(b / 2e-17, 1.0 / k);
            ik = mul(ik, {0.0, 1.0});
            const double q = (2.0 * k + 1.0) * (2.0 * k + 1.0);
            a0 *= (0.0 - q) / (8.0 * (k + 1));
            a1 *= (4.0 - q) / (8.0 * (k + 1));
        }
    }
};
const AsyCoefs& asy_coefs() {
    static const AsyCoefs c;
    return c;
}

inline H01 hankel_asymptotic(C z, double r) {
    const AsyCoefs& ac = asy_coefs();
    int N = 2;
    while (N < kAsyMax - 1 && r < ac.rmin[N]) ++N;
    C w;
    const C e = hankel_prefactor(z, r, &w);
    C p0 = ac.c0[N - 1], p1 = ac.c1[N - 1];
    for (int k = N - 2; k >= 0; --k) {
        p0 = fma_c(p0, w, ac.c0[k]);
        p1 = fma_c(p1, w, ac.c1[k]);
    }
    const C h0 = mul(e, p0);
    const C h1m = mul(e, p1);  // H1 = -i e p1
    return {to(h0), cplx(h1m.im, -h1m.re)};
}

// ---------------------------------------------------------------------------------------------
// Taylor tables of P0(z) = H0(z) / (sqrt(2/(pi z)) e^{i(z - pi/4)}).
using LC = std::complex<long double>;

struct Level {
    double h = 0.0, ylo = 0.0, rmax = 0.0;
    int nx = 0, ny = 0;
    std::vector<C> coef;  // (iy * nx + ix) * kNT + k
    std::vector<char> needed;
    bool need(int ix, int iy) const { return needed[static_cast<size_t>(iy) * nx + ix] != 0; }
    double xc(int ix) const { return (ix + 0.5) * h; }
    double yc(int iy) const { return ylo + (iy + 0.5) * h; }
};

struct Tables {
    Level l1, l2;
    Tables();
};

// Taylor coefficients p[0..M-1] of P0 about zc given P0(zc), P0'(zc):
//   P'' + 2i P' - mu P / z^2 = 0,  mu = -1/4.
void taylor_coefs(LC zc, LC p0, LC p1, int M, LC* p) {
    const long double mu = -0.25L;
    const LC iz2 = 1.0L / (zc * zc);
    const LC two_zc = 2.0L * zc;
    p[0] = p0;
    p[1] = p1;
    LC qm1 = 0.0L, qm2 = 0.0L;
    for (int k = 0; k + 2 < M; ++k) {
        const LC qk = (mu * p[k] - two_zc * qm1 - qm2) * iz2;
        p[k + 2] = (qk - LC(0.0L, 2.0L * (k + 1)) * p[k + 1]) / (static_cast<long double>(k + 2) * (k + 1));
        qm2 = qm1;
        qm1 = qk;
    }
}

void taylor_step(LC& z, LC& P, LC& dP, LC dz) {
    constexpr int M = 40;
    LC p[M];
    taylor_coefs(z, P, dP, M, p);
    LC s = p[M - 1], ds = 0.0L;
    for (int k = M - 2; k >= 0; --k) {
        ds = ds * dz + s;
        s = s * dz + p[k];
    }
    P = s;
    dP = ds;
    z += dz;
}

long double dist_origin_segment(LC a, LC b) {
    const LC d = b - a;
    const long double dd = std::norm(d);
    long double t = dd > 0 ? -(a.real() * d.real() + a.imag() * d.imag()) / dd : 0.0L;
    t = std::clamp(t, 0.0L, 1.0L);
    return std::abs(a + t * d);
}

void march(LC& z, LC& P, LC& dP, LC target) {
    const LC d = target - z;
    const long double len = std::abs(d);
    if (len == 0.0L) return;
    const long double smax = std::min(0.5L, 0.125L * dist_origin_segment(z, target));
    const int n = static_cast<int>(std::ceil(len / smax));
    const LC dz = d / static_cast<long double>(n);
    for (int i = 0; i < n; ++i) taylor_step(z, P, dP, dz);
    z = target;
}

void asym_start(LC z, LC& P, LC& dP) {
    const LC w = 1.0L / z;
    LC wk = 1.0L, ik = 1.0L;
    long double a = 1.0L;
    P = 0.0L;
    dP = 0.0L;
    for (int k = 0; k < 200; ++k) {
        const LC t = ik * a * wk;
        P += t;
        dP += -static_cast<long double>(k) * t * w;
        if (k > 4 && std::abs(t) < 1e-24L) break;
        const long double q = (2.0L * k + 1.0L) * (2.0L * k + 1.0L);
        a *= -q / (8.0L * (k + 1));
        wk *= w;
        ik *= LC(0.0L, 1.0L);
    }
}

bool in_series(double x, double y) { return std::hypot(x, y) + std::fabs(y) <= kSeriesBound; }

void init_level(Level& L, double h, double rmax, double rmin_level) {
    L.h = h;
    L.rmax = rmax;
    L.ylo = -rmax;
    L.nx = static_cast<int>(std::lround(rmax / h));
    L.ny = 2 * L.nx;
    L.coef.assign(static_cast<size_t>(L.nx) * L.ny * kNT, C{0.0, 0.0});
    L.needed.assign(static_cast<size_t>(L.nx) * L.ny, 0);
    for (int iy = 0; iy < L.ny; ++iy) {
        for (int ix = 0; ix < L.nx; ++ix) {
            const double x0 = ix * h, x1 = x0 + h, y0 = L.ylo + iy * h, y1 = y0 + h;
            // nearest point of the cell to the origin, farthest corner
            const double nxp = std::clamp(0.0, x0, x1), nyp = std::clamp(0.0, y0, y1);
            const double rnear = std::hypot(nxp, nyp);
            bool all_series = in_series(x0, y0) && in_series(x1, y0) && in_series(x0, y1) && in_series(x1, y1);
            double rfar = 0.0;
            for (double cx : {x0, x1})
                for (double cy : {y0, y1}) rfar = std::max(rfar, std::hypot(cx, cy));
            const bool used = !all_series && rnear < rmax && rfar >= rmin_level;
            L.needed[static_cast<size_t>(iy) * L.nx + ix] = used ? 1 : 0;
        }
    }
}

void store(Level& L, int ix, int iy, LC P, LC dP) {
    LC p[kNT];
    const LC zc(L.xc(ix), L.yc(iy));
    taylor_coefs(zc, P, dP, kNT, p);
    C* dst = &L.coef[(static_cast<size_t>(iy) * L.nx + ix) * kNT];
    for (int k = 0; k < kNT; ++k)
        dst[k] = {static_cast<double>(p[k].real()), static_cast<double>(p[k].imag())};
}

Tables::Tables() {
    init_level(l1, kTab1H, kTab1R, 0.0);
    init_level(l2, kTab2H, kTab2R, kTab1R);
    constexpr double X0 = 6.0, YTOP = 40.0;
    Level* levels[2] = {&l1, &l2};

    // (a) column x = X0: values at every row centre that has a needed cell left of X0.
    struct RowStart {
        int lev, iy;
        double y;
    };
    std::vector<RowStart> rows;
    for (int l = 0; l < 2; ++l) {
        const Level& L = *levels[l];
        for (int iy = 0; iy < L.ny; ++iy) {
            bool any = false;
            for (int ix = 0; ix < L.nx && L.xc(ix) < X0; ++ix) any = any || L.need(ix, iy);
            if (any) rows.push_back({l, iy, L.yc(iy)});
        }
    }
    std::sort(rows.begin(), rows.end(), [](const RowStart& a, const RowStart& b) { return a.y > b.y; });
    {
        LC z(X0, YTOP), P, dP;
        asym_start(z, P, dP);
        for (const RowStart& rs : rows) {
            march(z, P, dP, LC(X0, rs.y));
            Level& L = *levels[rs.lev];
            // (b) march left along the row.
            int ixmin = -1;
            for (int ix = 0; ix < L.nx && L.xc(ix) < X0; ++ix)
                if (L.need(ix, rs.iy)) {
                    ixmin = ix;
                    break;
                }
            LC zr = z, Pr = P, dPr = dP;
            for (int ix = L.nx - 1; ix >= ixmin; --ix) {
                if (L.xc(ix) >= X0) continue;
                march(zr, Pr, dPr, LC(L.xc(ix), rs.y));
                if (L.need(ix, rs.iy)) store(L, ix, rs.iy, Pr, dPr);
            }
        }
    }
    // (c) columns x_c >= X0: march down from Im z = YTOP.
    for (int l = 0; l < 2; ++l) {
        Level& L = *levels[l];
        for (int ix = 0; ix < L.nx; ++ix) {
            if (L.xc(ix) < X0) continue;
            int iylo = -1;
            for (int iy = 0; iy < L.ny; ++iy)
                if (L.need(ix, iy)) {
                    iylo = iy;
                    break;
                }
            if (iylo < 0) continue;
            LC z(L.xc(ix), YTOP), P, dP;
            asym_start(z, P, dP);
            for (int iy = L.ny - 1; iy >= iylo; --iy) {
                march(z, P, dP, LC(L.xc(ix), L.yc(iy)));
                if (L.need(ix, iy)) store(L, ix, iy, P, dP);
            }
        }
    }
}

const Tables& tables() {
    static const Tables t;
    return t;
}

inline H01 hankel_table(const Level& L, C z, double r) {
    int ix = static_cast<int>(z.re / L.h);
    int iy = static_cast<int>((z.im - L.ylo) / L.h);
    ix = std::clamp(ix, 0, L.nx - 1);
    iy = std::clamp(iy, 0, L.ny - 1);
    const C* c = &L.coef[(static_cast<size_t>(iy) * L.nx + ix) * kNT];
    const C t = {z.re - (ix + 0.5) * L.h, z.im - (L.ylo + (iy + 0.5) * L.h)};
    C p = c[kNT - 1], dp = {0.0, 0.0};
    for (int k = kNT - 2; k >= 0; --k) {
        dp = fma_c(dp, t, p);
        p = fma_c(p, t, c[k]);
    }
    C iz;
    const C e = hankel_prefactor(z, r, &iz);
    // H1 = -e [ (i - 1/(2z)) P + P' ]
    const C f = {-0.5 * iz.re, 1.0 - 0.5 * iz.im};
    const C q = add(mul(f, p), dp);
    const C h1 = mul(e, q);
    return {to(mul(e, p)), cplx(-h1.re, -h1.im)};
}

inline JY01 jy_series(C z) {
    const SeriesParts sp = series_parts(z);
    const C L = add(log_half(z), {kEulerGamma, 0.0});
    JY01 r;
    r.j0 = to(sp.j0);
    r.j1 = to(sp.j1);
    const C y0 = scale(add(mul(L, sp.j0), sp.ps0), kTwoOverPi);
    const C iz = inv(z);
    C y1 = scale(mul(L, sp.j1), kTwoOverPi);
    y1 = add(y1, scale(sp.ps1, -kInvPi));
    y1 = add(y1, scale(iz, -kTwoOverPi));
    r.y0 = to(y0);
    r.y1 = to(y1);
    return r;
}

enum Region { kSeries = 0, kTable1 = 1, kTable2 = 2, kAsym = 3 };

inline Region region_of(double y, double r) {
    if (r + std::fabs(y) <= kSeriesBound) return kSeries;
    if (r < kTab1R) return kTable1;
    if (r < kTab2R) return kTable2;
    return kAsym;
}

inline H01 hankel_nonseries(Region reg, C z, double r) {
    if (reg == kAsym) return hankel_asymptotic(z, r);
    const Tables& T = tables();
    return hankel_table(reg == kTable1 ? T.l1 : T.l2, z, r);
}

}  // namespace

H01 hankel1_01(cplx zz) {
    const C z = of(zz);
    const double r = std::sqrt(z.re * z.re + z.im * z.im);
    const Region reg = region_of(z.im, r);
    if (reg == kSeries) {
        const JY01 jy = jy_series(z);
        return {jy.j0 + cplx(-jy.y0.imag(), jy.y0.real()), jy.j1 + cplx(-jy.y1.imag(), jy.y1.real())};
    }
    return hankel_nonseries(reg, z, r);
}

JY01 bessel_jy01(cplx zz) {
    const C z = of(zz);
    const double r = std::sqrt(z.re * z.re + z.im * z.im);
    const Region reg = region_of(z.im, r);
    if (reg == kSeries) return jy_series(z);
    const H01 a = hankel_nonseries(reg, z, r);                  // H^(1)(z)
    const H01 b = hankel_nonseries(reg, {z.re, -z.im}, r);      // H^(1)(conj z)
    const cplx h20 = std::conj(b.h0), h21 = std::conj(b.h1);    // H^(2)(z)
    JY01 o;
    o.j0 = 0.5 * (a.h0 + h20);
    o.j1 = 0.5 * (a.h1 + h21);
    o.y0 = cplx(0.0, -0.5) * (a.h0 - h20);
    o.y1 = cplx(0.0, -0.5) * (a.h1 - h21);
    return o;
}

cplx hankel1_1_reg(cplx zz) {
    const C z = of(zz);
    const double r = std::sqrt(z.re * z.re + z.im * z.im);
    if (r == 0.0) return {0.0, 0.0};
    const Region reg = region_of(z.im, r);
    if (reg == kSeries) {
        // J1 + i [ (2/pi) L J1 - (1/pi) ps1 ]
        const SeriesParts sp = series_parts(z);
        const C L = add(log_half(z), {kEulerGamma, 0.0});
        const C y1r = add(scale(mul(L, sp.j1), kTwoOverPi), scale(sp.ps1, -kInvPi));
        return {sp.j1.re - y1r.im, sp.j1.im + y1r.re};
    }
    const H01 h = hankel_nonseries(reg, z, r);
    const C iz = inv(z);
    return h.h1 + cplx(-kTwoOverPi * iz.im, kTwoOverPi * iz.re);
}

GreenReg green2d_reg_both(cplx gamma, double R) {
    const C g = of(gamma);
    const C z = scale(g, R);
    const double r = std::sqrt(z.re * z.re + z.im * z.im);
    const Region reg = region_of(z.im, r);
    GreenReg out;
    if (reg == kSeries) {
        const SeriesParts sp = series_parts(z);
        // G_reg = (i/4) J0 - (ln(gamma/2) + C_E) J0/(2pi) - ps0/(2pi) + ln R (1 - J0)/(2pi)
        const C Lg = add(log_half(g), {kEulerGamma, 0.0});
        C v = {-0.25 * sp.j0.im, 0.25 * sp.j0.re};
        v = add(v, scale(add(mul(Lg, sp.j0), sp.ps0), -kInv2Pi));
        if (R > 0.0) v = add(v, scale(sp.omj0, std::log(R) * kInv2Pi));
        out.g = to(v);
        if (R > 0.0) {
            const C L = add(log_half(z), {kEulerGamma, 0.0});
            const C y1r = add(scale(mul(L, sp.j1), kTwoOverPi), scale(sp.ps1, -kInvPi));
            const C h1r = {sp.j1.re - y1r.im, sp.j1.im + y1r.re};
            const C m = mul(g, h1r);  // -(i/4) gamma h1r
            out.dg = {0.25 * m.im, -0.25 * m.re};
        } else {
            out.dg = {0.0, 0.0};
        }
        return out;
    }
    const H01 h = hankel_nonseries(reg, z, r);
    out.g = cplx(-0.25 * h.h0.imag(), 0.25 * h.h0.real()) + std::log(R) * kInv2Pi;
    const C iz = inv(z);
    const cplx h1r = h.h1 + cplx(-kTwoOverPi * iz.im, kTwoOverPi * iz.re);
    const C m = mul(g, of(h1r));
    out.dg = {0.25 * m.im, -0.25 * m.re};
    return out;
}

cplx green2d_reg(cplx gamma, double R) { return green2d_reg_both(gamma, R).g; }
cplx green2d_reg_deriv(cplx gamma, double R) { return green2d_reg_both(gamma, R).dg; }

Green green2d(cplx gamma, double R) {
    const H01 h = hankel1_01(gamma * R);
    const C m = mul(of(gamma), of(h.h1));
    return {cplx(-0.25 * h.h0.imag(), 0.25 * h.h0.real()), cplx(0.25 * m.im, -0.25 * m.re)};
}

namespace detail {
int hankel_region(cplx z) {
    const double r = std::abs(z);
    return static_cast<int>(region_of(z.imag(), r));
}
void hankel_init() { (void)tables(); }
void fast_sincos(double x, double& s, double& c) { plumage::bem::fast_sincos(x, s, c); }
}  // namespace detail

}  // namespace plumage::bem
