// The material from the shard files of a sharded characterisation (characterize.hpp): the same
// records assembled by the same code as a single run, so the bytes are identical.
#include "plumage/characterize.hpp"

#include <algorithm>

#include "plumage/atomic_file.hpp"
#include "plumage/input_file.hpp"
#include "plumage/material_warnings.hpp"

namespace plumage {

namespace {

// The same shard file named twice (by two names, or a link): refused naming both.
void refuse_same_file_twice(const std::vector<std::filesystem::path>& shards) {
  for (std::size_t a = 0; a < shards.size(); ++a) {
    check_input_file(shards[a], "shard");
    for (std::size_t b = 0; b < a; ++b) {
      std::error_code ec;
      if (std::filesystem::equivalent(shards[a], shards[b], ec))
        throw InputFileError(shards[a].string(), "the same shard file was given twice (also as " + shards[b].string() + ")");
    }
  }
}

// Every work group exactly once over all shards: a group in two shards (a copy of a shard, or
// shards of different shard counts) and groups in none (a missing shard) are refused before
// anything is written, so the material and its summary count each unit once.
void check_groups(const CharacterizeSettings& s, const std::vector<GroupRecord>& records,
                  const std::vector<std::size_t>& shard_of, const std::vector<std::filesystem::path>& shards) {
  const std::size_t groups = s.group_count(), grid = static_cast<std::size_t>(s.grid);
  std::vector<std::size_t> owner(groups, shards.size());
  for (std::size_t k = 0; k < records.size(); ++k) {
    const GroupRecord& r = records[k];
    const std::size_t g = r.w * grid + (r.a - 1);
    const std::string group = "work group (w " + std::to_string(r.w) + ", a " + std::to_string(r.a) + ")";
    if (r.a < 1 || r.a > grid || g >= groups)
      throw InputFileError(shards[shard_of[k]].string(), group + " does not fit the characterisation's grid");
    if (owner[g] != shards.size())
      throw InputFileError(shards[shard_of[k]].string(),
                           group + " is also in " + shards[owner[g]].string() +
                               ": the same shard given twice, or shards of different shard counts (--shard i/N)");
    owner[g] = shard_of[k];
  }
  std::size_t missing = 0, first = groups;
  for (std::size_t g = 0; g < groups; ++g)
    if (owner[g] == shards.size()) missing += 1, first = std::min(first, g);
  if (missing)
    throw ConfigError({"command line", 0, 0}, "shards",
                      std::to_string(missing) + " of " + std::to_string(groups) + " work groups are in none of the " +
                          std::to_string(shards.size()) + " shard files given (the first: group " + std::to_string(first) +
                          "): a shard is missing; give all N shards of --shard i/N");
}

}  // namespace

MergeResult merge_shards(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out) {
  if (shards.empty()) throw ConfigError({"command line", 0, 0}, "shards", "no shard files to merge");
  // Before reading: the output must not replace a symlink or device, nor any of the shards.
  check_output_path(out, "output");
  for (const auto& file : shards) check_output_not_input(out, "output", file, "shard");
  refuse_same_file_twice(shards);
  std::vector<GroupRecord> records;
  std::vector<std::size_t> shard_of;  // which shard each record came from
  std::string fingerprint, inputs, config_hash;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const auto& file = shards[k];
    JournalContents j = read_journal(file);
    const auto size = std::filesystem::file_size(file);
    if (!j.damaged.empty())
      throw InputFileError(file.string(), "damaged record at bytes " + std::to_string(j.damaged.front().offset) + " to " +
                                              std::to_string(j.damaged.front().end) +
                                              " (checksum or layout): recompute this shard");
    if (j.valid_bytes != size)
      throw InputFileError(file.string(), "damaged or unfinished shard (valid records end at byte " +
                                              std::to_string(j.valid_bytes) + " of " + std::to_string(size) + ")");
    if (j.format < 2)
      throw InputFileError(file.string(), "shard of an older plumage (journal format 1, no material key): recompute it");
    // The species file's bytes may differ between shards by comments alone (same key): the
    // material names the one of the shard holding the reference group (group 0), whatever the order.
    for (const GroupRecord& r : j.records)
      if (r.w == 0 && r.a == 1) config_hash = j.config_hash;
    if (fingerprint.empty()) fingerprint = j.fingerprint, inputs = j.inputs;
    else if (j.fingerprint != fingerprint)
      throw ConfigError({file.string(), 0, 0}, "",
                        "shard of a different characterisation\n  " + shards.front().string() + ": " + fingerprint +
                            "\n  " + file.string() + ": " + j.fingerprint);
    for (auto& r : j.records) records.push_back(std::move(r)), shard_of.push_back(k);
  }
  MergeResult result;
  // A header that parses as a journal but not as settings (a damaged field) is bad input of the
  // shard it came from (all shards share it; found by fuzz/fuzz_merge).
  try {
    result.settings = CharacterizeSettings::from_fingerprint(fingerprint, config_hash, inputs);
  } catch (const Error& e) {
    throw InputFileError(shards.front().string(), e.what());
  }
  check_groups(result.settings, records, shard_of, shards);
  try {
    const FeatherMaterial material = assemble_material(result.settings, records);
    write_feather_material(out, material);
    result.warnings = material_warning_summaries(material.warnings);
  } catch (const OutputPathError&) {
    throw;  // bad input, not a failed write: keeps its type (exit status 2)
  } catch (const Error& e) {
    throw Error(std::string("merge: ") + e.what());
  }
  result.fit_summary = fit_quality_summary(result.settings, records);
  return result;
}

}  // namespace plumage
