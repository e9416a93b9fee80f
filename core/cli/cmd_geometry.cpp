// `plumage geometry CONFIG [--variant V] [--instances N] [--first K] --out DIR [--stats]`:
// procedural barbule cross sections of a species (or validation shape), each written as
// DIR/<species>-<variant>-<n>.xsec (text format, docs/formats.md), .svg and .png (exact regions
// above, reduced model below, on one x axis). Every instance is checked for geometric validity before anything is
// written; files are written atomically.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "commands.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/cross_section_io.hpp"
#include "plumage/geometry.hpp"
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
  bool svg = true;
  bool png = true;
  bool allow_invalid = false;
  double window_um = 0.0;
  double pixels_per_um = 50.0;
};

struct Stats {
  std::vector<double> width_um, thickness_um, rough_lo, rough_hi, corr_um, regularity_lo, regularity_hi;
  std::vector<double> diameters;
  std::map<std::string, int> roles;
  // Mean stack over central nodes: per layer index, sum of thickness and count.
  std::vector<std::pair<std::string, std::vector<double>>> layers;
  int vertices = 0;
};

void accumulate(Stats& st, const CrossSection& cs) {
  st.width_um.push_back(cs.width_nm() / 1000.0);
  // Thickness at the centre: top minus bottom at x = 0.
  st.thickness_um.push_back((z_at(cs.top, 0.0) - z_at(cs.bottom, 0.0)) / 1000.0);
  if (!cs.top_roughness_nm.empty()) {
    const auto [lo, hi] = std::minmax_element(cs.top_roughness_nm.begin(), cs.top_roughness_nm.end());
    st.rough_lo.push_back(*lo);
    st.rough_hi.push_back(*hi);
    std::vector<double> xs(cs.top.size());
    for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = cs.top[i].x;
    double step = 0.0;
    const auto c = circular_autocovariance(xs, cs.top_roughness_nm, 2048, 1024, step);
    st.corr_um.push_back(gaussian_correlation_length(c, step) / 1000.0);
  }
  if (cs.crystal && !cs.crystal->regularity.empty()) {
    const auto [lo, hi] = std::minmax_element(cs.crystal->regularity.begin(), cs.crystal->regularity.end());
    st.regularity_lo.push_back(*lo);
    st.regularity_hi.push_back(*hi);
  }
  for (const Disc& d : cs.melanosomes) st.diameters.push_back(d.diameter_nm);
  for (const Region& r : cs.regions) st.roles[std::string(role_name(r.role))] += r.members;
  st.vertices += static_cast<int>(cs.top.size());
  if (cs.layered) {
    const double quarter = 0.25 * cs.width_nm();
    for (std::size_t i = 0; i < cs.top.size(); ++i) {
      if (std::abs(cs.top[i].x) > quarter) continue;
      const LayerProfile p = layer_profile_at(cs, i);
      for (std::size_t j = 0; j < p.layers.size(); ++j) {
        if (j >= st.layers.size()) st.layers.push_back({p.layers[j].material.name(), {}});
        st.layers[j].second.push_back(p.layers[j].thickness_nm);
      }
    }
  }
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

void print_stats(const Stats& st, const std::string& label, int n) {
  auto range = [](const std::vector<double>& v) {
    std::ostringstream o;
    if (v.empty()) return std::string("-");
    o << std::setprecision(4) << *std::min_element(v.begin(), v.end()) << " .. "
      << *std::max_element(v.begin(), v.end()) << " (mean " << mean(v) << ")";
    return o.str();
  };
  std::cout << "statistics of " << n << " instance(s) of " << label << "\n";
  std::cout << "  width (um)                    " << range(st.width_um) << "\n";
  std::cout << "  thickness at x = 0 (um)       " << range(st.thickness_um) << "\n";
  if (!st.rough_lo.empty()) {
    std::cout << "  top roughness min (nm)        " << range(st.rough_lo) << "\n";
    std::cout << "  top roughness max (nm)        " << range(st.rough_hi) << "\n";
    std::cout << "  correlation length tau (um)   " << range(st.corr_um)
              << "   [C(dx) ~ exp(-dx^2/(2 tau^2))]\n";
  }
  if (!st.regularity_lo.empty()) {
    std::cout << "  regularity min                " << range(st.regularity_lo) << "\n";
    std::cout << "  regularity max                " << range(st.regularity_hi) << "\n";
  }
  if (!st.diameters.empty()) {
    std::cout << "  melanosome diameter (nm)      " << range(st.diameters) << ", " << st.diameters.size()
              << " melanosomes\n";
  }
  std::cout << "  bodies by role               ";
  for (const auto& [role, count] : st.roles) std::cout << " " << role << " " << count;
  std::cout << "\n";
  if (!st.layers.empty()) {
    std::cout << "  mean local stack under the central half (layer: material, thickness nm, share of normals)\n";
    const std::size_t total = st.layers.front().second.size();
    for (std::size_t j = 0; j < st.layers.size() && j < 14; ++j) {
      std::cout << "    " << std::setw(2) << j + 1 << ": " << std::setw(28) << std::left
                << st.layers[j].first << std::right << std::setw(9) << std::fixed << std::setprecision(1)
                << mean(st.layers[j].second) << "  " << std::setprecision(2)
                << static_cast<double>(st.layers[j].second.size()) / static_cast<double>(std::max<std::size_t>(1, total))
                << std::defaultfloat << std::setprecision(6) << "\n";
    }
    if (st.layers.size() > 14) std::cout << "    ... " << st.layers.size() << " layers at most\n";
  }
}

void run(AppContext& context, const Options& o) {
  if (o.instances < 1) throw UsageError("--instances must be at least 1");
  if (o.first < 0) throw UsageError("--first must be >= 0");
  if (o.out.empty() && !o.stats) throw UsageError("give --out DIR and/or --stats");
  SpeciesConfig config = load_species_config(o.config, context.registry(), o.variant);
  context.warn_about_problems();
  if (!config.structure) {
    throw ConfigError(config.root.mark(), "structure", "the config has no 'structure:' section");
  }
  const std::string stem = config.species + (config.variant.empty() ? "" : "-" + config.variant);
  Stats st;
  std::vector<CrossSection> sections;
  for (int k = 0; k < o.instances; ++k) {
    const auto index = static_cast<std::uint64_t>(o.first + k);
    const auto t0 = std::chrono::steady_clock::now();
    CrossSection cs = config.structure->generate(index);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    auto problems = validate(cs);
    if (!problems.empty() && o.allow_invalid) {
      for (const auto& p : problems) if (!context.quiet) std::cerr << "warning: instance " << index << ": " << p << "\n";
    } else if (!problems.empty()) {
      std::string msg = stem + " instance " + std::to_string(index) + " is geometrically invalid:";
      for (const auto& p : problems) msg += "\n  " + p;
      throw Error(msg);
    }
    if (!context.quiet) {
      std::cerr << "geometry: " << stem << " instance " << index << " (" << k + 1 << "/" << o.instances
                << "): " << cs.top.size() << " top vertices, " << cs.regions.size() << " regions, "
                << std::fixed << std::setprecision(2) << ms << " ms" << std::defaultfloat << "\n";
    }
    if (o.stats) accumulate(st, cs);
    if (!o.out.empty()) sections.push_back(std::move(cs));
  }
  // Everything generated and valid: now write.
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    for (const CrossSection& cs : sections) {
      const std::filesystem::path base = std::filesystem::path(o.out) / (stem + "-" + std::to_string(cs.instance));
      write_file_atomically(base.string() + ".xsec", [&](std::ostream& s) { write_cross_section_text(s, cs); });
      if (o.svg) {
        SvgOptions svg;
        svg.pixels_per_um = o.pixels_per_um;
        if (o.window_um > 0) svg.window_nm = std::make_pair(-500.0 * o.window_um, 500.0 * o.window_um);
        write_file_atomically(base.string() + ".svg", [&](std::ostream& s) { write_cross_section_svg(s, cs, svg); });
      }
      if (o.png) {
        SvgOptions png;
        png.pixels_per_um = o.pixels_per_um;
        if (o.window_um > 0) png.window_nm = std::make_pair(-500.0 * o.window_um, 500.0 * o.window_um);
        write_png(render_cross_section(cs, png), base.string() + ".png");
      }
    }
    if (!context.quiet) std::cerr << "geometry: wrote " << sections.size() << " instance(s) to " << o.out << "\n";
  }
  if (o.stats) print_stats(st, stem, o.instances);
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
  cmd->add_flag("!--no-svg", o->svg, "Do not write SVG pictures");
  cmd->add_flag("!--no-png", o->png, "Do not write PNG pictures");
  cmd->add_flag("--allow-invalid", o->allow_invalid, "Write instances that fail the validity check (debugging)");
  cmd->add_option("--window-um", o->window_um, "SVG: draw only the central window of this width (um)");
  cmd->add_option("--pixels-per-um", o->pixels_per_um, "SVG: scale")->capture_default_str();
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
