// The characterisation driver (characterize.hpp): resume, the groups of this part, then either a
// shard file or the records of every rank assembled into the material on rank 0.
#include "plumage/characterize.hpp"


#include <chrono>
#include <ctime>
#include <iostream>

#include "fit_report.hpp"
#include "journal.hpp"
#include "mpi_distribution.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/material_warnings.hpp"
#include "records.hpp"
#include "warning_attribution.hpp"
#include "work_groups.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

fs::path journal_path(const fs::path& out, const Ranks& ranks) {
  fs::path journal = out;
  journal += ranks.size() > 1 ? ".rank" + std::to_string(ranks.rank()) + "of" + std::to_string(ranks.size()) + ".journal"
                              : ".journal";
  return journal;
}

// Which groups this part computes and what its journal already holds.
struct Part {
  CharacterizePlan plan;
  std::vector<std::size_t> todo;
  std::uintmax_t valid_bytes = 0;
};

Part plan_part(const CharacterizeSettings& s, const fs::path& out, const CharacterizeOptions& o, const Ranks& ranks) {
  if (ranks.size() > 1 && o.shard)
    throw ConfigError({"command line", 0, 0}, "shard", "a shard and an MPI launch cannot be combined");
  Part p;
  p.plan.mpi = ranks.size() > 1;
  p.plan.part = o.shard ? o.shard->index : ranks.rank();
  p.plan.parts = o.shard ? o.shard->count : ranks.size();
  if (p.plan.parts < 1 || p.plan.part < 0 || p.plan.part >= p.plan.parts)
    throw ConfigError({"command line", 0, 0}, "shard", "shard " + std::to_string(p.plan.part + 1) + " of " +
                                                           std::to_string(p.plan.parts) + " does not exist");
  p.plan.journal = journal_path(out, ranks);
  JournalResume resume = read_journal_resume(p.plan.journal, s);
  if (!resume.matches) {
    if (o.other_journal == CharacterizeOptions::OtherJournal::refuse)
      throw ConfigError({p.plan.journal.string(), 0, 0}, "",
                        "journal of a run with other settings; delete it to start over\n  journal:  " +
                            resume.fingerprint + "\n  this run: " + s.fingerprint());
    fs::remove(p.plan.journal);  // a cache journal of other settings: start over
    resume = JournalResume{};
  }
  for (std::size_t g = 0; g < s.group_count(); ++g)
    if (static_cast<int>(g % static_cast<std::size_t>(p.plan.parts)) == p.plan.part && !resume.done.count(g))
      p.todo.push_back(g);
  p.plan.groups = s.group_count();
  p.plan.resumed = resume.done.size();
  p.plan.todo = p.todo.size();
  p.plan.damaged_records = resume.damaged;
  p.valid_bytes = resume.valid_bytes;
  return p;
}

// Rank 0: every rank's records (the bytes its journal holds), assembled and written.
void write_material(const CharacterizeSettings& s, const fs::path& out, const std::vector<std::string>& parts,
                    const CharacterizeOptions& o, std::vector<FitDiagnostic>& diagnostics, CharacterizeResult& result) {
  std::vector<GroupRecord> records;
  for (std::size_t rank = 0; rank < parts.size(); ++rank) {
    for (auto& r : parse_records(parts[rank], "records of rank " + std::to_string(rank))) records.push_back(std::move(r));
  }
  const FeatherMaterial material = assemble_material(s, records);
  write_feather_material(out, material);
  result.fit_summary = fit_quality_summary(s, records);
  result.warnings = material_warning_summaries(material.warnings);
  if (!o.diagnostics_dir.empty()) write_fit_diagnostics(o.diagnostics_dir, s, diagnostics, result.fit_summary);
}

CharacterizeResult run(const SpeciesConfig& config, const CharacterizeSettings& s, const fs::path& out,
                       const CharacterizeOptions& o, const std::function<void(const CharacterizePlan&)>& on_plan,
                       const Ranks& ranks) {
  const Part part = plan_part(s, out, o, ranks);
  CharacterizeResult result;
  result.plan = part.plan;
  result.root = ranks.rank() == 0;
  // Warnings are echoed by rank 0 only; the other ranks' are relayed to it below.
  if (!result.root) diagnostics().set_echo(nullptr);
  if (result.root && on_plan) on_plan(part.plan);

  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  std::vector<FitDiagnostic> diagnostics = fit_diagnostic_units(s);
  GroupCallbacks callbacks{result.root ? o.progress : nullptr, o.cancelled};
  PreparationOptions preparation = o.preparation;
  if (!result.root) preparation.progress = nullptr;  // rank 0 reports the preparation step
  compute_groups(config, s, preparation, part.todo, part.plan.journal, part.valid_bytes, callbacks,
                 o.diagnostics_dir.empty() ? nullptr : &diagnostics);
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  result.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;

  // Everything this part owns, read back from its journal (the bytes that shards and ranks ship).
  const JournalContents mine = read_journal(part.plan.journal);
  if (o.shard) {
    check_output_path(out);  // rename(2) would replace a symlink or device put there meanwhile
    fs::rename(part.plan.journal, out);  // a complete shard file
    result.shard_written = true;
    result.shard_groups = mine.records.size();
    return result;
  }
  std::string bytes;
  for (const auto& r : mine.records) bytes += serialize(r);
  const auto all = ranks.gather(bytes);
  // Every rank's warnings reach rank 0's stderr (the material takes its warnings from the
  // records, which carry their codes).
  const auto rank_warnings = ranks.gather(plumage::diagnostics().summary());
  if (result.root) {
    for (std::size_t rank = 1; rank < rank_warnings.size(); ++rank) relay_rank_warnings(static_cast<int>(rank), rank_warnings[rank]);
    write_material(s, out, all, o, diagnostics, result);
  }
  if (ranks.broadcast(true)) fs::remove(part.plan.journal);
  return result;
}

}  // namespace

CharacterizeResult characterize(const SpeciesConfig& config, const CharacterizeSettings& s, const fs::path& out,
                                const CharacterizeOptions& options,
                                const std::function<void(const CharacterizePlan&)>& on_plan) {
  required_structure(config);
  // Output paths before any work: never replace a symlink, device or folder, nor the species file.
  check_output_path(out, "output");
  check_output_not_input(out, "output", config.file, "species config");
  check_output_directory(options.diagnostics_dir, "diagnostics folder");
  const Ranks& ranks =
      options.distribution == CharacterizeOptions::Distribution::automatic ? launch_ranks() : single_rank();
  try {
    return run(config, s, out, options, on_plan, ranks);
  } catch (const std::exception& e) {
    // One rank's failure ends the launch (the others would wait in the gather forever).
    if (ranks.active()) {
      std::cerr << "rank " << ranks.rank() << ": " << e.what() << "\n";
      ranks.abort(dynamic_cast<const ConfigError*>(&e) || dynamic_cast<const OutputPathError*>(&e) ? 2 : 1);
    }
    throw;
  }
}

}  // namespace plumage
