// CPML (Roden–Gedney convolutional PML, stretched ∂̃z = ∂z/κ + ψ) above the air and below the
// substrate, PEC behind (NOTES.md §2): the profiles per row and the ψ recursions
//   ψ⁺ = b ψ + a ∂z F,   b = e^{−(σ/κ + α) dt},   a = σ (b − 1) / (σ κ + κ² α).
#include <algorithm>
#include <cmath>

#include "sim.hpp"

namespace plumage::fdtd::detail {

void Sim::init_cpml(const SimParams& Pm) {
    const double d = L.npml * L.h;
    const double ztop = L.z0 + L.npml * L.h;
    const double zbot = L.z0 + (L.nz - 1 - L.npml) * L.h;
    const int m = Pm.pml_order;
    const double smax = Pm.pml_sigma_factor * 0.8 * (m + 1) / L.h;
    // Polynomial grading of order m over the PML depth d; α graded linearly to 0 at the inner edge.
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
}

// Row k (H at z_{k+½}): ψ of ∂z Ey (into Hx) and ∂z Ex (into Hy).
void Sim::cpml_H_row(int k, const cplx* ex, const cplx* ex1, const cplx* ey, const cplx* ey1) {
    const int nx = L.nx, r = k * nx;
    const double rh = 1.0 / L.h;
    const double bb = b_half[k], aa = a_half[k] * rh;
    cplx* __restrict hx = Hx.data() + r;
    cplx* __restrict hy = Hy.data() + r;
    cplx* px = pHx.data() + r;
    cplx* py = pHy.data() + r;
    for (int i = 0; i < nx; ++i) {
        px[i] = bb * px[i] + aa * (ey1[i] - ey[i]);
        py[i] = bb * py[i] + aa * (ex1[i] - ex[i]);
        hx[i] += dt * px[i];
        hy[i] -= dt * py[i];
    }
}

// Row k (D at z_k): ψ of ∂z Hy (into Dx) and ∂z Hx (into Dy).
void Sim::cpml_D_row(int k, const cplx* hx, const cplx* hx0, const cplx* hy, const cplx* hy0) {
    const int nx = L.nx, r = k * nx;
    const double rh = 1.0 / L.h;
    const double bb = b_int[k], aa = a_int[k] * rh;
    cplx* __restrict dx = Dx.data() + r;
    cplx* __restrict dy = Dy.data() + r;
    cplx* px = pDx.data() + r;
    cplx* py = pDy.data() + r;
    for (int i = 0; i < nx; ++i) {
        px[i] = bb * px[i] + aa * (hy[i] - hy0[i]);
        py[i] = bb * py[i] + aa * (hx[i] - hx0[i]);
        dx[i] -= dt * px[i];
        dy[i] += dt * py[i];
    }
}

}  // namespace plumage::fdtd::detail
