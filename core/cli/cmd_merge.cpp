// `plumage merge SHARD... --out x.plm`: the material from the shard files of
// `plumage characterize --shard i/N` (one per shard, any order), through the library's
// merge_shards (plumage/characterize.hpp): bit-identical to a single run.
#include <iostream>

#include "commands.hpp"
#include "plumage/characterize.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::vector<std::string> shards;
  std::string out;
};

void run(AppContext& context, const Options& o) {
  check_output_flag("--out", o.out, o.shards, "shard");  // merge X --out X would overwrite a shard
  const std::vector<std::filesystem::path> shards(o.shards.begin(), o.shards.end());
  const MergeResult merged = merge_shards(shards, o.out);
  if (!context.quiet) {
    std::cerr << merged.fit_summary << "\n";
    std::cerr << material_warnings_report(merged.warnings);  // where and how much, per code
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
