// Characterisation of a species variant into a feather material (spec geometry-and-brdf §4.1–4.8):
// geometry → simulate every instance → fit every work unit → assemble the FeatherMaterial.
//
// Work is scheduled in groups (λ bin w, cos θ_i = a/G): one solve() per instance serves all G
// azimuths cos φ_i = b/G of the group (each instance with its azimuth jitter, spec §0.3), then the
// G units are fitted in parallel. Prepared instances are reused by every group. Each finished
// group is appended to a journal beside the output (fsync'ed), so a killed run resumes with only
// the groups in flight redone. A shard i of N and MPI rank i of N take the groups g ≡ i (mod N);
// the material is assembled from the records alone, so every way of running writes the same bytes.
//
// MPI: when the process was started by an MPI launcher (OpenMPI's OMPI_COMM_WORLD_SIZE, PMIx's
// PMIX_RANK or PMI_SIZE in the environment) and the library was built with MPI, characterize()
// with Distribution::automatic runs as one rank of the launch: rank 0 gathers the records,
// writes the material and calls the callbacks; the other ranks are silent. Otherwise no MPI
// call is made at all.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "plumage/benchmark.hpp"
#include "plumage/characterize_records.hpp"
#include "plumage/characterize_settings.hpp"
#include "plumage/error.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

// A part of the work groups: groups g with g mod count == index (0-based).
struct CharacterizeShard {
  int index = 0;
  int count = 1;
};

struct CharacterizeOptions {
  // How the models' one-time work (crystal tables) is done before simulating (prepare_species).
  PreparationOptions preparation;
  // Only this part, written as a shard file to `out` (combine with merge_shards); none: the material.
  std::optional<CharacterizeShard> shard;
  enum class Distribution {
    automatic,       // the ranks of an MPI launch when started by one, else this process
    single_process,  // this process alone, even under an MPI launcher
  };
  Distribution distribution = Distribution::automatic;
  // A journal beside the output written with other settings: refuse (ConfigError naming both
  // fingerprints) or delete it and start over (a cache).
  enum class OtherJournal { refuse, restart };
  OtherJournal other_journal = OtherJournal::refuse;
  // Pattern-vs-fit pictures and the fit-quality summary of four units go here when not empty.
  std::filesystem::path diagnostics_dir;
  // (work units done, total, "work units") after each group, rank 0 only; may be empty.
  std::function<void(std::size_t done, std::size_t total, std::string_view what)> progress;
  // Polled before each group: true stops the run with CharacterizeCancelled, the journal kept.
  std::function<bool()> cancelled;
};

// What a run will do, reported before any work (rank 0 only).
struct CharacterizePlan {
  std::size_t groups = 0;   // of the whole characterisation
  std::size_t resumed = 0;  // already in this part's journal
  std::size_t todo = 0;     // to compute now
  int part = 0, parts = 1;  // this shard or rank of how many
  bool mpi = false;         // parts are MPI ranks
  std::filesystem::path journal;
  // Damaged records skipped in the journal (one message each, naming the journal and the byte
  // offsets); their groups are among `todo`.
  std::vector<std::string> damaged_records;
};

struct CharacterizeResult {
  CharacterizePlan plan;
  bool root = true;             // rank 0 (the one that wrote the material)
  bool shard_written = false;   // `out` is a shard file
  std::size_t shard_groups = 0; // records in it
  std::string fit_summary;      // material runs, rank 0
  // Material runs, rank 0: the material's warnings, one "<code>: <where and how much>" line per
  // code (material_warning_summaries, plumage/material_warnings.hpp); "" if none.
  std::string warnings;
  double wall_s = 0, cpu_s = 0; // of this process's computation
};

class CharacterizeCancelled : public Error {
 public:
  using Error::Error;
};

// Characterises `config` with settings `s` into `out` (a .plm, or the shard file with
// options.shard), resuming from `<out>.journal` (`<out>.rank<r>of<N>.journal` for MPI ranks) when
// one of the same settings exists; the journal is removed on success. `on_plan` is called (rank
// 0) before the work starts. Bad input is a ConfigError (nothing written).
CharacterizeResult characterize(const SpeciesConfig& config, const CharacterizeSettings& s,
                                const std::filesystem::path& out, const CharacterizeOptions& options,
                                const std::function<void(const CharacterizePlan&)>& on_plan = {});

// The material from the shard files of a sharded characterisation (any order), written to `out`;
// bit-identical to a single run. Shards of different settings are a ConfigError, a damaged or
// missing shard an Error; nothing is written then.
struct MergeResult {
  CharacterizeSettings settings;
  std::string fit_summary;
  std::string warnings;  // as CharacterizeResult::warnings: one "<code>: <where and how much>" line per code
};
MergeResult merge_shards(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out);

// The record of a finished run for docs/benchmarks.md (bench_record.hpp): section id
// "characterize:<species>-<variant>:<fidelity>", `command` as typed, the output's size.
Benchmark::Report characterize_benchmark(const SpeciesConfig& config, const CharacterizeSettings& s,
                                         const CharacterizeResult& r, const std::string& command,
                                         std::uintmax_t file_bytes);

}  // namespace plumage
