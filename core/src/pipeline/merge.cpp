// The material from the shard files of a sharded characterisation (characterize.hpp): the same
// records assembled by the same code as a single run, so the bytes are identical.
#include "plumage/characterize.hpp"

namespace plumage {

MergeResult merge_shards(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out) {
  if (shards.empty()) throw ConfigError({"command line", 0, 0}, "shards", "no shard files to merge");
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
  } catch (const Error& e) {
    throw Error(std::string("merge: ") + e.what());
  }
  result.fit_summary = fit_quality_summary(result.settings, records);
  return result;
}

}  // namespace plumage
