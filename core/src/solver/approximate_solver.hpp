// ScatteringSolver "approximate" (paper §4): local reflection under every top-surface node,
// fictitious surface currents (Eq. 2), far field on the specular cone (Eqs. 3, 7), incident
// power (Eq. 9).
//
// | name            | type   | unit | default   | meaning                                             |
// |-----------------|--------|------|-----------|-----------------------------------------------------|
// | currents        | choice | -    | reflected | `reflected` (E_r, H_r only, as the reference code)  |
// |                 |        |      |           | or `incident_and_reflected` (Eq. 2 as printed)      |
// | window_fraction | number | 1    | 0.25      | Gaussian window w(x) = exp(−x²/s²), s = fraction·W  |
// | normalisation   | choice | -    | capped    | what FarField::incident_power (the normaliser) is:  |
// |                 |        |      |           | `eq9` paper Eq. 9 (intercepted power); `lossless`   |
// |                 |        |      |           | the cone power of the same currents with every      |
// |                 |        |      |           | local reflectance raised to 1 (phase and            |
// |                 |        |      |           | polarization kept); `capped` max of the two         |
// | reflection_samples | int | -    | 1         | local reflection averaged over K sub-samples per    |
// |                 |        |      |           | segment, tent-weighted per node (stacks that change |
// |                 |        |      |           | abruptly along the top, e.g. platelet ends)         |
// | far_field       | choice | -    | chunked   | `chunked` (band-limited interpolation per chunk) or |
// |                 |        |      |           | `exact` (every node × direction); radiation.hpp     |
//
// Why `capped` is the default (docs/architecture.md, docs/validation.md): with windowed
// Kirchhoff currents, Eq. 9 lets a perfect flat mirror reflect 1.56 of the incident power at
// (cos θ_i, cos φ_i) = (0.05, 0.05) — the window's angular spread meets the obliquity of the
// currents — and real barbules up to 2.6. A lossless surface cannot reflect more than it
// receives, so where the lossless reference radiates more than Eq. 9's power the approximation
// is creating energy and the reference becomes the normaliser; elsewhere Eq. 9 stands (it was
// the closer of the two to the full-wave reflected fraction on a rock-dove segment, issue 6).
// R = P/max(Φ_eq9, P_ref) ≤ P/P_ref, which stays in [0, 1] on the whole grid. Cost: 12 more
// current columns in the far field (~+40 %).
#pragma once

#include "plumage/plugin_registry.hpp"
#include "plumage/scattering_solver.hpp"
#include "chunking_options.hpp"

namespace plumage {

class ApproximateSolver final : public ScatteringSolver {
 public:
  enum class Currents { reflected, incident_and_reflected };
  enum class Normalisation { capped, lossless, eq9 };
  static constexpr int kReferenceBins = 400;  // the pattern bins of the lossless reference

  ApproximateSolver(Currents currents, double window_fraction,
                    Normalisation normalisation = Normalisation::capped,
                    detail::ChunkingOptions chunking = {}, int reflection_samples = 1)
      : currents_(currents), window_fraction_(window_fraction), normalisation_(normalisation),
        chunking_(chunking), reflection_samples_(reflection_samples) {}

  // The same solver with another far-field evaluation (benchmarks, accuracy studies).
  ApproximateSolver with_chunking(const detail::ChunkingOptions& chunking) const {
    return ApproximateSolver(currents_, window_fraction_, normalisation_, chunking, reflection_samples_);
  }
  const detail::ChunkingOptions& chunking() const { return chunking_; }

  std::shared_ptr<const Prepared> prepare(
      const CrossSection& section, std::shared_ptr<const LocalReflection> reflection) const override;

  std::vector<FarField> solve(const Prepared& prepared, double lambda_nm, double theta_i_rad,
                              std::span<const double> phi_i_rad,
                              std::span<const double> phi_o_rad) const override;

  MemoryEstimate estimate_memory(const CrossSection& section, double lambda_nm, std::size_t n_phi_i,
                                 std::size_t n_phi_o) const override;

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
  Normalisation normalisation_;
  detail::ChunkingOptions chunking_;
  int reflection_samples_;
};

// Registers "approximate" with the registry's built-in registrar.
void register_approximate_solver(PluginRegistry& registry);

}  // namespace plumage
