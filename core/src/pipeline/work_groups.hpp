// Private to the pipeline: computing work groups (work_groups.cpp). A group is (λ bin w,
// cos θ_i row a): the far fields of every instance for all G azimuths b = 1 … G, then the G fits.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "plumage/characterize.hpp"
#include "plumage/scattering_solver.hpp"

namespace plumage {

// A unit shown by the fit diagnostics (pattern vs fit of one node), filled by the group that
// computes it.
struct FitDiagnostic {
  std::uint32_t w, a, b;
  std::vector<double> phi_o, u, fit;
  double rel_l2 = 0;
};

using PreparedInstances = std::vector<std::shared_ptr<const ScatteringSolver::Prepared>>;

// Instance n of N sees φ_i + δ_n with δ spread linearly over ±jitter (spec §0.3).
double azimuth_jitter_rad(int n, int count, double jitter_deg);

// Every instance's geometry, prepared for the solver (in parallel).
PreparedInstances prepare_instances(const SpeciesConfig& config, const CharacterizeSettings& s);

// One group: far fields of every instance for all G azimuths, then the G fits.
GroupRecord run_group(const SpeciesConfig& config, const CharacterizeSettings& s, const PreparedInstances& prepared,
                      std::size_t g, std::vector<FitDiagnostic>* diagnostics);

// Prepares the models and instances (only if there is work) and appends the groups `todo` to
// the journal in order, each with the warning codes raised for it (warning_attribution.hpp).
// `progress` and `cancelled` as in CharacterizeOptions (either may be empty).
struct GroupCallbacks {
  std::function<void(std::size_t, std::size_t, std::string_view)> progress;
  std::function<bool()> cancelled;
};
void compute_groups(const SpeciesConfig& config, const CharacterizeSettings& s, const PreparationOptions& preparation,
                    const std::vector<std::size_t>& todo, const std::filesystem::path& journal,
                    std::uintmax_t valid_bytes, const GroupCallbacks& callbacks,
                    std::vector<FitDiagnostic>* diagnostics);

}  // namespace plumage
