// `plumage geometry CONFIG [--variant V] [--instances N] [--first K] --out DIR [--stats]`:
// procedural barbule cross sections of a species (or validation shape), each written as
// DIR/<species>-<variant>-<n>.xsec (text format, docs/formats.md), .svg and .png (exact regions
// above, reduced model below, on one x axis). Every instance is checked for geometric validity before anything is
// written; files are written atomically.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/instance_geometry.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string config;
  std::string variant;
  int instances = 1;
  long long first = 0;
  std::string out;
  bool stats = false;
  CrossSectionPictures pictures;
  bool allow_invalid = false;
};

void run(AppContext& context, const Options& o) {
  if (o.instances < 1) throw UsageError("--instances must be at least 1");
  if (o.first < 0) throw UsageError("--first must be >= 0");
  if (o.out.empty() && !o.stats) throw UsageError("give --out DIR and/or --stats");
  check_output_folder_flag("--out", o.out);
  SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
  context.warn_about_problems();
  required_structure(config);
  const std::string stem = config.species + (config.variant.empty() ? "" : "-" + config.variant);
  GeometryStatistics stats;
  std::vector<CrossSection> sections;
  for (int k = 0; k < o.instances; ++k) {
    const auto index = static_cast<std::uint64_t>(o.first + k);
    CheckedInstance instance = generate_checked(*config.structure, index);
    if (!instance.problems.empty() && o.allow_invalid) {
      for (const auto& p : instance.problems)
        if (!context.quiet) std::cerr << "warning: instance " << index << ": " << p << "\n";
    } else {
      refuse_invalid_instance(instance, stem, index);
    }
    const CrossSection& cs = instance.section;
    if (!context.quiet) {
      std::cerr << "geometry: " << stem << " instance " << index << " (" << k + 1 << "/" << o.instances
                << "): " << cs.top.size() << " top vertices, " << cs.regions.size() << " regions, " << std::fixed
                << std::setprecision(2) << instance.generate_ms << " ms" << std::defaultfloat << "\n";
    }
    if (o.stats) stats.add(cs);
    if (!o.out.empty()) sections.push_back(std::move(instance.section));
  }
  // Everything generated and valid: now write.
  if (!o.out.empty()) {
    for (const CrossSection& cs : sections) check_cross_section_pictures(cs, o.pictures);
    create_output_directory(o.out, "--out");
    for (const CrossSection& cs : sections) {
      write_cross_section_files(cs, std::filesystem::path(o.out) / (stem + "-" + std::to_string(cs.instance)), o.pictures);
    }
    if (!context.quiet) std::cerr << "geometry: wrote " << sections.size() << " instance(s) to " << o.out << "\n";
  }
  if (o.stats) std::cout << stats.report(stem, o.instances);
}

}  // namespace

void add_geometry_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("geometry", "Generate barbule cross sections of a species config");
  cmd->add_option("config", o->config, "Species or validation-shape YAML file")->required();
  cmd->add_option("--variant", o->variant, "Colour variant (default: the file's `variant`)");
  cmd->add_option("--instances", o->instances, "Number of instances")->capture_default_str();
  cmd->add_option("--first", o->first, "Index of the first instance")->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder (.xsec text + .svg per instance)");
  cmd->add_flag("--stats", o->stats, "Print measured widths, stacks, roughness and correlation length");
  cmd->add_flag("!--no-svg", o->pictures.svg, "Do not write SVG pictures");
  cmd->add_flag("!--no-png", o->pictures.png, "Do not write PNG pictures");
  cmd->add_flag("--allow-invalid", o->allow_invalid, "Write instances that fail the validity check (debugging)");
  cmd->add_option("--window-um", o->pictures.window_um, "SVG: draw only the central window of this width (um)");
  cmd->add_option("--pixels-per-um", o->pictures.pixels_per_um, "SVG: scale")->capture_default_str();
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
