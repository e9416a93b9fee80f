// Work groups of a characterisation (work_groups.hpp): one solve() per instance serves the G
// azimuths of a (λ, θ_i) group, then the G units are fitted in parallel.
#include "work_groups.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "journal.hpp"
#include "solve_memory.hpp"
#include "plumage/conventions.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/far_field.hpp"
#include "plumage/fitter.hpp"
#include "warning_attribution.hpp"

namespace plumage {

double azimuth_jitter_rad(int n, int count, double jitter_deg) {
  if (count < 2 || jitter_deg == 0.0) return 0.0;
  return deg_to_rad(-jitter_deg + 2.0 * jitter_deg * n / (count - 1));
}

PreparedInstances prepare_instances(const SpeciesConfig& config, const CharacterizeSettings& s) {
  PreparedInstances prepared(static_cast<std::size_t>(s.instances));
  tbb::parallel_for(0, s.instances, [&](int n) {
    const CrossSection cs = config.structure->generate(static_cast<std::uint64_t>(n));
    prepared[n] = config.solver->prepare(cs, config.reflection);
  });
  return prepared;
}

namespace {

// The fits of the G units of a group from the far fields per_b[b][n] (instance n, azimuth b).
std::vector<UnitFit> fit_group(const CharacterizeSettings& s, const GroupRecord& rec, double lambda, double theta,
                               const std::vector<double>& phi_i, std::size_t pattern_count,
                               const std::vector<std::vector<FarField>>& per_b) {
  std::vector<UnitFit> fits(phi_i.size());
  const bool reference = rec.w == 0 && rec.a == static_cast<std::uint32_t>(s.grid);
  tbb::parallel_for(std::size_t{0}, phi_i.size(), [&](std::size_t b) {
    UnitInput in;
    in.lambda_nm = lambda;
    in.theta_i_rad = theta;
    in.phi_i_rad = phi_i[b];
    in.sigma = s.sigma;
    in.pattern_count = pattern_count;
    in.instances = per_b[b];
    in.want_autocorrelation = reference && b + 1 == phi_i.size();
    fits[b] = fit_unit(in);
  });
  return fits;
}

// Per (code, unit b): how many instances raised it and the worst measure, from every
// instance's sites (the same whatever thread solved which instance).
std::vector<GroupRecord::UnitWarning> unit_warnings(const std::vector<std::vector<WarningSite>>& sites,
                                                    std::size_t units) {
  std::map<std::pair<std::string, std::uint32_t>, GroupRecord::UnitWarning> by_unit;
  for (const std::vector<WarningSite>& instance : sites) {
    std::set<std::pair<std::string, std::uint32_t>> seen;  // an instance counts once per unit
    for (const WarningSite& site : instance) {
      if (site.kind != WarningSite::Item::azimuth || site.item >= units) continue;
      const auto key = std::make_pair(site.code, static_cast<std::uint32_t>(site.item + 1));
      GroupRecord::UnitWarning& u = by_unit[key];
      u.code = key.first, u.b = key.second;
      if (seen.insert(key).second) ++u.instances;
      u.worst = std::max(u.worst, site.value);
    }
  }
  std::vector<GroupRecord::UnitWarning> out;
  for (auto& [key, u] : by_unit) out.push_back(std::move(u));
  return out;
}

// A production group allocates ~150 MB of far fields (50 instances x 20 azimuths x 1424
// directions x 2 polarizations x 48 B) plus per-instance current and radiation buffers whose
// sizes change with the instance's node count; all of it is freed before the next group. With
// glibc's default thresholds much of that went back to the kernel (munmap, heap trim) and every
// group faulted fresh zeroed pages in again: clear_page was 13.5 % of the rock-dove 550 nm
// sub-grid's profile and 1.7-1.9 s of its 9 s CPU were system time (issue 26). Blocks up to
// 64 MiB now come from the heap and up to 512 MiB of freed heap are kept for reuse; the peak
// resident size is that of the largest group either way (measured: 236 -> 239-250 MB).
void retain_freed_memory() {
#if defined(__GLIBC__)
  static const bool once = [] {
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
    return true;
  }();
  (void)once;
#endif
}

}  // namespace

GroupRecord run_group(const SpeciesConfig& config, const CharacterizeSettings& s, const PreparedInstances& prepared,
                      std::size_t g, std::vector<FitDiagnostic>* diagnostics) {
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
  // sites[n]: where instance n's solve raised per-azimuth warnings (diagnostics.hpp, warn_at).
  std::vector<std::vector<WarningSite>> sites(static_cast<std::size_t>(s.instances));
  tbb::parallel_for(0, s.instances, [&](int n) {
    std::vector<double> phis = phi_i;
    const double d = azimuth_jitter_rad(n, s.instances, s.jitter_deg);
    for (double& p : phis) p += d;
    const WarningSites scope;
    auto fields = config.solver->solve(*prepared[n], lambda, theta, phis, phi_o);
    for (std::size_t b = 0; b < fields.size(); ++b) per_b[b][n] = std::move(fields[b]);
    sites[static_cast<std::size_t>(n)] = scope.sites();
  });
  rec.unit_warnings = unit_warnings(sites, phi_i.size());
  const std::vector<UnitFit> fits = fit_group(s, rec, lambda, theta, phi_i, pattern.phi_o_rad.size(), per_b);
  rec.units.resize(phi_i.size());
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

void compute_groups(const SpeciesConfig& config, const CharacterizeSettings& s, const PreparationOptions& preparation,
                    const std::vector<std::size_t>& todo, const std::filesystem::path& journal,
                    std::uintmax_t valid_bytes, const GroupCallbacks& callbacks,
                    std::vector<FitDiagnostic>* diagnostics) {
  // Codes raised while preparing (the models' one-time work, the instances) go to every group
  // this process computes.
  const RaiseCounts before_prepare = raise_counts();
  PreparedInstances prepared;
  SolvePlan plan;
  if (!todo.empty()) {
    retain_freed_memory();
    prepare_species(config, preparation);
    prepared = prepare_instances(config, s);
    // Before the solves, with the tables and the prepared instances resident: how many instances
    // the budget lets us solve at a time (solve_memory.hpp). `plumage check` runs the same plan.
    const std::size_t n_phi_o = cone_directions(s.pattern_samples, s.projected_samples);
    plan = plan_parallel_solves(config, s.lambda_nm, static_cast<std::size_t>(s.grid), n_phi_o, s.instances,
                                far_field_bytes(static_cast<double>(s.grid) * s.instances, n_phi_o), "characterize");
  }
  const std::set<std::string> prepare_codes = raised_since(before_prepare);
  JournalWriter writer(journal, s, valid_bytes);
  const std::size_t total = todo.size() * static_cast<std::size_t>(s.grid);
  if (callbacks.progress && !todo.empty()) callbacks.progress(0, total, "work units");
  std::size_t count = 0;
  for (std::size_t g : todo) {
    if (callbacks.cancelled && callbacks.cancelled())
      throw CharacterizeCancelled(s.label + ": characterisation cancelled after " + std::to_string(count) + " of " +
                                  std::to_string(todo.size()) + " groups (" + journal.string() + " resumes it)");
    const RaiseCounts before = raise_counts();
    GroupRecord record;
    run_with_plan(plan, [&] { record = run_group(config, s, prepared, g, diagnostics); });
    std::set<std::string> codes = raised_since(before);
    codes.insert(prepare_codes.begin(), prepare_codes.end());
    record.warnings.assign(codes.begin(), codes.end());
    writer.append(record);
    if (callbacks.progress) callbacks.progress(++count * static_cast<std::size_t>(s.grid), total, "work units");
  }
}

}  // namespace plumage
