// The single-process core of `plumage characterize` (characterize_run.hpp), shared with
// `plumage render`, which characterises a missing material in-process.
#include "characterize_run.hpp"

#include "plumage/diagnostics.hpp"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>

#include "app_context.hpp"
#include "plumage/conventions.hpp"
#include "plumage/far_field_set.hpp"
#include "plumage/fitter.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

double jitter_rad(int n, int count, double jitter_deg) {
  if (count < 2 || jitter_deg == 0.0) return 0.0;
  return deg_to_rad(-jitter_deg + 2.0 * jitter_deg * n / (count - 1));
}

}  // namespace

// Fidelity presets. production: the spec's grid (config simulation settings: 50 λ, 20 × 20,
// 50 instances). preview: 10 instances, λ = 400, 430, …, 670 nm (10 bins of 30 nm), 10 × 10
// incident nodes; same direction sampling and fits.
CharacterizeSettings preset_settings(const SpeciesConfig& config, const std::string& fidelity, double sigma) {
  CharacterizeSettings s;
  s.label = config.species + "/" + config.variant;
  s.config_hash = config.content_hash;
  s.variant = config.variant;
  s.fidelity = fidelity;
  const auto& sim = config.simulation;
  s.pattern_samples = sim.pattern_samples;
  s.projected_samples = sim.projected_samples;
  s.jitter_deg = sim.azimuth_jitter_deg;
  s.sigma = sigma;
  s.noise_functions = 512;
  if (fidelity == "production") {
    s.instances = sim.instances;
    s.grid = sim.incident_grid;
    s.lambda_nm = sim.wavelengths_nm;
  } else {
    s.instances = 10;
    s.grid = 10;
    for (int k = 0; k < 10; ++k) s.lambda_nm.push_back(400.0 + 30.0 * k);
  }
  s.bin_width_nm = s.lambda_nm.size() > 1 ? s.lambda_nm[1] - s.lambda_nm[0] : 6.0;
  return s;
}

// One group: far fields of every instance for all G azimuths, then the G fits.
GroupRecord run_group(const SpeciesConfig& config, const CharacterizeSettings& s,
                      const std::vector<std::shared_ptr<const ScatteringSolver::Prepared>>& prepared,
                      std::size_t g, std::vector<DiagnosticUnit>* diagnostics) {
  GroupRecord rec;
  rec.w = static_cast<std::uint32_t>(g / static_cast<std::size_t>(s.grid));
  rec.a = static_cast<std::uint32_t>(g % static_cast<std::size_t>(s.grid)) + 1;
  const double lambda = s.lambda_nm[rec.w];
  const double theta = std::acos(static_cast<double>(rec.a) / s.grid);
  std::vector<double> phi_i(static_cast<std::size_t>(s.grid));
  for (int b = 1; b <= s.grid; ++b) phi_i[b - 1] = std::acos(static_cast<double>(b) / s.grid);
  const DirectionSet pattern = pattern_directions(s.pattern_samples);
  const DirectionSet projected = projected_directions(theta, s.projected_samples);
  std::vector<double> phi_o = pattern.phi_o_rad;
  phi_o.insert(phi_o.end(), projected.phi_o_rad.begin(), projected.phi_o_rad.end());

  // per_b[b][n]: far field of instance n at azimuth b.
  std::vector<std::vector<FarField>> per_b(phi_i.size(), std::vector<FarField>(static_cast<std::size_t>(s.instances)));
  tbb::parallel_for(0, s.instances, [&](int n) {
    std::vector<double> phis = phi_i;
    const double d = jitter_rad(n, s.instances, s.jitter_deg);
    for (double& p : phis) p += d;
    auto fields = config.solver->solve(*prepared[n], lambda, theta, phis, phi_o);
    for (std::size_t b = 0; b < fields.size(); ++b) per_b[b][n] = std::move(fields[b]);
  });
  rec.units.resize(phi_i.size());
  std::vector<UnitFit> fits(phi_i.size());
  const bool reference = rec.w == 0 && rec.a == static_cast<std::uint32_t>(s.grid);
  tbb::parallel_for(std::size_t{0}, phi_i.size(), [&](std::size_t b) {
    UnitInput in;
    in.lambda_nm = lambda;
    in.theta_i_rad = theta;
    in.phi_i_rad = phi_i[b];
    in.sigma = s.sigma;
    in.pattern_count = pattern.phi_o_rad.size();
    in.instances = per_b[b];
    in.want_autocorrelation = reference && b + 1 == phi_i.size();
    fits[b] = fit_unit(in);
  });
  for (std::size_t b = 0; b < fits.size(); ++b) {
    rec.units[b] = {fits[b].node, fits[b].rel_l2_eff, fits[b].rel_l2_sta, fits[b].energy};
    if (!fits[b].autocorrelation.empty()) rec.autocorrelation = fits[b].autocorrelation;
  }
  if (diagnostics) {
    for (auto& d : *diagnostics) {
      if (d.w == rec.w && d.a == rec.a) {
        d.phi_o = pattern.phi_o_rad;
        d.u = fits[d.b - 1].mean_pattern;
        d.fit = fits[d.b - 1].fit_pattern;
        d.rel_l2 = fits[d.b - 1].rel_l2_eff;
      }
    }
  }
  return rec;
}

JournalResume read_journal_resume(const std::filesystem::path& journal, const CharacterizeSettings& s) {
  JournalResume resume;
  if (!std::filesystem::exists(journal)) return resume;
  const JournalContents j = read_journal(journal);
  resume.fingerprint = j.fingerprint;
  if (j.fingerprint != s.fingerprint()) {
    resume.matches = false;
    return resume;
  }
  for (const auto& r : j.records) resume.done.insert(r.w * static_cast<std::size_t>(s.grid) + (r.a - 1));
  resume.valid_bytes = j.valid_bytes;
  return resume;
}

void compute_groups(const SpeciesConfig& config, const CharacterizeSettings& s, const std::vector<std::size_t>& todo,
                    const std::filesystem::path& journal, std::uintmax_t valid_bytes, bool quiet,
                    std::vector<DiagnosticUnit>* diagnostics, const PreparationOptions& preparation) {
  // Warning codes are attributed to groups by their raise counts before and after each group
  // (groups run one after another); those raised while preparing the instances go to every group
  // this process computes.
  auto raise_counts = [] {
    std::map<std::string, std::size_t> counts;
    for (const Warning& w : plumage::diagnostics().warnings()) counts[w.code] = w.count;
    return counts;
  };
  auto raised_since = [&](const std::map<std::string, std::size_t>& before) {
    std::set<std::string> codes;
    for (const auto& [code, count] : raise_counts()) {
      const auto it = before.find(code);
      if (it == before.end() || it->second < count) codes.insert(code);
    }
    return codes;
  };
  const auto before_prepare = raise_counts();
  std::vector<std::shared_ptr<const ScatteringSolver::Prepared>> prepared(static_cast<std::size_t>(s.instances));
  if (!todo.empty()) {
    prepare_species(config, preparation);
    tbb::parallel_for(0, s.instances, [&](int n) {
      const CrossSection cs = config.structure->generate(static_cast<std::uint64_t>(n));
      prepared[n] = config.solver->prepare(cs, config.reflection);
    });
  }
  const std::set<std::string> prepare_codes = raised_since(before_prepare);
  JournalWriter writer(journal, s, valid_bytes);
  Progress progress("work units", todo.size() * static_cast<std::size_t>(s.grid), quiet);
  std::size_t count = 0;
  for (std::size_t g : todo) {
    const auto before = raise_counts();
    GroupRecord record = run_group(config, s, prepared, g, diagnostics);
    std::set<std::string> codes = raised_since(before);
    codes.insert(prepare_codes.begin(), prepare_codes.end());
    record.warnings.assign(codes.begin(), codes.end());
    writer.append(record);
    progress.advance(++count * static_cast<std::size_t>(s.grid));
  }
}

CharacterizeRun characterize_to_file(const SpeciesConfig& config, const CharacterizeSettings& s,
                                     const std::filesystem::path& out, bool quiet,
                                     const PreparationOptions& preparation) {
  if (!config.structure) throw UsageError(config.file.string() + ": no `structure:` section to characterise");
  std::filesystem::path journal = out;
  journal += ".journal";
  JournalResume resume = read_journal_resume(journal, s);
  if (!resume.matches) {
    std::filesystem::remove(journal);  // a cache journal of other settings: start over
    resume = JournalResume{};
  }
  std::vector<std::size_t> todo;
  for (std::size_t g = 0; g < s.group_count(); ++g)
    if (!resume.done.count(g)) todo.push_back(g);
  if (!quiet) {
    std::cerr << s.label << ": characterising at " << s.fidelity << " fidelity, " << s.lambda_nm.size() << " wavelengths x "
              << s.grid << " x " << s.grid << " incident nodes, " << s.instances << " instances";
    if (!resume.done.empty()) std::cerr << ", resuming (" << resume.done.size() << " groups in " << journal.string() << ")";
    std::cerr << "\n";
  }
  CharacterizeRun run;
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  compute_groups(config, s, todo, journal, resume.valid_bytes, quiet, nullptr, preparation);
  const JournalContents all = read_journal(journal);
  write_feather_material(out, assemble_material(s, all.records));
  std::filesystem::remove(journal);
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  run.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  run.groups_computed = todo.size();
  return run;
}

}  // namespace plumage::cli
