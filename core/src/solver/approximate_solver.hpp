// ScatteringSolver "approximate" (paper §4): local reflection under every top-surface node,
// fictitious surface currents (Eq. 2), far field on the specular cone (Eqs. 3, 7), incident
// power (Eq. 9).
//
// | name            | type   | unit | default   | meaning                                             |
// |-----------------|--------|------|-----------|-----------------------------------------------------|
// | currents        | choice | -    | reflected | `reflected` (E_r, H_r only, as the reference code)  |
// |                 |        |      |           | or `incident_and_reflected` (Eq. 2 as printed)      |
// | window_fraction | number | 1    | 0.25      | Gaussian window w(x) = exp(−x²/s²), s = fraction·W  |
#pragma once

#include "plumage/plugin_registry.hpp"
#include "plumage/scattering_solver.hpp"

namespace plumage {

class ApproximateSolver final : public ScatteringSolver {
 public:
  enum class Currents { reflected, incident_and_reflected };

  ApproximateSolver(Currents currents, double window_fraction)
      : currents_(currents), window_fraction_(window_fraction) {}

  std::shared_ptr<const Prepared> prepare(
      const CrossSection& section, std::shared_ptr<const LocalReflection> reflection) const override;

  std::vector<FarField> solve(const Prepared& prepared, double lambda_nm, double theta_i_rad,
                              std::span<const double> phi_i_rad,
                              std::span<const double> phi_o_rad) const override;

  // The Eq. 2 currents at the interior top nodes for one incident direction, incident phase
  // included: [pol][node] of (J̃ = η0 J, M), for diagnostics and independent checks.
  struct NodeCurrents {
    std::vector<Vec2> position;
    std::array<std::vector<std::array<Complex, 6>>, 2> current;
    std::array<double, 2> incident_power{0.0, 0.0};  // Φ_i (Eq. 9)
  };
  NodeCurrents currents(const Prepared& prepared, double lambda_nm, const IncidentDirection& incident) const;

  // The reference code's way, kept as a baseline for benchmarks: node currents (incident phase
  // included) on tents, 3-point Gauss on each half support, one complex exponential per node,
  // quadrature point and direction; no GEMM.
  FarField solve_direct_sum(const Prepared& prepared, double lambda_nm,
                            const IncidentDirection& incident, std::span<const double> phi_o_rad) const;

 private:
  Currents currents_;
  double window_fraction_;
};

// Registers "approximate" with the registry's built-in registrar.
void register_approximate_solver(PluginRegistry& registry);

}  // namespace plumage
