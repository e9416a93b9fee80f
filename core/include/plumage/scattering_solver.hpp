// Extension point: far field of one barbule cross section under plane-wave illumination.
// Implementations: "approximate" (core; paper §4, local reflection → Eq. 2 currents → far
// field) and "bem" (plugins/bem; full-wave 2.5D boundary elements).
//
// Work is split so that nothing is computed more often than it changes: prepare() does what
// depends only on the instance (surface sampling, layer profiles under every node, a BEM mesh),
// solve() what depends on (λ, θ_i) and serves any number of incident azimuths at once (the
// far-field kernel of the approximate solver, the factorisation of a BEM matrix).
#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/far_field.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

class ScatteringSolver : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "scattering_solver";

  // Solver-specific, instance-only precomputation. Immutable and shareable across threads.
  class Prepared {
   public:
    virtual ~Prepared() = default;
  };

  // `reflection` is the species' LocalReflection (used by the approximate solver, ignored by
  // full-wave ones). The result does not refer to `section` afterwards.
  virtual std::shared_ptr<const Prepared> prepare(
      const CrossSection& section, std::shared_ptr<const LocalReflection> reflection) const = 0;

  // Far fields for every azimuth in `phi_i_rad` at one (λ, θ_i), both polarizations, at the
  // outgoing azimuths `phi_o_rad` on the specular cone. Thread-safe.
  virtual std::vector<FarField> solve(const Prepared& prepared, double lambda_nm,
                                      double theta_i_rad, std::span<const double> phi_i_rad,
                                      std::span<const double> phi_o_rad) const = 0;

  // Peak memory of one solve() of `section` at λ with `n_phi_i` incident azimuths and `n_phi_o`
  // outgoing directions, estimated without doing the work (plumage/memory_budget.hpp): what
  // `plumage check` reports, and what solve() refuses with MemoryBudgetError (exit status 2) where
  // it would not fit. Default: an empty estimate (a solver with nothing large to hold).
  virtual MemoryEstimate estimate_memory(const CrossSection& section, double lambda_nm, std::size_t n_phi_i,
                                         std::size_t n_phi_o) const {
    (void)section, (void)lambda_nm, (void)n_phi_i, (void)n_phi_o;
    return {};
  }
};

}  // namespace plumage
