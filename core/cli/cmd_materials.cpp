// `plumage materials SPECIES.yaml... [--fidelity F] [--into DIR] [--grid G ...]` (issue 26, behind
// `make materials`): flags and printing over make_materials (plumage/material_batch.hpp).
#include <iostream>
#include <memory>

#include "characterize_flags.hpp"
#include "commands.hpp"
#include "plumage/fidelity.hpp"
#include "plumage/material_batch.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::vector<std::string> species;
  std::string fidelity = "production", into = "build/materials";
  OverrideFlags overrides;
};

void run(AppContext& context, const Options& o) {
  check_output_folder_flag("--into", o.into);
  MaterialStoreOptions store_options;
  store_options.directory = o.into;
  store_options.overrides = read_characterize_overrides(o.overrides);
  store_options.preparation = context.preparation();  // --tables
  std::unique_ptr<Progress> progress;
  store_options.progress = [&](std::size_t done, std::size_t total, std::string_view what) {
    if (done == 0) progress = std::make_unique<Progress>(std::string(what), total, context.quiet);
    else if (progress) progress->advance(done);
  };
  if (!context.quiet) store_options.status = [](std::string_view line) {
    if (explains_characterisation(line)) std::cerr << "  " << line << "\n";
  };
  const MaterialStore store(context.registry(), store_options);
  std::vector<std::filesystem::path> files(o.species.begin(), o.species.end());
  const auto on_start = [&](const MaterialBatchItem& item) {
    if (!context.quiet) std::cerr << material_batch_item_tag(item) << ": looking up " << item.file.string() << "\n";
  };
  const auto on_item = [](const MaterialBatchItem& item) { std::cout << material_batch_item_line(item) << std::endl; };
  const MaterialBatchSummary sum = make_materials(store, context.registry(), files, o.fidelity, on_start, on_item);
  std::cout << material_batch_summary_line(sum, o.fidelity, o.into) << std::endl;
}

}  // namespace

void add_materials_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("materials",
                                 "Characterise every variant of species files into a materials folder (skips current ones)");
  cmd->add_option("species", o->species, "Species YAML files")->required();
  cmd->add_option("--fidelity", o->fidelity, "Fidelity preset of every material")
      ->check(CLI::IsMember(fidelity_names()))
      ->capture_default_str();
  cmd->add_option("--into", o->into, "Folder of the materials (as `render --materials`)")->capture_default_str();
  add_characterize_override_flags(*cmd, o->overrides);
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
