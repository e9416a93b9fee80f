// plumage.characterize / plumage.merge_shards: `plumage characterize` and `plumage merge` from
// Python (characterize.hpp). The settings come from the library (characterize_settings with the
// overrides read through the command's parameter table, so the same ranges and messages); the
// progress goes to a Python callable; Ctrl-C (or an exception raised by the callable) stops the
// run between groups with the journal kept, and the next call with the same settings resumes it.
#include <optional>
#include <string>
#include <vector>

#include "plumage/atomic_file.hpp"
#include "plumage/characterize.hpp"
#include "plumage/config_document.hpp"
#include "plumage/param_table.hpp"
#include "py_material.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

// The keyword arguments as the overrides table reads them: a small YAML map of the given ones
// (the command builds the same map from its flags), so ranges and messages are the table's.
CharacterizeOverrides read_overrides(const py::dict& given) {
  std::string yaml;
  for (const auto& [key, value] : given) {
    if (value.is_none()) continue;
    const std::string name = py::str(key);
    if (name == "lambda_nm") {
      std::string list;
      for (double v : as_doubles(value, "lambda_nm")) list += (list.empty() ? "" : ", ") + format_param_number(v);
      yaml += name + ": [" + list + "]\n";
    } else {
      yaml += name + ": " + format_param_number(as_doubles(value, name).at(0)) + "\n";
    }
  }
  const auto& table = characterize_overrides_table();
  const ConfigDocument doc = ConfigDocument::parse(yaml.empty() ? "{}" : yaml, "plumage.characterize arguments");
  CharacterizeOverrides overrides = table.read(doc.root());
  doc.root().finish();
  return overrides;
}

py::dict plan_dict(const CharacterizePlan& p) {
  py::dict d;
  d["groups"] = p.groups, d["resumed"] = p.resumed, d["todo"] = p.todo;
  d["part"] = p.part, d["parts"] = p.parts, d["mpi"] = p.mpi;
  d["journal"] = p.journal;
  d["damaged_records"] = p.damaged_records;
  return d;
}

py::dict settings_dict(const CharacterizeSettings& s) {
  py::dict d;
  d["label"] = s.label, d["variant"] = s.variant, d["fidelity"] = s.fidelity;
  d["instances"] = s.instances, d["grid"] = s.grid, d["lambda_nm"] = to_array(s.lambda_nm);
  d["bin_width_nm"] = s.bin_width_nm, d["pattern_samples"] = s.pattern_samples;
  d["projected_samples"] = s.projected_samples, d["jitter_deg"] = s.jitter_deg;
  d["sigma"] = s.sigma, d["noise_functions"] = s.noise_functions;
  d["groups"] = s.group_count(), d["key"] = s.key();
  return d;
}

std::optional<CharacterizeShard> shard_of(const py::object& shard) {
  if (shard.is_none()) return std::nullopt;
  const auto pair = py::cast<std::vector<int>>(shard);
  if (pair.size() != 2 || pair[1] < 1 || pair[0] < 1 || pair[0] > pair[1])
    throw py::value_error("shard: expected (i, N) with 1 <= i <= N, as the command's --shard i/N");
  return CharacterizeShard{pair[0] - 1, pair[1]};
}

py::dict run_characterize(const Species& species, const std::filesystem::path& out, const std::string& fidelity,
                          const py::dict& overrides, const py::object& progress, const py::object& on_plan,
                          const py::object& shard, const std::string& other_journal,
                          const py::object& diagnostics, const std::string& tables) {
  // The command's checks of --out and --diagnostics (before any work).
  check_output_path(out, "out");
  check_output_not_input(out, "out", species.config.file, "species config");
  const CharacterizeSettings s =
      characterize_settings(species.config, *species.registry->registry, fidelity, read_overrides(overrides));
  CharacterizeOptions options;
  options.shard = shard_of(shard);
  if (other_journal == "restart") options.other_journal = CharacterizeOptions::OtherJournal::restart;
  else if (other_journal != "refuse") throw py::value_error("other_journal: expected 'refuse' or 'restart'");
  // None: no pictures (an empty path; Python's Path('') would be '.', the current folder).
  if (!diagnostics.is_none()) {
    options.diagnostics_dir = diagnostics.cast<std::filesystem::path>();
    check_output_directory(options.diagnostics_dir, "diagnostics");
  }
  options.preparation = preparation_from(tables, progress);  // the table build reports to it too
  options.progress = progress_from_python(progress);
  // Polled before each group: a pending Ctrl-C raises KeyboardInterrupt there (journal kept).
  options.cancelled = [] { return python_interrupt_pending(); };
  std::function<void(const CharacterizePlan&)> plan_callback;
  if (!on_plan.is_none()) {
    plan_callback = [&on_plan](const CharacterizePlan& plan) {
      py::gil_scoped_acquire gil;
      on_plan(plan_dict(plan));
    };
  }
  CharacterizeResult r;
  begin_run();
  {
    py::gil_scoped_release release;
    r = characterize(species.config, s, out, options, plan_callback);
  }
  py::dict d;
  d["settings"] = settings_dict(s);
  d["plan"] = plan_dict(r.plan);
  d["root"] = r.root, d["shard_written"] = r.shard_written, d["shard_groups"] = r.shard_groups;
  d["fit_summary"] = r.fit_summary, d["warnings"] = r.warnings;
  d["wall_s"] = r.wall_s, d["cpu_s"] = r.cpu_s;
  d["material"] = r.root && !r.shard_written ? py::cast(load_material(out)) : py::none();
  return d;
}

}  // namespace

void bind_characterize(py::module_& m) {
  m.def(
      "characterize",
      [](const std::shared_ptr<Species>& species, const std::filesystem::path& out, const std::string& fidelity,
         const py::object& instances, const py::object& grid, const py::object& lambda_nm,
         const py::object& noise_functions, const py::object& sigma, const py::object& progress,
         const py::object& on_plan, const py::object& shard, const std::string& other_journal,
         const py::object& diagnostics, const std::string& tables) {
        py::dict overrides;
        overrides["instances"] = instances, overrides["grid"] = grid, overrides["lambda_nm"] = lambda_nm;
        overrides["noise_functions"] = noise_functions, overrides["sigma"] = sigma;
        return run_characterize(*species, out, fidelity, overrides, progress, on_plan, shard, other_journal,
                                diagnostics, tables);
      },
      py::arg("species"), py::arg("out"), py::arg("fidelity") = "preview", py::kw_only(),
      py::arg("instances") = py::none(), py::arg("grid") = py::none(), py::arg("lambda_nm") = py::none(),
      py::arg("noise_functions") = py::none(), py::arg("sigma") = py::none(), py::arg("progress") = py::none(),
      py::arg("on_plan") = py::none(), py::arg("shard") = py::none(), py::arg("other_journal") = "refuse",
      py::arg("diagnostics") = py::none(), py::arg("tables") = "build",
      R"doc(`plumage characterize CONFIG --fidelity F --out OUT`: simulate and fit a species variant
(plumage.Species) into a feather material (.plm) — the same bytes as the command.

fidelity: preview | production | reference (the species file's `simulation:` keys over it).
instances, grid, lambda_nm (nm, ascending), noise_functions, sigma: the command's overrides
(None: the preset's). progress(done, total, what): work units after each group (what =
'work units'), and the models' preparation; on_plan(plan dict) before the work starts.
shard=(i, N), 1-based: only groups g ≡ i−1 (mod N), written as a shard file to `out`
(combine with merge_shards). A journal `<out>.journal` of the same settings is resumed
(plan['resumed'] groups); one of other settings raises ConfigError (other_journal='refuse') or
is discarded ('restart'). diagnostics: a folder for pattern-vs-fit pictures (None: none). tables: build |
preview | never (the command's --tables).

Ctrl-C, or an exception raised by progress, stops the run between groups: KeyboardInterrupt (or
that exception), no output file, the journal kept for the next call. Returns a dict: settings,
plan (groups, resumed, todo, part, parts, mpi, journal, damaged_records), root, shard_written,
shard_groups, fit_summary, warnings, wall_s, cpu_s, material (plumage.Material; None for a
shard). ConfigError for bad settings, OutputPathError for `out` a symlink or the species file
itself (nothing written).)doc");
  m.def(
      "merge_shards",
      [](const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out) {
        check_output_path(out, "out");  // the command's: merge X --out X would overwrite a shard
        for (const auto& shard : shards) check_output_not_input(out, "out", shard, "shard");
        MergeResult r;
        begin_run();
        {
          py::gil_scoped_release release;
          r = merge_shards(shards, out);
        }
        py::dict d;
        d["settings"] = settings_dict(r.settings);
        d["fit_summary"] = r.fit_summary, d["warnings"] = r.warnings;
        d["material"] = load_material(out);
        return d;
      },
      py::arg("shards"), py::arg("out"),
      "`plumage merge SHARDS... --out OUT`: the material from the shard files of a sharded "
      "characterisation (any order), bit-identical to a single run. ConfigError for shards of "
      "different settings, Error for a damaged or missing one, OutputPathError for `out` a shard "
      "(nothing written). Returns a dict: "
      "settings, fit_summary, warnings, material.");
}

}  // namespace plumage::python
