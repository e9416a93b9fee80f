// The material from the shard files of a sharded characterisation (characterize.hpp): the same
// records assembled by the same code as a single run, so the bytes are identical.
#include "plumage/characterize.hpp"

#include "plumage/atomic_file.hpp"

namespace plumage {

MergeResult merge_shards(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out) {
  if (shards.empty()) throw ConfigError({"command line", 0, 0}, "shards", "no shard files to merge");
  // Before reading: the output must not replace a symlink or device, nor any of the shards.
  check_output_path(out, "output");
  for (const auto& file : shards) check_output_not_input(out, "output", file, "shard");
  std::vector<GroupRecord> records;
  std::string fingerprint, inputs, config_hash;
  for (const auto& file : shards) {
    JournalContents j = read_journal(file);
    const auto size = std::filesystem::file_size(file);
    if (j.valid_bytes != size)
      throw Error(file.string() + ": damaged or unfinished shard (valid records end at byte " +
                  std::to_string(j.valid_bytes) + " of " + std::to_string(size) + ")");
    if (j.format < 2) throw Error(file.string() + ": shard of an older plumage (journal format 1, no material key): recompute it");
    // The species file's bytes may differ between shards by comments alone (same key): the
    // material names the one of the shard holding the reference group (group 0), whatever the order.
    for (const GroupRecord& r : j.records)
      if (r.w == 0 && r.a == 1) config_hash = j.config_hash;
    if (fingerprint.empty()) fingerprint = j.fingerprint, inputs = j.inputs;
    else if (j.fingerprint != fingerprint)
      throw ConfigError({file.string(), 0, 0}, "",
                        "shard of a different characterisation\n  " + shards.front().string() + ": " + fingerprint +
                            "\n  " + file.string() + ": " + j.fingerprint);
    for (auto& r : j.records) records.push_back(std::move(r));
  }
  MergeResult result;
  result.settings = CharacterizeSettings::from_fingerprint(fingerprint, config_hash, inputs);
  try {
    write_feather_material(out, assemble_material(result.settings, records));
  } catch (const OutputPathError&) {
    throw;  // bad input, not a failed write: keeps its type (exit status 2)
  } catch (const Error& e) {
    throw Error(std::string("merge: ") + e.what());
  }
  result.fit_summary = fit_quality_summary(result.settings, records);
  return result;
}

}  // namespace plumage
