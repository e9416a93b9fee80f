// Rigorous reference values from Arb (tests only).
#pragma once

#include <acb.h>
#include <acb_hypgeom.h>
#include <arb.h>

#include <complex>
#include <stdexcept>

namespace plumage::bem::testing {

// J_n(z), Y_n(z), H_n^(1)(z) = J + iY for integer n and complex double z, rounded to double.
// The working precision is raised until every result has >= 60 correct relative bits.
struct ArbJYH {
    std::complex<double> j, y, h;
};

inline std::complex<double> acb_to_cd(const acb_t v) {
    return {arf_get_d(arb_midref(acb_realref(v)), ARF_RND_NEAR), arf_get_d(arb_midref(acb_imagref(v)), ARF_RND_NEAR)};
}

inline ArbJYH arb_bessel(int n, std::complex<double> z) {
    acb_t az, anu, j, y, h;
    acb_init(az);
    acb_init(anu);
    acb_init(j);
    acb_init(y);
    acb_init(h);
    acb_set_d_d(az, z.real(), z.imag());
    acb_set_si(anu, n);
    ArbJYH out{};
    bool ok = false;
    for (slong prec = 128; prec <= 65536 && !ok; prec *= 2) {
        acb_hypgeom_bessel_jy(j, y, anu, az, prec);
        acb_mul_onei(h, y);
        acb_add(h, h, j, prec);
        ok = acb_rel_accuracy_bits(j) >= 60 && acb_rel_accuracy_bits(y) >= 60 && acb_rel_accuracy_bits(h) >= 60;
        if (ok) {
            out.j = acb_to_cd(j);
            out.y = acb_to_cd(y);
            out.h = acb_to_cd(h);
        }
    }
    acb_clear(az);
    acb_clear(anu);
    acb_clear(j);
    acb_clear(y);
    acb_clear(h);
    if (!ok) throw std::runtime_error("arb_bessel: precision not reached");
    return out;
}

}  // namespace plumage::bem::testing
