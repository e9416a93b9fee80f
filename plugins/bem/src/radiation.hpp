// Far field of the BEM currents (spec §6.9 with the formulas of §4.1):
//   𝓔(φ_o) = ∫_C g(ρ') [ −(k0/4) (I − ôô)·J̃(ρ') + (k0/4) ô × M(ρ') ] dl',
//   g = sqrt(2/(iπγ0)) e^{−iγ0 ρ̂_o·ρ'},  ô = (cos θ_i sin φ_o, −sin θ_i, cos θ_i cos φ_o),
// over every segment bordering the air (σ_{0,i} = +1 there), J̃ = η0 J, lengths in nm.
#pragma once

#include <Eigen/Dense>
#include <span>

#include "mesh.hpp"

namespace plumage::bem {

// F with 𝓔_c(φ_o[d]) = Σ_u F(3d + c, u) x_u for a solution vector x (rows 3·#directions,
// columns mesh.unknowns(); only columns of air-side unknowns are non-zero).
Eigen::MatrixXcd far_field_operator(const Mesh& mesh, double k0, double theta, std::span<const double> phi_o);

}  // namespace plumage::bem
