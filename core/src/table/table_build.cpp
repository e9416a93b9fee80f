// build_table_file (plumage/table_build.hpp).
#include "plumage/table_build.hpp"

#include <algorithm>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/param_table.hpp"

namespace plumage {

namespace {

bool declares(const PluginRegistry& registry, const std::string& builder, std::string_view name) {
  const PluginRegistry::Entry* entry = registry.find(TableBuilder::plugin_kind, builder);
  if (!entry) return false;
  return std::any_of(entry->info.params.begin(), entry->info.params.end(),
                     [&](const ParamSpec& spec) { return spec.name == name; });
}

// Every warning of the run (plumage/diagnostics.hpp), also those raised outside the builder;
// codes the builder already wrote into its notes ("WARNING: … [code]") are not repeated.
void append_run_warnings(std::string& notes) {
  std::string extra;
  for (const Warning& w : diagnostics().warnings()) {
    if (notes.find("[" + w.code + "]") != std::string::npos) continue;
    extra += "; WARNING: " + w.message + (w.count > 1 ? " (raised " + std::to_string(w.count) + " times)" : "") + " [" +
             w.code + "]";
  }
  if (!extra.empty()) notes += notes.empty() ? extra.substr(2) : extra;
}

}  // namespace

TableBuildResult build_table_file(const TableBuildRequest& request, const PluginRegistry& registry,
                                  const TableBuilder::Progress& progress) {
  // Output paths before any work: the table, its checkpoint, never the crystal file itself.
  check_output_path(request.out, "output");
  check_output_path(request.out.string() + ".partial", "checkpoint");
  check_output_not_input(request.out, "output", request.crystal_config, "crystal config");
  const Limits wavelengths = Limits::wavelength_nm();
  for (const auto& [flag, value] : {std::pair{"--lambda-min", request.lambda_min_nm}, std::pair{"--lambda-max", request.lambda_max_nm}}) {
    if (!wavelengths.admits(value))
      throw ConfigError({flag, 0, 0}, "", "wavelength " + format_param_number(value) + " nm is out of range: must be " + wavelengths.describe());
  }
  const CrystalCell cell = load_crystal_cell(request.crystal_config);
  const TableGridSize preset = request.fidelity == "preview" ? kPreviewTableGrid : kProductionTableGrid;
  const TableGridSize grid{request.grid.n_lambda > 0 ? request.grid.n_lambda : preset.n_lambda,
                           request.grid.n_theta > 0 ? request.grid.n_theta : preset.n_theta,
                           request.grid.n_phi > 0 ? request.grid.n_phi : preset.n_phi};
  std::ostringstream params;
  params << "fidelity: " << request.fidelity << "\n";
  if (request.resolution_nm) params << "resolution_nm: " << format_param_number(*request.resolution_nm) << "\n";
  if (request.k_step_per_um) params << "k_step_per_um: " << format_param_number(*request.k_step_per_um) << "\n";
  const std::filesystem::path partial = request.out.string() + ".partial";
  if (request.restart) std::filesystem::remove(partial);
  const bool resumable = declares(registry, request.builder, "checkpoint");
  if (resumable) params << "checkpoint: \"" << partial.string() << "\"\n";
  const ConfigDocument doc = ConfigDocument::parse(params.str(), "table build options");
  auto builder = registry.create_named<TableBuilder>(request.builder, doc.root(), registry.context());
  ReflectionTable table = builder->build(
      cell, TableGrid::uniform(request.lambda_min_nm, request.lambda_max_nm, grid.n_lambda, grid.n_theta, grid.n_phi),
      progress);
  table.metadata().config_hash = ConfigDocument::load(request.crystal_config).content_hash();  // of the file's bytes
  append_run_warnings(table.metadata().notes);
  table.save(request.out.string());
  if (resumable) std::filesystem::remove(partial);
  return {cell.name, grid, table.metadata().resolution_nm, table.metadata().notes};
}

}  // namespace plumage
