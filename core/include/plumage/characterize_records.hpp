// Work records of a characterisation: one record per (λ bin w, cos θ_i row a) group holding the
// fitted node of every cos φ_i column b = 1 … G (and, for the reference group, the noise
// autocorrelation). Records are what journals, shard files and MPI messages carry; a material is
// assembled from a complete set of them, so every way of running gives the same bytes.
// Journal and shard layout: docs/formats.md, "Characterisation journals and shards".
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/characterize_settings.hpp"
#include "plumage/feather_material.hpp"

namespace plumage {

struct UnitRecord {
  MaterialNode node;  // correlation = absolute l (not yet divided by l0)
  double rel_l2_eff = 0, rel_l2_sta = 0, energy = 0;
};

struct GroupRecord {
  std::uint32_t w = 0, a = 0;          // λ bin, cos θ_i = a / G
  std::vector<UnitRecord> units;       // b = 1 … G
  std::vector<double> autocorrelation; // reference group only (first bin, a = G: unit b = G)
  // Warning codes (plumage/diagnostics.hpp) raised while this group was computed (and while the
  // process that computed it prepared its instances), sorted. Kept in the record so that a
  // material merged from shards, MPI ranks or a resumed journal carries exactly the warnings of
  // a single run, independent of thread scheduling.
  std::vector<std::string> warnings;
  // Codes raised per incident direction (WarningSite::Item::azimuth, plumage/diagnostics.hpp,
  // e.g. approx.grazing): the units b that raised them, in how many of the instances, and the
  // worst measure of a raise (the horizon spill ratio for approx.grazing). Sorted by (code, b).
  // Records written before issue 23 have none (the material then says only how many groups).
  struct UnitWarning {
    std::string code;
    std::uint32_t b = 0;          // 1 … G
    std::uint32_t instances = 0;  // of the run's instances
    double worst = 0.0;           // may be +inf
  };
  std::vector<UnitWarning> unit_warnings;
};

// One record as bytes: u32 'PLMR', u64 body length, body, u64 FNV-1a of the body.
std::string serialize(const GroupRecord& r);

// A journal or shard file: a text header (magic, fingerprint, the species file's config hash,
// the material inputs) and appended records, each with its own checksum. A record that does not
// parse (a flipped byte) is skipped alone: reading resumes at the next record that parses whole
// with its checksum, and the skipped bytes are listed in `damaged` (its group is recomputed on
// resume; a shard with one is refused by merge). Bytes after the last good record are a torn
// tail (a run killed while appending): `valid_bytes` is where the last good record ends. A journal of format 1 (before material keys) is read with its
// fingerprint only: it matches no current settings.
struct JournalContents {
  int format = 0;
  std::string fingerprint;
  std::string config_hash;
  std::string inputs;
  std::vector<GroupRecord> records;
  std::uintmax_t valid_bytes = 0;
  // Damaged stretches skipped between good records: [offset, end) in bytes.
  struct Damage {
    std::uintmax_t offset = 0, end = 0;
  };
  std::vector<Damage> damaged;
};
JournalContents read_journal(const std::filesystem::path& file);
// The same from bytes in memory; `name` stands for the file in messages.
JournalContents parse_journal(std::string_view data, const std::string& name);
std::string journal_header(const CharacterizeSettings& s);

// Appends records, flushed and fsync'ed after each so a kill loses at most the record in flight.
class JournalWriter {
 public:
  // Opens (creating with a header, or truncating a torn tail to `valid_bytes`).
  JournalWriter(const std::filesystem::path& file, const CharacterizeSettings& s, std::uintmax_t valid_bytes);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  void append(const GroupRecord& r);

 private:
  int fd_ = -1;
  std::filesystem::path file_;
};

// The material from a complete set of records (one per group; identical duplicates allowed).
// Throws Error naming the missing or conflicting groups.
FeatherMaterial assemble_material(const CharacterizeSettings& s, const std::vector<GroupRecord>& records);

// Relative L2 fit-error summary over all units of the records (docs/validation.md "Fitting").
std::string fit_quality_summary(const CharacterizeSettings& s, const std::vector<GroupRecord>& records);

}  // namespace plumage
