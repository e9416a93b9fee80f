// Independent closed-form reference of the FDTD ladder and tests: Airy/Parratt recursion for a
// layered medium (wave-simulation.md §2.4 convention), with the reflected E and H vectors of a
// plane wave of arbitrary (conical) incidence reconstructed from r_s and r_p. Written without the
// engine's code paths (the caller supplies the permittivities, e.g. MaterialModel::eps).
#pragma once

#include <array>
#include <complex>
#include <vector>

namespace plumage::fdtd_reference {

using cplx = std::complex<double>;
using V3 = std::array<cplx, 3>;

struct Stack {
  std::vector<cplx> eps;      // ambient, layers..., substrate
  std::vector<double> thick;  // layers only (size eps.size() - 2)
};

// {r_s (E ratio), r_p (H ratio)} at wavenumber k0 and in-plane wavenumber kpar.
std::array<cplx, 2> airy(const Stack& s, double k0, double kpar);

// Engine frame (z down into the stack). Incident wave e^{i(kx x + ky y + kz z)} with E = Einc:
// the reflected {E, H} at z = 0 (H = k̂_r × E, η0 = 1).
std::array<V3, 2> reflect(const Stack& s, double k0, double kx, double ky, const V3& Einc);

}  // namespace plumage::fdtd_reference
