// plumage — exact series solutions for infinite circular cylinders (the BEM's reference). See the header.

#include "cylinder_series.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "numerics/hankel.hpp"

namespace plumage::oracle {

namespace {
constexpr double kPi = 3.14159265358979323846264338327950288;
const cplx kI(0.0, 1.0);

cplx ipow(int n) {  // i^n
    switch (((n % 4) + 4) % 4) {
        case 0: return {1.0, 0.0};
        case 1: return {0.0, 1.0};
        case 2: return {-1.0, 0.0};
        default: return {0.0, -1.0};
    }
}

// Values and derivatives of a Bessel-type family at one argument, orders 0..nmax.
struct Family {
    std::vector<cplx> f, fp;
};
enum class Kind { J, Y, H };

Family family(Kind k, cplx z, int nmax) {
    Family F;
    std::vector<cplx> v;
    switch (k) {
        case Kind::J: bessel_j_orders(z, nmax + 1, v); break;
        case Kind::Y: bessel_y_orders(z, nmax + 1, v); break;
        case Kind::H: hankel1_orders(z, nmax + 1, v); break;
    }
    F.f.assign(v.begin(), v.begin() + nmax + 1);
    F.fp.resize(nmax + 1);
    F.fp[0] = -v[1];
    for (int n = 1; n <= nmax; ++n) F.fp[n] = v[n - 1] - (static_cast<double>(n) / z) * v[n];
    return F;
}

// Order n (may be negative) value/derivative: C_{-n} = (-1)^n C_n for J, Y, H.
inline cplx val(const Family& F, int n) { return (n < 0 && (n % 2)) ? -F.f[-n] : F.f[std::abs(n)]; }
inline cplx der(const Family& F, int n) { return (n < 0 && (n % 2)) ? -F.fp[-n] : F.fp[std::abs(n)]; }

void finish(CylinderSolution& s) {
    const int N = s.nmax;
    // scattered axial-field coefficients (inverse of the co/cross mapping of solve_layered)
    const double ct = std::cos(s.theta_i);
    s.ez.assign(2 * N + 1, 0.0);
    s.hz.assign(2 * N + 1, 0.0);
    for (int n = -N; n <= N; ++n) {
        const cplx t1 = (s.pol == 1) ? s.co[n + N] : s.cr[n + N];  // along e1_o
        const cplx t2 = (s.pol == 1) ? s.cr[n + N] : s.co[n + N];  // along e2_o
        s.ez[n + N] = -t1 * ipow(n) * ct;
        s.hz[n + N] = t2 * ipow(n) * ct;
    }
    double sca = 0.0;
    cplx fwd = 0.0;
    for (int n = -N; n <= N; ++n) {
        sca += std::norm(s.co[n + N]) + std::norm(s.cr[n + N]);
        fwd += s.co[n + N];
    }
    s.q_sca = 2.0 / s.x * sca;
    s.q_ext = 2.0 / s.x * fwd.real();
    s.q_abs = s.q_ext - s.q_sca;
}
}  // namespace

int default_nmax(double x) { return static_cast<int>(std::ceil(x + 4.0 * std::cbrt(x) + 10.0)); }

void bessel_j_orders(cplx z, int nmax, std::vector<cplx>& J) {
    J.assign(nmax + 1, 0.0);
    const plumage::bem::JY01 b = plumage::bem::bessel_jy01(z);
    J[0] = b.j0;
    if (nmax >= 1) J[1] = b.j1;
    if (nmax < 2) return;
    const double az = std::abs(z);
    const int M = std::max(nmax, static_cast<int>(std::ceil(az))) + 30 + static_cast<int>(std::ceil(6.0 * std::cbrt(az)));
    // ratios r_k = J_k / J_{k-1}, k = 1..nmax, by backward recurrence r_k = 1 / (2k/z - r_{k+1}).
    std::vector<cplx> r(nmax + 2, 0.0);
    cplx rk = 0.0;
    const cplx iz = 1.0 / z;
    for (int k = M; k >= 1; --k) {
        rk = 1.0 / (2.0 * k * iz - rk);
        if (k <= nmax) r[k] = rk;
    }
    if (std::abs(b.j0) >= std::abs(b.j1)) {
        cplx v = b.j0;
        for (int n = 1; n <= nmax; ++n) {
            v *= r[n];
            if (n >= 2) J[n] = v;
        }
    } else {
        cplx v = b.j1;
        for (int n = 2; n <= nmax; ++n) {
            v *= r[n];
            J[n] = v;
        }
    }
}

// Y_n = i (J_n - H_n^(1)).  (A plain forward recurrence for Y is unstable for complex z: Y ~ H^(2)/(2i)
// for n < |z| but ~ H^(1)/(2i)... for n > |z|, so the H^(1) part is lost to cancellation; J by backward
// and H^(1) by forward recurrence are both stable, and their difference does not cancel badly.)
void bessel_y_orders(cplx z, int nmax, std::vector<cplx>& Y) {
    std::vector<cplx> J, H;
    bessel_j_orders(z, nmax, J);
    hankel1_orders(z, nmax, H);
    Y.assign(nmax + 1, 0.0);
    const plumage::bem::JY01 b = plumage::bem::bessel_jy01(z);
    for (int n = 0; n <= nmax; ++n) Y[n] = cplx(0.0, 1.0) * (J[n] - H[n]);
    Y[0] = b.y0;
    if (nmax >= 1) Y[1] = b.y1;
}

void hankel1_orders(cplx z, int nmax, std::vector<cplx>& H) {
    H.assign(nmax + 1, 0.0);
    const plumage::bem::H01 b = plumage::bem::hankel1_01(z);
    H[0] = b.h0;
    if (nmax >= 1) H[1] = b.h1;
    const cplx iz = 1.0 / z;
    for (int n = 1; n < nmax; ++n) H[n + 1] = (2.0 * n) * iz * H[n] - H[n - 1];
}

double scattering_angle(double phi_o, double phi_i) {
    double a = std::remainder(phi_o - phi_i - kPi, 2.0 * kPi);
    if (a <= -kPi) a += 2.0 * kPi;
    return a;
}

cplx CylinderSolution::t_co(double Phi) const {
    cplx s = 0.0;
    for (int n = -nmax; n <= nmax; ++n) s += co[n + nmax] * std::polar(1.0, n * Phi);
    return s;
}
cplx CylinderSolution::t_cross(double Phi) const {
    cplx s = 0.0;
    for (int n = -nmax; n <= nmax; ++n) s += cr[n + nmax] * std::polar(1.0, n * Phi);
    return s;
}
double CylinderSolution::dq_sca_dphi(double Phi) const {
    return (std::norm(t_co(Phi)) + std::norm(t_cross(Phi))) / (kPi * x);
}

AxialFields scattered_axial_fields(const CylinderSolution& s, double rho_um, double Phi) {
    std::vector<cplx> H;
    hankel1_orders(cplx(s.gamma0 * rho_um, 0.0), s.nmax, H);
    AxialFields f{0.0, 0.0};
    for (int n = -s.nmax; n <= s.nmax; ++n) {
        const cplx hn = (n < 0 && (n % 2)) ? -H[-n] : H[std::abs(n)];
        const cplx e = std::polar(1.0, n * Phi);
        f.e_axis += s.ez[n + s.nmax] * hn * e;
        f.eta0_h_axis += s.hz[n + s.nmax] * hn * e;
    }
    return f;
}

Vec3c far_field_vector(const CylinderSolution& s, double phi_i, double phi_o) {
    const double Phi = scattering_angle(phi_o, phi_i);
    const cplx tc = s.t_co(Phi), tx = s.t_cross(Phi);
    const cplx t1 = (s.pol == 1) ? tc : tx, t2 = (s.pol == 1) ? tx : tc;
    const double st = std::sin(s.theta_i), ct = std::cos(s.theta_i);
    const double sp = std::sin(phi_o), cp = std::cos(phi_o);
    const cplx pre = std::sqrt(2.0 / (kPi * s.gamma0)) * std::polar(1.0, 0.75 * kPi);
    // e1_o = (sin t sin phi_o, cos t, sin t cos phi_o), e2_o = (-cos phi_o, 0, sin phi_o)
    return {pre * (t1 * (st * sp) - t2 * cp), pre * (t1 * ct), pre * (t1 * (st * cp) + t2 * sp)};
}

FarField far_field(const CylinderSolution& s, const std::vector<double>& Phi) {
    FarField f;
    f.t_co.reserve(Phi.size());
    f.t_cross.reserve(Phi.size());
    for (double p : Phi) {
        f.t_co.push_back(s.t_co(p));
        f.t_cross.push_back(s.t_cross(p));
    }
    return f;
}

// ------------------------------------------------------------------------------------------------
// (a) Bohren & Huffman §8.4.
CylinderSolution solve_homogeneous_bh(double radius_um, cplx m, double lambda_um, double theta_i, int pol) {
    if (pol != 1 && pol != 2) throw std::invalid_argument("pol must be 1 or 2");
    if (!(std::fabs(theta_i) < kPi / 2)) throw std::invalid_argument("|theta_i| must be < pi/2");
    const double k0 = 2.0 * kPi / lambda_um;
    const double x = k0 * radius_um;
    const double sinz = std::cos(theta_i), cosz = std::sin(theta_i);  // zeta = pi/2 - theta_i
    const double xi = x * sinz;
    cplx eta = x * std::sqrt(m * m - cosz * cosz);
    if (eta.imag() < 0) eta = -eta;
    CylinderSolution s;
    s.x = x;
    s.theta_i = theta_i;
    s.pol = pol;
    s.k0 = k0;
    s.gamma0 = k0 * std::cos(theta_i);
    s.beta = -k0 * std::sin(theta_i);
    s.nmax = default_nmax(x);
    s.q_abs_flux = std::numeric_limits<double>::quiet_NaN();
    const int N = s.nmax;
    const Family Je = family(Kind::J, eta, N), Jx = family(Kind::J, cplx(xi, 0.0), N),
                 Hx = family(Kind::H, cplx(xi, 0.0), N);
    s.co.assign(2 * N + 1, 0.0);
    s.cr.assign(2 * N + 1, 0.0);
    const cplx m2 = m * m;
    for (int n = 0; n <= N; ++n) {
        const cplx jn_e = Je.f[n], jnp_e = Je.fp[n], jn_x = Jx.f[n], jnp_x = Jx.fp[n], hn = Hx.f[n], hnp = Hx.fp[n];
        const cplx A = kI * xi * (xi * jnp_e * jn_x - eta * jn_e * jnp_x);
        const cplx B = xi * (m2 * xi * jnp_e * jn_x - eta * jn_e * jnp_x);
        const cplx fac = static_cast<double>(n) * cosz * eta * jn_e * (xi * xi / (eta * eta) - 1.0);
        const cplx Cc = fac * jn_x;
        const cplx D = fac * hn;
        const cplx V = xi * (m2 * xi * jnp_e * hn - eta * jn_e * hnp);
        const cplx W = kI * xi * (eta * jn_e * hnp - xi * jnp_e * hn);
        const cplx Delta = W * V + kI * D * D;
        const cplx aI = (Cc * V - B * D) / Delta;
        const cplx bI = (W * B + kI * D * Cc) / Delta;
        const cplx aII = -(A * V - kI * Cc * D) / Delta;
        const cplx bII = -kI * (Cc * W + A * D) / Delta;
        // B&H symmetry: a_{-n,I} = -a_{n,I}, b_{-n,I} = b_{n,I}; a_{-n,II} = a_{n,II}, b_{-n,II} = -b_{n,II}.
        // Cross-polarised terms: T_cross = -sum_n a_nI e^{in Phi} (case I), -sum_n b_nII e^{in Phi} (case II)
        // in this header's frame/basis (the sign is a basis-orientation convention; it is verified
        // against the independent field-matching solver in test_cylinder_oracle.cpp).
        if (pol == 1) {
            s.co[N + n] = bI;
            s.co[N - n] = bI;
            s.cr[N + n] = -aI;
            s.cr[N - n] = (n == 0) ? -aI : aI;
        } else {
            s.co[N + n] = aII;
            s.co[N - n] = aII;
            s.cr[N + n] = -bII;
            s.cr[N - n] = (n == 0) ? -bII : bII;
        }
    }
    finish(s);
    return s;
}

// ------------------------------------------------------------------------------------------------
// (b) Multilayer cylinder by field matching.
//
// In every homogeneous region, fields ~ e^{i n phi} e^{i beta z_axis}; with Ht = eta0 H (so all four
// components are dimensionless),
//   E_phi  = (i/gamma^2) [ beta (i n/rho) E_z - k0 d_rho Ht_z ]
//   Ht_phi = (i/gamma^2) [ beta (i n/rho) Ht_z + k0 m^2 d_rho E_z ]
// (e^{-i omega t}; from E_t = (i/gamma^2)[beta grad_t E_z - omega mu0 z x grad_t H_z], H_t dual).
// Local frame: axis z_L = project y, x_L = d_t (incident transverse direction), phi measured from x_L
// toward y_L = z_L x x_L; phi = Phi.  Incident: E_z = e_z sum i^n J_n(gamma0 rho) e^{i n phi}, same for
// Ht_z with h_z; pol 1: (e_z, h_z) = (cos theta_i, 0), pol 2: (0, -cos theta_i).
// Far field: E along e1_o = E_z / cos theta_i, along e2_o (= -phi_hat) = -Ht_z / cos theta_i.
namespace {

// The layered cylinder at one (λ, θ_i, pol), the same for every order n: transverse wavenumbers,
// the Bessel families at every interface and the layout of the unknowns.
struct Layered {
    int L = 0, N = 0, nu = 0;  // layers, highest order, unknowns per order (4 L)
    double k0 = 0, beta = 0, ct = 0;
    double e_z = 0, h_z = 0;   // incident axial amplitudes
    const std::vector<double>* radii = nullptr;
    std::vector<cplx> gam, m2;  // per layer, [L] = outside
    // Families: for layer l, J at its inner (l-1) and outer (l) radius, Y likewise (l >= 1).
    // Outside: J and H at the outer radius.
    struct AtR {
        Family J, Y, H;
    };
    std::vector<AtR> inner, outer;  // inner[l]: layer l evaluated at radii[l-1]; outer[l]: at radii[l]

    // Column layout: core: [AE, AH] -> cols 0,1; shell l (1..L-1): [AE, BE, AH, BH] -> 2 + 4(l-1) + 0..3;
    // outside: [cE, cH] -> nu-2, nu-1.
    int col_of(int layer, int which) const {  // which: 0 AE, 1 BE, 2 AH, 3 BH (core/outside: 0 -> E, 2 -> H)
        if (layer == 0) return which == 0 ? 0 : 1;
        if (layer == L) return which == 0 ? nu - 2 : nu - 1;
        return 2 + 4 * (layer - 1) + which;
    }
    // Field rows (E_z, Ht_z, E_phi, Ht_phi) of one basis function of order n (value f, derivative fp
    // w.r.t. the argument) at radius r in medium l.
    void rows(int n, int l, double r, cplx f, cplx fp, bool etype, cplx out[4]) const {
        const cplx g = gam[l];
        const cplx pre = kI / (g * g);
        const cplx ang = beta * kI * static_cast<double>(n) / r;
        if (etype) {  // coefficient of E_z
            out[0] = f;
            out[1] = 0.0;
            out[2] = pre * ang * f;
            out[3] = pre * k0 * m2[l] * g * fp;
        } else {  // coefficient of Ht_z
            out[0] = 0.0;
            out[1] = f;
            out[2] = -pre * k0 * g * fp;
            out[3] = pre * ang * f;
        }
    }
};

Layered layered_setup(const std::vector<double>& radii_um, const std::vector<cplx>& m, double k0, double theta_i,
                      int N, int pol) {
    const int L = static_cast<int>(radii_um.size());
    const double st = std::sin(theta_i), ct = std::cos(theta_i);
    Layered c;
    c.L = L;
    c.N = N;
    c.nu = 4 * L;
    c.k0 = k0;
    c.beta = -k0 * st;
    c.ct = ct;
    c.e_z = (pol == 1) ? ct : 0.0;
    c.h_z = (pol == 1) ? 0.0 : -ct;
    c.radii = &radii_um;
    c.gam.resize(L + 1);
    c.m2.resize(L + 1);
    for (int l = 0; l < L; ++l) {
        c.m2[l] = m[l] * m[l];
        c.gam[l] = k0 * std::sqrt(c.m2[l] - st * st);
        if (c.gam[l].imag() < 0) c.gam[l] = -c.gam[l];
    }
    c.m2[L] = 1.0;
    c.gam[L] = k0 * ct;
    c.inner.resize(L + 1);
    c.outer.resize(L + 1);
    for (int l = 0; l < L; ++l) {
        c.outer[l].J = family(Kind::J, c.gam[l] * radii_um[l], N);
        if (l >= 1) {
            c.outer[l].Y = family(Kind::Y, c.gam[l] * radii_um[l], N);
            c.inner[l].J = family(Kind::J, c.gam[l] * radii_um[l - 1], N);
            c.inner[l].Y = family(Kind::Y, c.gam[l] * radii_um[l - 1], N);
        }
    }
    c.inner[L].J = family(Kind::J, c.gam[L] * radii_um[L - 1], N);
    c.inner[L].H = family(Kind::H, c.gam[L] * radii_um[L - 1], N);
    return c;
}

// Scale of every unknown of order n (the larger of its basis function's value and derivative at
// its radius); false when one of them under- or overflows (such high orders do not contribute).
bool column_scales(const Layered& c, int n, std::vector<double>& colscale) {
    const int L = c.L;
    colscale.assign(c.nu, 1.0);
    auto scale_of = [](cplx f, cplx fp) { return std::max(std::abs(f), std::abs(fp)); };
    colscale[c.col_of(0, 0)] = colscale[c.col_of(0, 2)] = scale_of(val(c.outer[0].J, n), der(c.outer[0].J, n));
    for (int l = 1; l < L; ++l) {
        const double sj = scale_of(val(c.outer[l].J, n), der(c.outer[l].J, n));
        const double sy = scale_of(val(c.inner[l].Y, n), der(c.inner[l].Y, n));
        colscale[c.col_of(l, 0)] = colscale[c.col_of(l, 2)] = sj;
        colscale[c.col_of(l, 1)] = colscale[c.col_of(l, 3)] = sy;
    }
    colscale[c.nu - 2] = colscale[c.nu - 1] = scale_of(val(c.inner[L].H, n), der(c.inner[L].H, n));
    bool bad = false;
    for (double v : colscale)
        if (!(v > 0.0) || !std::isfinite(v)) bad = true;
    return !bad;
}

// The four continuity rows of order n at interface ifc (radius radii[ifc], between layer ifc inside
// and ifc + 1 outside): inside fields minus outside fields, the incident part on the right.
void fill_interface(const Layered& c, int n, int ifc, const std::vector<double>& colscale, Eigen::MatrixXcd& A,
                    Eigen::VectorXcd& rhs) {
    const int L = c.L, nu = c.nu;
    const double r = (*c.radii)[ifc];
    const int row0 = 4 * ifc;
    cplx rv[4];
    // inside medium (layer ifc): J at its outer radius, Y at its outer radius
    {
        const int l = ifc;
        const cplx fj = val(c.outer[l].J, n), fjp = der(c.outer[l].J, n);
        for (int et = 0; et < 2; ++et) {
            c.rows(n, l, r, fj, fjp, et == 0, rv);
            const int col = c.col_of(l, et == 0 ? 0 : 2);
            for (int k = 0; k < 4; ++k) A(row0 + k, col) += rv[k] / colscale[col];
        }
        if (l >= 1) {
            const cplx fy = val(c.outer[l].Y, n), fyp = der(c.outer[l].Y, n);
            for (int et = 0; et < 2; ++et) {
                c.rows(n, l, r, fy, fyp, et == 0, rv);
                const int col = c.col_of(l, et == 0 ? 1 : 3);
                for (int k = 0; k < 4; ++k) A(row0 + k, col) += rv[k] / colscale[col];
            }
        }
    }
    // outside medium (layer ifc+1), subtracted
    const int l = ifc + 1;
    if (l < L) {
        const cplx fj = val(c.inner[l].J, n), fjp = der(c.inner[l].J, n);
        const cplx fy = val(c.inner[l].Y, n), fyp = der(c.inner[l].Y, n);
        for (int et = 0; et < 2; ++et) {
            c.rows(n, l, r, fj, fjp, et == 0, rv);
            int col = c.col_of(l, et == 0 ? 0 : 2);
            for (int k = 0; k < 4; ++k) A(row0 + k, col) -= rv[k] / colscale[col];
            c.rows(n, l, r, fy, fyp, et == 0, rv);
            col = c.col_of(l, et == 0 ? 1 : 3);
            for (int k = 0; k < 4; ++k) A(row0 + k, col) -= rv[k] / colscale[col];
        }
    } else {
        const cplx fh = val(c.inner[L].H, n), fhp = der(c.inner[L].H, n);
        const cplx fj = val(c.inner[L].J, n), fjp = der(c.inner[L].J, n);
        for (int et = 0; et < 2; ++et) {
            c.rows(n, L, r, fh, fhp, et == 0, rv);
            const int col = (et == 0) ? nu - 2 : nu - 1;
            for (int k = 0; k < 4; ++k) A(row0 + k, col) -= rv[k] / colscale[col];
            // incident part -> right-hand side (+ incident)
            c.rows(n, L, r, fj, fjp, et == 0, rv);
            const cplx amp = ipow(n) * (et == 0 ? c.e_z : c.h_z);
            for (int k = 0; k < 4; ++k) rhs(row0 + k) += rv[k] * amp;
        }
    }
}

// Order n's term of the absorbed power from the total exterior field at r = a (per-order Poynting
// flux): Q_abs = -pi Re sum_n (E_phi Ht_z^* - E_z Ht_phi^*).
double exterior_flux_term(const Layered& c, int n, cplx cE, cplx cH) {
    const int L = c.L;
    const double r = (*c.radii)[L - 1];
    cplx rv[4];
    cplx tot[4] = {0, 0, 0, 0};
    const cplx fh = val(c.inner[L].H, n), fhp = der(c.inner[L].H, n);
    const cplx fj = val(c.inner[L].J, n), fjp = der(c.inner[L].J, n);
    c.rows(n, L, r, fh, fhp, true, rv);
    for (int k = 0; k < 4; ++k) tot[k] += rv[k] * cE;
    c.rows(n, L, r, fh, fhp, false, rv);
    for (int k = 0; k < 4; ++k) tot[k] += rv[k] * cH;
    c.rows(n, L, r, fj, fjp, true, rv);
    for (int k = 0; k < 4; ++k) tot[k] += rv[k] * (ipow(n) * c.e_z);
    c.rows(n, L, r, fj, fjp, false, rv);
    for (int k = 0; k < 4; ++k) tot[k] += rv[k] * (ipow(n) * c.h_z);
    return (tot[2] * std::conj(tot[1]) - tot[0] * std::conj(tot[3])).real();
}

}  // namespace

CylinderSolution solve_layered(const std::vector<double>& radii_um, const std::vector<cplx>& m, double lambda_um,
                               double theta_i, int pol) {
    if (pol != 1 && pol != 2) throw std::invalid_argument("pol must be 1 or 2");
    if (!(std::fabs(theta_i) < kPi / 2)) throw std::invalid_argument("|theta_i| must be < pi/2");
    const int L = static_cast<int>(radii_um.size());
    if (L < 1 || static_cast<int>(m.size()) != L) throw std::invalid_argument("radii/m size mismatch");
    for (int l = 1; l < L; ++l)
        if (!(radii_um[l] > radii_um[l - 1])) throw std::invalid_argument("radii must increase");
    const double k0 = 2.0 * kPi / lambda_um;
    const double ct = std::cos(theta_i);
    const double x = k0 * radii_um.back();
    CylinderSolution s;
    s.x = x;
    s.theta_i = theta_i;
    s.pol = pol;
    s.k0 = k0;
    s.gamma0 = k0 * ct;
    s.beta = -k0 * std::sin(theta_i);
    s.nmax = default_nmax(x);
    const int N = s.nmax;
    s.co.assign(2 * N + 1, 0.0);
    s.cr.assign(2 * N + 1, 0.0);
    const Layered c = layered_setup(radii_um, m, k0, theta_i, N, pol);
    const int nu = c.nu;
    Eigen::MatrixXcd A(nu, nu);
    Eigen::VectorXcd rhs(nu);
    std::vector<double> colscale;
    double qabs_sum = 0.0;
    for (int n = -N; n <= N; ++n) {
        A.setZero();
        rhs.setZero();
        if (!column_scales(c, n, colscale)) continue;  // orders this high do not contribute: leave zero
        for (int ifc = 0; ifc < L; ++ifc) fill_interface(c, n, ifc, colscale, A, rhs);
        const Eigen::VectorXcd sol = A.fullPivLu().solve(rhs);
        const cplx cE = sol(nu - 2) / colscale[nu - 2];
        const cplx cH = sol(nu - 1) / colscale[nu - 1];
        const cplx ph = ipow(-n) / ct;  // (-i)^n / cos theta_i
        const cplx tE = -cE * ph;       // component along e1_o
        const cplx tH = cH * ph;        // component along e2_o
        if (pol == 1) {
            s.co[n + N] = tE;
            s.cr[n + N] = tH;
        } else {
            s.co[n + N] = tH;
            s.cr[n + N] = tE;
        }
        qabs_sum += exterior_flux_term(c, n, cE, cH);
    }
    s.q_abs_flux = -kPi * qabs_sum;
    finish(s);
    return s;
}

}  // namespace plumage::oracle
