// plumage — exact series solutions for light scattering by infinite circular cylinders
// (homogeneous and multilayer/coated), normal and oblique incidence.  The reference ("oracle") the
// 2.5D BEM is checked against by its accuracy ladder and tests (spec wave-simulation.md §6.11 items
// 1 and 2).  Independent of any BEM code: it uses only the order-0/1 Bessel functions of
// plugins/bem/numerics/hankel.hpp and its own integer-order recurrences.
//
// ------------------------------------------------------------------------------------------------
// Conventions
//  * Time factor e^{-i omega t}; complex index m = n + i kappa, kappa >= 0 absorbs.  H_n = H_n^(1).
//  * Lengths in micrometres (names end in _um), angles in radians.  Non-magnetic media.
//  * Project frame (DESIGN.md §6): barbule/cylinder axis = +y, cross-section plane = xz.
//    A direction is omega = (cos t sin p, sin t, cos t cos p) (t out of the xz-plane, p = azimuth
//    from +z).  omega_i points TOWARD the light: the incident wave vector is k_i = -k0 omega_i.
//    theta_i = 0 means the light travels perpendicular to the axis.  Axial wavenumber
//    beta = -k0 sin theta_i, transverse wavenumber in air gamma0 = k0 cos theta_i, inside layer j
//    gamma_j = k0 sqrt(m_j^2 - sin^2 theta_i) (Im >= 0).  Requires |theta_i| < pi/2.
//  * Incident polarisations (unit |E|, H = (k_hat x E)/eta0, k_hat = -omega_i):
//      pol 1 (= Bohren & Huffman case I, "E has an axial component", TM_z at theta_i = 0):
//          E1 = (-sin t sin p, cos t, -sin t cos p)  = unit vector perpendicular to k_hat in the
//               plane (k_hat, axis), with positive axial component;
//      pol 2 (= B&H case II, "E perpendicular to the axis", TE_z at theta_i = 0):
//          E2 = (cos p, 0, -sin p) = d_t x y_hat, with d_t = -(sin p, 0, cos p) the transverse
//               propagation direction.
//    (These are the component-wise images of spec §1.3 under spec (x, y, z) -> project (x, z, y).)
//  * Scattered light lies on the cone theta_o = -theta_i:
//      omega_o = (cos theta_i sin phi_o, -sin theta_i, cos theta_i cos phi_o).
//    The oracle uses the scattering angle  Phi = phi_o - phi_i - pi  (Phi = 0: forward direction;
//    Phi increases from the forward transverse direction d_t toward y_hat x d_t).  Use
//    scattering_angle(phi_o, phi_i) to convert.
//  * Outgoing basis on the cone (both perpendicular to omega_o):
//      e1_o = (y_hat - (y_hat.omega_o) omega_o)/cos theta_i   (axial-plane vector, positive y part),
//      e2_o = rho_o x y_hat = (-cos phi_o, 0, sin phi_o),  rho_o = (sin phi_o, 0, cos phi_o).
//    In the forward direction e1_o = E1 and e2_o = E2.
//
// Far field and normalisation
//  At distance rho from the axis (rho -> infinity), for unit incident |E|:
//      E_sca = sqrt(2/(pi gamma0 rho)) exp(i(gamma0 rho + beta y + 3 pi/4)) [T1(Phi) e1_o + T2(Phi) e2_o]
//  ("T_co" = component along the incident polarisation's own basis vector, e_p,o, "T_cross" = the
//  other one).  With this normalisation (B&H §8.4, T = T1..T4 of B&H up to the basis orientation):
//      differential scattering width per unit length, normalised by the incident irradiance
//      |S_i| = 1/(2 eta0):   d sigma/d Phi = (2/(pi k0)) (|T_co|^2 + |T_cross|^2)   [um]
//      Q_sca = C_sca/(2a) = (1/(pi x)) Int_0^{2pi} (|T_co|^2 + |T_cross|^2) dPhi = (2/x) Sum_n (|co_n|^2 + |cr_n|^2)
//      Q_ext = (2/x) Re T_co(0)     (optical theorem),  Q_abs = Q_ext - Q_sca,
//  with x = k0 a (a = outer radius) and efficiencies per unit DIAMETER and unit length, relative to
//  the full incident irradiance (B&H convention, also at oblique incidence).
//  Relation to FastSim's far-field vector (spec §4.1, E ~ e^{i gamma0 rho} rho^{-1/2} calE):
//      calE = sqrt(2/(pi gamma0)) e^{3 i pi/4} (T1 e1_o + T2 e2_o).
//  Power per unit axial length per unit Phi: |T|^2 /(pi eta0 k0) (= cos theta_i rho |E|^2 /(2 eta0)).
// ------------------------------------------------------------------------------------------------
#pragma once

#include <complex>
#include <vector>

namespace plumage::oracle {

using cplx = std::complex<double>;

// Integer-order Bessel functions of complex argument (Re z > 0 or real z > 0), orders 0..nmax.
//   J: backward (Miller) ratio recurrence anchored on J0 or J1 from numerics/hankel;
//   H^(1): forward recurrence from the order-0/1 values;  Y_n = i (J_n - H_n^(1)).
void bessel_j_orders(cplx z, int nmax, std::vector<cplx>& J);
void bessel_y_orders(cplx z, int nmax, std::vector<cplx>& Y);
void hankel1_orders(cplx z, int nmax, std::vector<cplx>& H);

struct CylinderSolution {
    double x = 0.0;          // k0 * outer radius
    double theta_i = 0.0;
    int pol = 1;
    double k0 = 0.0;         // 2 pi / lambda  [1/um]
    double gamma0 = 0.0;     // k0 cos theta_i
    double beta = 0.0;       // -k0 sin theta_i (axial wavenumber along +y)
    int nmax = 0;            // orders -nmax..nmax
    std::vector<cplx> co;    // T_co(Phi)    = sum_n co[n+nmax] e^{i n Phi}
    std::vector<cplx> cr;    // T_cross(Phi) = sum_n cr[n+nmax] e^{i n Phi}
    double q_ext = 0.0;      // (2/x) Re T_co(0)
    double q_sca = 0.0;      // (2/x) sum |co|^2 + |cr|^2
    double q_abs = 0.0;      // q_ext - q_sca
    double q_abs_flux = 0.0; // layered solver only: net inward Poynting flux through the outer surface
                             // (independent of the optical theorem); NaN for the B&H solver.
    // Scattered axial fields outside the cylinder, in the local frame of the header (factor e^{i beta y}
    // omitted):  E_y = sum_n ez[n+nmax] H_n(gamma0 rho) e^{i n Phi},  eta0 H_y = sum_n hz[n+nmax] H_n(...) e^{i n Phi}.
    std::vector<cplx> ez, hz;
    cplx t_co(double Phi) const;
    cplx t_cross(double Phi) const;
    // d sigma/dPhi normalised as Q: dQ_sca/dPhi = (|T_co|^2 + |T_cross|^2)/(pi x).
    double dq_sca_dphi(double Phi) const;
};

// Exact scattered axial fields (E_y, eta0 H_y) at distance rho_um >= outer radius from the axis and
// scattering angle Phi (factor e^{i beta y} omitted); for near-field comparisons with the BEM.
struct AxialFields {
    cplx e_axis, eta0_h_axis;
};
AxialFields scattered_axial_fields(const CylinderSolution& s, double rho_um, double Phi);

// FastSim-style far-field vector calE(phi_o) in the project frame (x, y, z), spec §4.1:
//   E_sca ~ e^{i beta y} e^{i gamma0 rho} rho^{-1/2} calE,  calE = sqrt(2/(pi gamma0)) e^{3 i pi/4} (T1 e1_o + T2 e2_o).
struct Vec3c {
    cplx x, y, z;
};
Vec3c far_field_vector(const CylinderSolution& s, double phi_i, double phi_o);

// Scattering angle Phi of an outgoing azimuth phi_o for incident azimuth phi_i (project frame), in (-pi, pi].
double scattering_angle(double phi_o, double phi_i);

// Far-field amplitudes over a list of scattering angles.
struct FarField {
    std::vector<cplx> t_co, t_cross;
};
FarField far_field(const CylinderSolution& s, const std::vector<double>& Phi);

// (a) Homogeneous cylinder, Bohren & Huffman §8.4 coefficient formulas (spec §6.11 item 1).
CylinderSolution solve_homogeneous_bh(double radius_um, cplx m, double lambda_um, double theta_i, int pol);

// (b) Multilayer cylinder: layer 0 is the core; radii_um strictly increasing (outer radius of each layer),
//     m[j] the index of layer j; exterior is vacuum/air (index 1).  Per order n, E_z and H_z are
//     expanded in J_n, Y_n (J_n only in the core, J_n + H_n outside) and continuity of E_z, H_z,
//     E_phi, H_phi is imposed at every interface (4 equations per interface, dense LU).
//     A single layer reproduces the homogeneous cylinder (checked against (a) in the tests).
CylinderSolution solve_layered(const std::vector<double>& radii_um, const std::vector<cplx>& m, double lambda_um,
                               double theta_i, int pol);

// Number of orders used for size parameter x: ceil(x + 4 x^{1/3} + 10).
int default_nmax(double x);

}  // namespace plumage::oracle
