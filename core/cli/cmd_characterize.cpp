// `plumage characterize CONFIG --fidelity preview|production --out x.plm`: geometry → simulate →
// fit every work unit (spec geometry-and-brdf §4.1–4.6) → assemble the FeatherMaterial (§4.7–4.8).
//
// Work is scheduled in groups (λ bin w, cos θ_i = a/G): one solve() per instance serves all G
// azimuths cos φ_i = b/G of the group (each instance with its azimuth jitter, spec §0.3), then the
// G units are fitted in parallel. Prepared instances are reused by every group. Each finished
// group is appended to a journal beside the output (fsync'ed), so a killed run resumes with only
// the groups in flight redone. `--shard i/N` and MPI ranks take the groups g ≡ i−1 (mod N);
// the material is assembled from the records alone, so every way of running writes the same bytes.
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "plumage/bench_record.hpp"
#include "characterize_records.hpp"
#include "characterize_run.hpp"
#include "plumage/charts.hpp"
#include "commands.hpp"
#include "plumage/diagnostics.hpp"
#include "grid_parse.hpp"
#include "mpi_session.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/fitter.hpp"
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

std::pair<int, int> parse_shard(const std::string& text) {
  int i = 0, n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || !in.eof() || n < 1 || i < 1 || i > n)
    throw UsageError("--shard: expected i/N with 1 <= i <= N (e.g. 2/8), got '" + text + "'");
  return {i - 1, n};
}

std::vector<DiagnosticUnit> diagnostic_units(const CharacterizeSettings& s) {
  std::uint32_t w = 0;
  for (std::size_t k = 0; k < s.lambda_nm.size(); ++k)
    if (std::abs(s.lambda_nm[k] - 550) < std::abs(s.lambda_nm[w] - 550)) w = static_cast<std::uint32_t>(k);
  const auto G = static_cast<std::uint32_t>(s.grid), h = std::max<std::uint32_t>(1, G / 2), q = std::max<std::uint32_t>(1, G / 4);
  return {{w, G, G, {}, {}, {}, 0}, {w, G, h, {}, {}, {}, 0}, {w, h, G, {}, {}, {}, 0}, {w, q, q, {}, {}, {}, 0}};
}

void write_diagnostics(const std::filesystem::path& dir, const CharacterizeSettings& s,
                       const std::vector<DiagnosticUnit>& units, const std::string& summary) {
  std::filesystem::create_directories(dir);
  LineChart chart;
  chart.title = s.label + ": simulated mean pattern U vs GGX fit on the cone (" + s.fidelity + ")";
  chart.x_label = "phi_o (deg)";
  chart.y_label = "reflectance density per rad";
  std::ostringstream csv;
  csv << std::setprecision(9) << "lambda_nm,cos_theta_i,cos_phi_i,phi_o_deg,mean_U,fit\n";
  for (const auto& d : units) {
    if (d.u.empty()) continue;  // computed by an earlier (resumed) run or another shard
    std::ostringstream panel;
    panel << std::setprecision(3) << s.lambda_nm[d.w] << " nm, cos th_i " << double(d.a) / s.grid << ", cos ph_i "
          << double(d.b) / s.grid << " (rel. L2 " << d.rel_l2 << ")";
    for (std::size_t k = 0; k < d.u.size(); ++k) {
      chart.points.push_back({panel.str(), "simulated U", rad_to_deg(d.phi_o[k]), d.u[k]});
      chart.points.push_back({panel.str(), "GGX fit", rad_to_deg(d.phi_o[k]), d.fit[k]});
      csv << s.lambda_nm[d.w] << ',' << double(d.a) / s.grid << ',' << double(d.b) / s.grid << ','
          << rad_to_deg(d.phi_o[k]) << ',' << d.u[k] << ',' << d.fit[k] << '\n';
    }
  }
  write_text_atomically(dir / "fit-patterns.csv", csv.str());
  write_text_atomically(dir / "fit-summary.txt", summary + "\n");
  if (!chart.points.empty()) draw_line_chart(chart, dir / "fit-patterns.png");
}

void run(AppContext& context, const Options& o) {
  MpiSession mpi;
  const bool root = mpi.rank() == 0;
  try {
    if (mpi.size() > 1 && !o.shard.empty()) throw UsageError("--shard and an MPI launch cannot be combined");
    const SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
    if (!config.structure) throw UsageError(o.config + ": no `structure:` section to characterise");
    const CharacterizeSettings s = make_settings(config, o);
    auto [part, parts] = o.shard.empty() ? std::pair<int, int>{mpi.rank(), mpi.size()} : parse_shard(o.shard);
    const std::filesystem::path out(o.out);
    std::filesystem::path journal = out;
    journal += mpi.size() > 1 ? ".rank" + std::to_string(part) + "of" + std::to_string(parts) + ".journal" : ".journal";

    // Resume: groups already in the journal are not recomputed.
    const JournalResume resume = read_journal_resume(journal, s);
    if (!resume.matches)
      throw UsageError(journal.string() + ": journal of a run with other settings; delete it to start over\n  journal:  " +
                       resume.fingerprint + "\n  this run: " + s.fingerprint());
    const std::set<std::size_t>& done = resume.done;
    std::vector<std::size_t> todo;
    for (std::size_t g = 0; g < s.group_count(); ++g)
      if (static_cast<int>(g % static_cast<std::size_t>(parts)) == part && !done.count(g)) todo.push_back(g);
    const bool quiet = context.quiet || !root;
    // Warnings are echoed by the root only; the other ranks' are gathered below.
    if (!root) diagnostics().set_echo(nullptr);
    if (!quiet) {
      std::cerr << s.label << ": " << s.fidelity << ", " << s.lambda_nm.size() << " wavelengths x " << s.grid << " x "
                << s.grid << " incident nodes, " << s.instances << " instances";
      if (mpi.size() > 1) std::cerr << ", " << parts << " MPI ranks";
      else if (parts > 1) std::cerr << ", shard " << part + 1 << "/" << parts;
      if (!done.empty()) std::cerr << ", resuming (" << done.size() << " groups already in " << journal.string() << ")";
      std::cerr << "\n";
    }

    const auto wall0 = std::chrono::steady_clock::now();
    const std::clock_t cpu0 = std::clock();
    auto diag = diagnostic_units(s);
    PreparationOptions preparation = context.preparation();
    if (quiet) preparation.progress = nullptr;  // other MPI ranks
    compute_groups(config, s, todo, journal, resume.valid_bytes, quiet, o.diagnostics.empty() ? nullptr : &diag,
                   preparation);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;

    // Everything this part owns, read back from its journal (the bytes that shards and ranks ship).
    JournalContents mine = read_journal(journal);
    if (!o.shard.empty()) {
      std::filesystem::rename(journal, out);  // a complete shard file
      if (!quiet) std::cerr << "wrote shard " << out.string() << " (" << mine.records.size() << " groups); combine with `plumage merge`\n";
      return;
    }
    std::string bytes;
    for (const auto& r : mine.records) bytes += serialize(r);
    const auto all = mpi.gather(bytes);
    // Every rank's warnings reach the root's stderr (the material takes its warnings from the
    // records, which carry their codes).
    const auto rank_warnings = mpi.gather(diagnostics().summary());
    if (root) {
      for (std::size_t rank = 1; rank < rank_warnings.size(); ++rank) {
        std::istringstream lines(rank_warnings[rank]);
        for (std::string line; std::getline(lines, line);) {
          const auto colon = line.find(": ");
          if (colon == std::string::npos) continue;
          warn(line.substr(0, colon), "rank " + std::to_string(rank) + ": " + line.substr(colon + 2));
        }
      }
    }
    bool ok = true;
    if (root) {
      std::vector<GroupRecord> records;
      for (const std::string& part_bytes : all) {
        // Parse the shipped records through the journal reader (same checks).
        const std::filesystem::path tmp = std::filesystem::path(out).concat(".gather.tmp");
        {
          std::ofstream f(tmp, std::ios::binary);
          f << journal_header(s) << part_bytes;
        }
        auto j = read_journal(tmp);
        std::filesystem::remove(tmp);
        for (auto& r : j.records) records.push_back(std::move(r));
      }
      const FeatherMaterial material = assemble_material(s, records);
      write_feather_material(out, material);
      const std::string summary = fit_quality_summary(s, records);
      if (!o.diagnostics.empty()) write_diagnostics(o.diagnostics, s, diag, summary);
      if (!context.quiet) {
        std::cerr << summary << "\n";
        std::cerr << "wrote " << out.string() << " (" << std::filesystem::file_size(out) << " bytes) in " << std::fixed
                  << std::setprecision(1) << wall << " s wall, " << cpu << " s CPU (this process"
                  << (mpi.size() > 1 ? ", rank 0" : "") << ", " << todo.size() << " groups computed)\n";
      }
      if (!o.record.empty()) {
        std::ostringstream md;
        md << std::fixed << "## characterize " << s.label << " (" << s.fidelity << ")\n\n"
           << s.lambda_nm.size() << " wavelengths x " << s.grid << " x " << s.grid << " incident nodes, " << s.instances
           << " instances, " << s.pattern_samples << " pattern + " << s.projected_samples << " projected directions.\n\n"
           << "| machine | command | date | wall | CPU | groups computed | file size |\n|---|---|---|---|---|---|---|\n"
           << "| " << machine_description() << " | `plumage characterize " << o.config << " --variant " << s.variant
           << " --fidelity " << s.fidelity << "` | " << today_iso() << " | " << std::setprecision(0) << wall << " s | "
           << cpu << " s | " << todo.size() << " of " << s.group_count() << " | "
           << std::setprecision(2) << std::filesystem::file_size(out) / 1e6 << " MB |\n\n" << summary << "\n";
        record_benchmark(o.record, "characterize:" + config.species + "-" + config.variant + ":" + s.fidelity, md.str());
      }
    }
    ok = mpi.broadcast(ok);
    if (ok) std::filesystem::remove(journal);
  } catch (const std::exception& e) {
    if (mpi.active()) {
      std::cerr << "rank " << mpi.rank() << ": " << e.what() << "\n";
      mpi.abort(dynamic_cast<const UsageError*>(&e) ? 2 : 1);
    }
    throw;
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
