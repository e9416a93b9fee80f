// Incident fields (spec §6.7) and the PMCHWT right-hand sides (spec §6.4).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "mesh.hpp"
#include "plumage/far_field.hpp"

namespace plumage::bem {

using CVec3 = std::array<std::complex<double>, 3>;

// A superposition of plane waves with the same θ_i (same β): Σ_q amp_q E^p(θ_i, α_q) e^{i k(α_q)·(ρ − focus)}.
// One wave of amplitude 1 is a plane wave; the exact 2.5D Gaussian beam of §6.7 uses
// amp_q = Δα A(α_q), A(α) = (γ0 s_b/(2√π)) exp(−γ0² s_b² sin²(α − φ_i)/4), unit amplitude at the focus.
struct IncidentField {
  double theta = 0.0;
  int pol = 0;  // 0: pol 1, 1: pol 2 (far_field.hpp)
  Vec2 focus{0.0, 0.0};
  std::vector<double> alpha;
  std::vector<double> amp;
  void fields(double k0, Vec2 rho, CVec3& e, CVec3& eta0_h) const;
};

IncidentField plane_wave(double theta, double phi, int pol);
// Beam of waist s_b (nm) about azimuth φ_i focused at `focus`; `extent` = largest distance of
// the body from the focus (sets the angular sampling so that aliased images lie ≥ 4·extent away).
IncidentField gaussian_beam(double k0, double theta, double phi, int pol, double s_b, Vec2 focus,
                            double extent);

// Right-hand side −σ_{0,i} ⟨Λ, E_inc⟩, −σ_{0,i} ⟨Λ, η0 H_inc⟩ on the segments bordering the air.
void fill_rhs(const Mesh& mesh, double k0, const IncidentField& inc, Eigen::Ref<Eigen::VectorXcd> b);

}  // namespace plumage::bem
