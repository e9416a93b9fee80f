// `plumage characterize CONFIG --fidelity preview|production --out x.plm [--shard i/N]`: a species
// variant into a feather material through the library's characterisation (plumage/characterize.hpp:
// work groups, journal and resume, shards, MPI ranks under mpirun). This file parses flags, calls
// the library and prints.
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "grid_parse.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/characterize.hpp"
#include "plumage/species_config.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string config, variant, fidelity = "preview", out, shard, diagnostics, lambda_nm, record;
  int instances = 0, grid = 0, noise_functions = 0;
  double sigma = 0.04;
};

CharacterizeSettings make_settings(const SpeciesConfig& config, const Options& o) {
  CharacterizeSettings s = preset_settings(config, o.fidelity, o.sigma);
  if (o.instances > 0) s.instances = o.instances;
  if (o.grid > 0) s.grid = o.grid;
  if (o.noise_functions > 0) s.noise_functions = o.noise_functions;
  if (!o.lambda_nm.empty()) s.lambda_nm = parse_samples(o.lambda_nm, "--lambda-nm");
  if (s.instances < 2) throw UsageError("--instances: at least 2 (the statistics need a variance)");
  if (s.grid < 2) throw UsageError("--grid: at least 2 incident nodes per axis");
  if (s.lambda_nm.empty()) throw UsageError("no wavelengths");
  for (std::size_t k = 0; k < s.lambda_nm.size(); ++k) {
    if (!(s.lambda_nm[k] > 0) || (k && s.lambda_nm[k] <= s.lambda_nm[k - 1]))
      throw UsageError("--lambda-nm: wavelengths must be positive and ascending");
  }
  s.bin_width_nm = s.lambda_nm.size() > 1 ? s.lambda_nm[1] - s.lambda_nm[0] : 6.0;
  return s;
}

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
  const SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
  const CharacterizeSettings s = make_settings(config, o);
  CharacterizeOptions options;
  if (!o.shard.empty()) options.shard = parse_shard(o.shard);
  options.diagnostics_dir = o.diagnostics;
  std::unique_ptr<Progress> progress;
  options.progress = [&](std::size_t done, std::size_t total, std::string_view what) {
    if (done == 0) progress = std::make_unique<Progress>(std::string(what), total, context.quiet);  // a run starts
    else if (progress) progress->advance(done);
  };
  const std::filesystem::path out(o.out);
  const CharacterizeResult r = characterize(config, s, out, options, [&](const CharacterizePlan& plan) {
    if (!context.quiet) print_plan(s, plan);
  });
  if (!r.root) return;  // rank 0 reports for the launch
  if (r.shard_written) {
    if (!context.quiet)
      std::cerr << "wrote shard " << out.string() << " (" << r.shard_groups << " groups); combine with `plumage merge`\n";
    return;
  }
  if (!context.quiet) {
    std::cerr << r.fit_summary << "\n";
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
  cmd->add_option("--fidelity", o->fidelity,
                  "preview: 10 lambda x 10 x 10 nodes, 10 instances; production: the config's grid (50 x 20 x 20, 50 instances)")
      ->check(CLI::IsMember({"preview", "production"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Material file to write (.plm), or the shard file with --shard")->required();
  cmd->add_option("--shard", o->shard, "Compute only shard i of N (1-based, i/N); combine with `plumage merge`");
  cmd->add_option("--instances", o->instances, "Override the preset's instance count");
  cmd->add_option("--grid", o->grid, "Override the preset's incident nodes per axis");
  cmd->add_option("--lambda-nm", o->lambda_nm, "Override the preset's wavelengths (ascending list or range)");
  cmd->add_option("--noise-functions", o->noise_functions, "Noise pool size (default 512)");
  cmd->add_option("--sigma", o->sigma, "D_y spread of the lobes (spec 4.3)")->capture_default_str();
  cmd->add_option("--diagnostics", o->diagnostics, "Folder for pattern-vs-fit pictures and the fit-quality summary");
  cmd->add_option("--record", o->record, "Record the timing in this benchmarks markdown file");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
