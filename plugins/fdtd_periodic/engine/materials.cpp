// Material models for the periodic FDTD engine: spec indices, broadband Lorentz fits.
#include "fdtd_periodic.hpp"
#include "internal.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace plumage::fdtd {

cplx MaterialModel::eps(double omega) const {
    cplx e = eps_inf;
    for (const auto& p : poles)
        e += p.delta_eps * p.omega0 * p.omega0 /
             cplx(p.omega0 * p.omega0 - omega * omega, -p.gamma * omega);
    if (eps_imag_ref != 0.0) e += cplx(0.0, eps_imag_ref * omega_ref / omega);
    return e;
}

cplx keratin_index(double lam) { return {1.532 + 0.00589 / (lam * lam), 0.0}; }
cplx melanin_index(double lam) {
    return {1.648 + 0.0237 / (lam * lam), 0.56 * std::exp(-lam / 0.270)};
}

MaterialModel air_model() {
    MaterialModel m;
    m.name = "air";
    m.eps_inf = 1.0;
    return m;
}

MaterialModel constant_model(std::string name, cplx eps, double lambda_ref_um) {
    MaterialModel m;
    m.name = std::move(name);
    m.eps_inf = eps.real();
    m.eps_imag_ref = eps.imag();
    m.omega_ref = 2.0 * kPi / lambda_ref_um;
    return m;
}

namespace detail {

FitReport fit_lorentz(const std::string& name, const std::function<cplx(double)>& index,
                      const std::vector<std::pair<double, double>>& shapes, double lam_min,
                      double lam_max) {
    // Unknowns: eps_inf, delta_eps_p (real). Least squares on Re and Im over a λ grid.
    const int ns = 61;
    const int np = static_cast<int>(shapes.size());
    Eigen::MatrixXd A(2 * ns, 1 + np);
    Eigen::VectorXd b(2 * ns);
    for (int s = 0; s < ns; ++s) {
        double lam = lam_min + (lam_max - lam_min) * s / (ns - 1);
        double w = 2 * kPi / lam;
        cplx n = index(lam);
        cplx e = n * n;
        A(2 * s, 0) = 1.0;
        A(2 * s + 1, 0) = 0.0;
        for (int p = 0; p < np; ++p) {
            double w0 = shapes[p].first, g = shapes[p].second;
            cplx chi = w0 * w0 / cplx(w0 * w0 - w * w, -g * w);
            A(2 * s, 1 + p) = chi.real();
            A(2 * s + 1, 1 + p) = chi.imag();
        }
        b(2 * s) = e.real();
        b(2 * s + 1) = e.imag();
    }
    Eigen::VectorXd x = A.colPivHouseholderQr().solve(b);
    FitReport r;
    r.model.name = name;
    r.model.eps_inf = x(0);
    for (int p = 0; p < np; ++p) r.model.poles.push_back({shapes[p].first, shapes[p].second, x(1 + p)});
    // error on a denser grid
    const int nd = 301;
    double sum2 = 0;
    for (int s = 0; s < nd; ++s) {
        double lam = lam_min + (lam_max - lam_min) * s / (nd - 1);
        cplx n = index(lam);
        cplx ef = r.model.eps(2 * kPi / lam);
        double de = std::abs(ef - n * n);
        double dn = std::abs(std::sqrt(ef) - n);
        r.max_abs_eps_error = std::max(r.max_abs_eps_error, de);
        r.max_abs_n_error = std::max(r.max_abs_n_error, dn);
        sum2 += de * de;
    }
    r.rms_abs_eps_error = std::sqrt(sum2 / nd);
    return r;
}

}  // namespace detail

// Pole shapes (ω0, γ in 1/µm; ω = 2π/λ[µm]) chosen once by a Nelder–Mead search over the
// shapes with the amplitudes solved linearly (dev tool, see NOTES.md); all amplitudes come
// out positive (passive, stable ADE).
const FitReport& keratin_fit() {
    static const FitReport r = detail::fit_lorentz(
        "keratin", keratin_index, {{kKeratinW0, 0.0}}, 0.38, 0.72);
    return r;
}

const FitReport& melanin_fit() {
    static const FitReport r = detail::fit_lorentz(
        "melanin", melanin_index, {{kMelaninW0a, kMelaninGa}, {kMelaninW0b, kMelaninGb}}, 0.38,
        0.72);
    return r;
}

}  // namespace plumage::fdtd
