// `plumage merge SHARD... --out x.plm`: the material from the shard files of
// `plumage characterize --shard i/N` (one per shard, any order). The result is bit-identical to a
// single run: the material is assembled from the same records by the same code.
#include <iostream>

#include "characterize_records.hpp"
#include "commands.hpp"
#include "plumage/error.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::vector<std::string> shards;
  std::string out;
};

void run(AppContext& context, const Options& o) {
  std::vector<GroupRecord> records;
  std::string fingerprint;
  for (const auto& file : o.shards) {
    JournalContents j = read_journal(file);
    const auto size = std::filesystem::file_size(file);
    if (j.valid_bytes != size)
      throw Error(file + ": damaged or unfinished shard (valid records end at byte " + std::to_string(j.valid_bytes) +
                  " of " + std::to_string(size) + ")");
    if (fingerprint.empty()) fingerprint = j.fingerprint;
    else if (j.fingerprint != fingerprint)
      throw UsageError(file + ": shard of a different characterisation\n  " + o.shards.front() + ": " + fingerprint +
                       "\n  " + file + ": " + j.fingerprint);
    for (auto& r : j.records) records.push_back(std::move(r));
  }
  const CharacterizeSettings s = CharacterizeSettings::from_fingerprint(fingerprint);
  try {
    write_feather_material(o.out, assemble_material(s, records));
  } catch (const Error& e) {
    throw Error(std::string("merge: ") + e.what());
  }
  if (!context.quiet) {
    std::cerr << fit_quality_summary(s, records) << "\n";
    std::cerr << "wrote " << o.out << " from " << o.shards.size() << " shards\n";
  }
}

}  // namespace

void add_merge_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("merge", "Combine the shards of `plumage characterize --shard i/N` into a material");
  cmd->add_option("shards", o->shards, "Shard files")->required();
  cmd->add_option("--out", o->out, "Material file to write (.plm)")->required();
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
