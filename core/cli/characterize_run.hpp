// The single-process core of `plumage characterize` as callable functions, shared by
// cmd_characterize.cpp (which adds shards, MPI, diagnostics and records) and `plumage render`
// (which characterises a missing scene material at preview fidelity in-process).
#pragma once

#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "characterize_records.hpp"
#include "plumage/scattering_solver.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

// Fidelity presets. production: the config's simulation grid (50 λ, 20 × 20, 50 instances).
// preview: 10 instances, λ = 400, 430, …, 670 nm (10 bins of 30 nm), 10 × 10 incident nodes;
// same direction sampling and fits.
CharacterizeSettings preset_settings(const SpeciesConfig& config, const std::string& fidelity, double sigma = 0.04);

// A unit of `characterize --diagnostics` (pattern vs fit of one node).
struct DiagnosticUnit {
  std::uint32_t w, a, b;
  std::vector<double> phi_o, u, fit;
  double rel_l2 = 0;
};

// One group: far fields of every instance for all G azimuths, then the G fits.
GroupRecord run_group(const SpeciesConfig& config, const CharacterizeSettings& s,
                      const std::vector<std::shared_ptr<const ScatteringSolver::Prepared>>& prepared,
                      std::size_t g, std::vector<DiagnosticUnit>* diagnostics);

// What a journal beside the output already holds: the groups done and its valid byte count.
// `matches` is false (and nothing is done) when it was written with other settings.
struct JournalResume {
  std::set<std::size_t> done;
  std::uintmax_t valid_bytes = 0;
  bool matches = true;
  std::string fingerprint;
};
JournalResume read_journal_resume(const std::filesystem::path& journal, const CharacterizeSettings& s);

// Runs the preparation step (prepare_species with `preparation`) and prepares every instance (in
// parallel; both only if there is work), then appends the groups `todo` to the journal in order,
// with progress on stderr unless quiet. Warnings raised while preparing go to every group.
void compute_groups(const SpeciesConfig& config, const CharacterizeSettings& s, const std::vector<std::size_t>& todo,
                    const std::filesystem::path& journal, std::uintmax_t valid_bytes, bool quiet,
                    std::vector<DiagnosticUnit>* diagnostics, const PreparationOptions& preparation);

struct CharacterizeRun {
  double wall_s = 0, cpu_s = 0;
  std::size_t groups_computed = 0;
};
// Every group in one process (resuming from `<out>.journal` if one of the same settings exists),
// then the material, written atomically to `out`; the journal is removed on success. Progress on
// stderr unless quiet.
CharacterizeRun characterize_to_file(const SpeciesConfig& config, const CharacterizeSettings& s,
                                     const std::filesystem::path& out, bool quiet,
                                     const PreparationOptions& preparation);

}  // namespace plumage::cli
