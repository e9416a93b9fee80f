// check_config_file (plumage/config_check.hpp): each kind of configuration loaded by the loader its
// command uses, so that `plumage check` and a run agree on what is valid. Every unit that can fail
// on its own (a species variant, a scene's feather material, a crystal's builder section) is
// loaded in turn and its error kept, so that one run of check reports every error of the file.
#include "plumage/config_check.hpp"
#include "plumage/input_file.hpp"

#include <algorithm>
#include <functional>
#include <optional>

#include "plumage/comparison.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "pipeline/solve_memory.hpp"
#include "plumage/error.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/render_job.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "plumage/table_build.hpp"
#include "plumage/table_builder.hpp"

namespace plumage {

namespace {

// Runs `step`, keeping a bad-input error (ConfigError, PluginError, a damaged input file the config
// names, e.g. an imported .xsec) in `c.errors` once; returns
// whether it succeeded. Faults (anything else) propagate: check itself failed.
bool collect(ConfigCheck& c, const std::function<void()>& step) {
  auto keep = [&c](const std::string& message) {
    if (std::find(c.errors.begin(), c.errors.end(), message) == c.errors.end()) c.errors.push_back(message);
  };
  try {
    step();
    return true;
  } catch (const ConfigError& e) {
    keep(e.what());
  } catch (const PluginError& e) {
    keep(e.what());
  } catch (const MemoryBudgetError& e) {
    keep(e.what());
  } catch (const InputFileError& e) {
    keep(e.what());
  }
  return false;
}

// The memory of the run's solves, as `simulate` and `characterize` plan them before any work
// (solve_memory.hpp: instance 0 at the shortest and the longest wavelength, the incident grid's
// azimuths per solve, the pattern's and projected outgoing directions, a characterisation group's
// far fields): refused when a single solve and those do not fit; a note when fewer instances
// than threads can be solved at a time.
void check_solver_memory(const SpeciesConfig& config) {
  const SimulationSettings& sim = config.simulation;
  const std::size_t n_phi_o = cone_directions(sim.pattern_samples, sim.projected_samples);
  plan_parallel_solves(config, sim.wavelengths_nm, static_cast<std::size_t>(sim.incident_grid), n_phi_o, sim.instances,
                       far_field_bytes(static_cast<double>(sim.incident_grid) * sim.instances, n_phi_o), "check");
}

// Every variant by name (the default too, which load_species_config checks against `variants:`
// whichever is asked for), each with the structure the commands need.
void check_species(const std::filesystem::path& file, const PluginRegistry& registry, ConfigCheck& c) {
  c.summary = "species";
  std::vector<std::string> variants;
  if (!collect(c, [&] { variants = species_variants(file); })) return;
  if (!variants.empty()) c.summary += ", " + std::to_string(variants.size()) + " variants";
  if (variants.empty()) variants.push_back("");
  for (const auto& v : variants) {
    collect(c, [&] {
      const SpeciesConfig config = load_species_config(file, registry, v);
      required_structure(config);
      check_solver_memory(config);
      const std::string work = pending_preparation(config);
      if (!work.empty()) c.to_prepare.push_back((v.empty() ? "" : v + ": ") + work);
    });
  }
}

// The scene is created as `plumage render` creates it (the renderer's own table checks its
// section), and each feather material's species file must load with its variant; an error there
// points at the scene's material entry as well as into the species file.
void check_scene(const std::filesystem::path& file, const PluginRegistry& registry, ConfigCheck& c) {
  collect(c, [&] {
    const RenderJob job(file, {}, registry);
    const SceneConfig& scene = job.config();
    std::size_t species_checked = 0;
    for (const auto& request : scene.feather_requests) {
      if (!request || request->species_config.empty()) continue;
      collect(c, [&] {
        try {
          required_structure(load_species_config(request->species_config.string(), registry, request->variant));
        } catch (const Error& e) {
          throw ConfigError(request->where, "species", std::string("the species config does not load: ") + e.what());
        }
      });
      ++species_checked;
    }
    c.summary = "scene " + scene.name + ", " + std::to_string(scene.views.size()) + " view(s), " +
                std::to_string(scene.materials.size()) + " materials, " + std::to_string(species_checked) +
                " species checked";
  });
}

// A crystal cell and each table builder's own section of it (CrystalCell::builder_sections).
void check_crystal(const std::filesystem::path& file, const PluginRegistry& registry, ConfigCheck& c) {
  collect(c, [&] {
    const CrystalCell cell = load_crystal_cell(file);
    c.summary = "crystal " + cell.name;
    for (const std::string& section : check_builder_sections(cell, registry)) c.summary += ", " + section + " section checked";
    // The memory of `plumage table build` at its defaults (production grid, 400-700 nm), as the
    // builder refuses it before any run (TableBuilder::estimate_memory).
    const TableBuildRequest defaults;
    const TableGrid grid = TableGrid::uniform(defaults.lambda_min_nm, defaults.lambda_max_nm, kProductionTableGrid.n_lambda,
                                              kProductionTableGrid.n_theta, kProductionTableGrid.n_phi);
    for (const auto& [name, section] : cell.builder_sections) {
      const MemoryEstimate e =
          registry.create_named<TableBuilder>(name, ParamView{}, registry.context())->estimate_memory(cell, grid);
      if (!e.parts.empty()) check_memory(e);
    }
  });
}

}  // namespace

ConfigCheck check_config_file(const std::filesystem::path& file, const PluginRegistry& registry) {
  ConfigCheck c;
  std::optional<ConfigDocument> doc;
  if (!collect(c, [&] { doc = ConfigDocument::load(file); })) return c;
  const ParamView root = doc->root();
  // `comparison` before `species`, which a comparison names too.
  if (root.has("comparison")) {
    c.kind = "comparison";
    collect(c, [&] { c.summary = check_comparison_config(file, registry); });
  } else if (root.has("species")) {
    c.kind = "species";
    check_species(file, registry, c);
  } else if (root.has("crystal")) {
    c.kind = "crystal";
    check_crystal(file, registry, c);
  } else if (root.has("scene") || root.has("objects")) {
    c.kind = "scene";
    check_scene(file, registry, c);
  } else {
    c.errors.push_back(ConfigError(root.mark(), "",
                                   "not a plumage configuration: expected a top-level 'species', 'crystal', "
                                   "'scene' or 'comparison' key")
                           .what());
  }
  return c;
}

}  // namespace plumage
