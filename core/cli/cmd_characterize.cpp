// `plumage characterize CONFIG --fidelity preview|production --out x.plm [--shard i/N]`: a species
// variant into a feather material through the library's characterisation (plumage/characterize.hpp:
// work groups, journal and resume, shards, MPI ranks under mpirun). This file parses flags, calls
// the library and prints.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "characterize_flags.hpp"
#include "commands.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/characterize.hpp"
#include "plumage/fidelity.hpp"
#include "plumage/species_config.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string config, variant, fidelity = "preview", out, shard, diagnostics, record;
  OverrideFlags overrides;  // flag values by parameter name (as typed)
};

CharacterizeShard parse_shard(const std::string& text) {
  int i = 0, n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || !in.eof() || n < 1 || i < 1 || i > n)
    throw UsageError("--shard: expected i/N with 1 <= i <= N (e.g. 2/8), got '" + text + "'");
  return {i - 1, n};
}

void print_plan(const CharacterizeSettings& s, const CharacterizePlan& plan) {
  std::cerr << s.label << ": " << s.fidelity << ", " << s.lambda_nm.size() << " wavelengths x " << s.grid << " x "
            << s.grid << " incident nodes, " << s.instances << " instances";
  if (plan.mpi) std::cerr << ", " << plan.parts << " MPI ranks";
  else if (plan.parts > 1) std::cerr << ", shard " << plan.part + 1 << "/" << plan.parts;
  if (plan.resumed) std::cerr << ", resuming (" << plan.resumed << " groups already in " << plan.journal.string() << ")";
  std::cerr << "\n";
}

void run(AppContext& context, const Options& o) {
  check_output_flag("--out", o.out, {o.config}, "species config");
  check_output_flag("--record", o.record, {o.config}, "species config");
  check_output_folder_flag("--diagnostics", o.diagnostics);
  const SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
  const CharacterizeSettings s = characterize_settings(config, context.registry(), o.fidelity, read_characterize_overrides(o.overrides));
  CharacterizeOptions options;
  if (!o.shard.empty()) options.shard = parse_shard(o.shard);
  options.diagnostics_dir = o.diagnostics;
  options.preparation = context.preparation();  // --tables, with progress unless quiet
  std::unique_ptr<Progress> progress;
  options.progress = [&](std::size_t done, std::size_t total, std::string_view what) {
    if (done == 0) progress = std::make_unique<Progress>(std::string(what), total, context.quiet);  // a run starts
    else if (progress) progress->advance(done);
  };
  const std::filesystem::path out(o.out);
  const CharacterizeResult r = characterize(config, s, out, options, [&](const CharacterizePlan& plan) {
    if (!context.quiet) print_plan(s, plan);
    for (const std::string& damage : plan.damaged_records) std::cerr << "warning: " << damage << "\n";
  });
  if (!r.root) return;  // rank 0 reports for the launch
  if (r.shard_written) {
    if (!context.quiet)
      std::cerr << "wrote shard " << out.string() << " (" << r.shard_groups << " groups); combine with `plumage merge`\n";
    return;
  }
  if (!context.quiet) {
    std::cerr << r.fit_summary << "\n";
    // Where and how much, per code (the first raise of each was printed as it happened).
    std::cerr << material_warnings_report(r.warnings);
    std::cerr << "wrote " << out.string() << " (" << std::filesystem::file_size(out) << " bytes) in " << std::fixed
              << std::setprecision(1) << r.wall_s << " s wall, " << r.cpu_s << " s CPU (this process"
              << (r.plan.mpi ? ", rank 0" : "") << ", " << r.plan.todo << " groups computed)\n";
  }
  if (!o.record.empty()) {
    const std::string command = "plumage characterize " + o.config + " --variant " + s.variant + " --fidelity " + s.fidelity;
    const Benchmark::Report record = characterize_benchmark(config, s, r, command, std::filesystem::file_size(out));
    record_benchmark(o.record, record.id, record.markdown);
  }
}

}  // namespace

void add_characterize_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("characterize", "Simulate and fit a species variant into a feather material (.plm)");
  cmd->add_option("config", o->config, "Species YAML file")->required();
  cmd->add_option("--variant", o->variant, "Variant (default: the file's)");
  std::string presets;
  for (const FidelityPreset& p : fidelity_presets()) presets += std::string(presets.empty() ? "" : "; ") + std::string(p.name) + ": " + std::string(p.summary);
  cmd->add_option("--fidelity", o->fidelity, presets + " (with the species file's `simulation:` keys over it)")
      ->check(CLI::IsMember(fidelity_names()))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Material file to write (.plm), or the shard file with --shard")->required();
  cmd->add_option("--shard", o->shard, "Compute only shard i of N (1-based, i/N); combine with `plumage merge`");
  add_characterize_override_flags(*cmd, o->overrides);
  cmd->add_option("--diagnostics", o->diagnostics, "Folder for pattern-vs-fit pictures and the fit-quality summary");
  cmd->add_option("--record", o->record, "Record the timing in this benchmarks markdown file");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
