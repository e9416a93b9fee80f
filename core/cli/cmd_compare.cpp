// `plumage compare CONFIG`: the paper's accuracy comparison (§6.1, Figs. 8–9). Several
// scattering-solver methods (plug-in type + options, optionally on the reduced layer geometry
// or with another local reflection) run on the same barbule cross section at the same
// wavelengths and incident directions; each is compared with the reference method per
// wavelength, incident direction and polarization (pattern correlation, relative L2 difference,
// reflected-fraction difference, Eqs. 8–10), with its wall time. Schema: docs/formats.md.
//
// The command never includes a plug-in's headers: methods are created through the registry.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "plumage/charts.hpp"
#include "commands.hpp"
#include "plumage/atomic_file.hpp"
#include "plumage/colour.hpp"
#include "plumage/config_document.hpp"
#include "plumage/reduced_regions.hpp"
#include "plumage/species_config.hpp"
#include "plumage/version.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace {

namespace fs = std::filesystem;

enum class Geometry { exact, reduced_layers };

struct Method {
  std::string name;
  std::string solver_type;
  std::string solver_options;  // the solver section as written, for the record
  Geometry geometry = Geometry::exact;
  std::shared_ptr<const ScatteringSolver> solver;
  std::shared_ptr<const LocalReflection> reflection;
  std::string reflection_note;  // "species" or the override's model
  SourceMark geometry_mark;     // where `geometry` is (for the error of a missing layered model)
  std::string geometry_field;
};

struct Comparison {
  fs::path file;
  std::string name;
  SpeciesConfig species;
  std::shared_ptr<const StructureGenerator> generator;
  double segment_um = 10.0;
  std::uint64_t instance = 0;
  std::vector<double> lambdas;
  std::vector<IncidentDirection> incidents;  // radians
  int pattern_samples = 400;
  std::vector<Method> methods;
  std::size_t reference = 0;
  ReducedRegionOptions reduced;
};

// ---------------------------------------------------------------------------------------------
// A ParamView subtree written back as YAML text (flow style, every scalar double-quoted), with
// some dotted paths replaced: how the barbule segment's width enters the species' generator
// section without editing the species file. yaml-cpp converts quoted scalars like plain ones.

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') { out += "\\n"; continue; }
    out += c;
  }
  return out + "\"";
}

void emit_yaml(std::ostream& out, const ParamView& v, const std::string& path,
               const std::map<std::string, std::string>& overrides, std::set<std::string>& used) {
  if (v.is_map()) {
    out << '{';
    bool first = true;
    for (const auto& key : v.keys()) {
      const std::string child = path.empty() ? key : path + "." + key;
      out << (first ? "" : ", ") << quoted(key) << ": ";
      first = false;
      if (auto it = overrides.find(child); it != overrides.end()) {
        out << it->second;
        used.insert(child);
        v.accept(key);
      } else {
        emit_yaml(out, v.node(key), child, overrides, used);
      }
    }
    out << '}';
  } else if (v.is_sequence()) {
    out << '[';
    bool first = true;
    for (const auto& item : v.items()) {
      out << (first ? "" : ", ");
      first = false;
      emit_yaml(out, item, path, overrides, used);
    }
    out << ']';
  } else if (v.is_null()) {
    out << "null";
  } else {
    out << quoted(v.scalar_text());
  }
}

std::string format_number(double x) {
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Loading

std::vector<double> parse_wavelengths(const ParamView& root) {
  if (!root.has("wavelengths_nm")) root.fail("wavelengths_nm", "missing required key 'wavelengths_nm'");
  std::vector<double> out;
  const ParamView node = root.node("wavelengths_nm");
  if (node.is_sequence()) {
    out = root.numbers("wavelengths_nm", Limits::positive());
  } else if (node.is_map()) {
    const ParamView m = root.child("wavelengths_nm");
    const double from = m.number("from", Limits::positive());
    const double to = m.number("to", Limits::positive());
    const double step = m.number("step", Limits::positive());
    if (to < from) m.fail("to", "must be >= from");
    for (int k = 0; from + k * step <= to + 1e-9 * step; ++k) out.push_back(from + k * step);
  } else {
    root.fail("wavelengths_nm", "expected a list of wavelengths or {from, to, step}");
  }
  if (out.empty()) root.fail("wavelengths_nm", "no wavelengths");
  for (std::size_t i = 1; i < out.size(); ++i) {
    if (!(out[i] > out[i - 1])) root.fail("wavelengths_nm", "wavelengths must increase strictly");
  }
  return out;
}

std::vector<IncidentDirection> parse_incidents(const ParamView& root) {
  if (!root.has("incident_deg")) root.fail("incident_deg", "missing required key 'incident_deg'");
  std::vector<IncidentDirection> out;
  for (const auto& item : root.items("incident_deg")) {
    if (!item.is_sequence()) item.fail_here("expected [theta_i_deg, phi_i_deg]");
    const auto pair = item.items();
    if (pair.size() != 2) item.fail_here("expected [theta_i_deg, phi_i_deg] (two numbers)");
    const double theta = pair[0].scalar_number(Limits{0.0, 90.0, false, true});
    const double phi = pair[1].scalar_number(Limits{-90.0, 90.0, true, true});
    out.push_back({deg_to_rad(theta), deg_to_rad(phi)});
  }
  if (out.empty()) root.fail("incident_deg", "no incident directions");
  return out;
}

Comparison load_comparison(const fs::path& file, const PluginRegistry& registry) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ParamView root = doc.root();
  Comparison c;
  c.file = file;
  c.name = root.text("comparison");
  if (c.name.empty() || c.name.find_first_of("/\\ ") != std::string::npos) {
    root.fail("comparison", "a name without spaces or slashes (it prefixes the output files)");
  }
  root.accept("description");
  const fs::path species_file = doc.directory() / root.text("species");
  if (!fs::exists(species_file)) root.fail("species", "no such file: " + species_file.string());
  c.species = load_species_config(species_file, registry, root.text_or("variant", ""));
  if (!c.species.structure) root.fail("species", species_file.string() + " has no `structure:` section");
  c.instance = static_cast<std::uint64_t>(root.integer_or("instance", 0, Limits::at_least(0)));

  // The barbule segment: the species' generator with its outline width set to segment_um.
  c.segment_um = root.number_or("segment_um", 10.0, Limits::positive());
  {
    const ParamView structure = c.species.root.child("structure");
    std::map<std::string, std::string> overrides{{"outline.width_um", format_number(c.segment_um)}};
    // Further generator parameters by dotted path (e.g. outline.thickness_um), replacing the
    // species' values; each must exist in the species' structure section.
    std::optional<ParamView> extra = root.child_if("structure_overrides");
    if (extra) {
      for (const auto& key : extra->keys()) {
        if (key == "outline.width_um") extra->fail(key, "the width is segment_um");
        std::ostringstream value;
        std::set<std::string> unused;
        emit_yaml(value, extra->node(key), "", {}, unused);
        overrides[key] = value.str();
      }
    }
    std::ostringstream text;
    std::set<std::string> used;
    emit_yaml(text, structure, "", overrides, used);
    if (!used.count("outline.width_um")) {
      root.fail("segment_um", "the species' structure has no outline.width_um to set (" +
                                  species_file.string() + ")");
    }
    if (extra) {
      for (const auto& key : extra->keys()) {
        if (!used.count(key)) extra->fail(key, "the species' structure has no parameter '" + key + "'");
      }
    }
    const ConfigDocument segment = ConfigDocument::parse(
        text.str(), species_file.string() + " (structure with outline.width_um = segment_um of " + file.string() + ")");
    auto generator = registry.create<StructureGenerator>(segment.root(), "generator",
                                                         registry.context(species_file.parent_path()));
    generator->bind(c.species.species, c.species.variant);
    c.generator = std::move(generator);
  }

  c.lambdas = parse_wavelengths(root);
  c.incidents = parse_incidents(root);
  c.pattern_samples = static_cast<int>(root.integer_or("pattern_samples", 400, Limits::closed(8, 20000)));
  if (auto reduced = root.child_if("reduced_layers")) {
    static constexpr std::string_view kMixture[] = {"mean", "piecewise"};
    c.reduced.mixture = reduced->choice_or("mixture", kMixture, "mean") == "mean"
                            ? ReducedRegionOptions::Mixture::mean
                            : ReducedRegionOptions::Mixture::piecewise;
    c.reduced.piece_nm = reduced->number_or("piece_nm", 1000.0, Limits::positive());
  }

  const PluginContext context = registry.context(doc.directory());
  if (!root.has("methods")) root.fail("methods", "missing required key 'methods'");
  for (const auto& m : root.items("methods")) {
    if (!m.is_map()) m.fail_here("expected {name: .., solver: {type: ..}, geometry: exact|reduced_layers}");
    Method method;
    method.geometry_mark = m.mark_of("geometry");
    method.geometry_field = m.path_of("geometry");
    method.name = m.text("name");
    if (method.name.empty() || method.name.find_first_of(",/\\ ") != std::string::npos) {
      m.fail("name", "a method name without spaces, commas or slashes");
    }
    for (const auto& other : c.methods) {
      if (other.name == method.name) m.fail("name", "duplicate method name '" + method.name + "'");
    }
    if (!m.has("solver")) m.fail("solver", "missing required key 'solver'");
    const ParamView solver = m.node("solver");
    if (solver.is_map()) {
      method.solver_type = solver.text("type");
      std::ostringstream text;
      std::set<std::string> unused;
      emit_yaml(text, solver, "", {}, unused);
      method.solver_options = text.str();
      method.solver = registry.create<ScatteringSolver>(m.child("solver"), "type", context);
    } else {
      method.solver_type = m.text("solver");
      method.solver_options = method.solver_type;
      try {
        method.solver = registry.create_named<ScatteringSolver>(method.solver_type, ParamView{}, context);
      } catch (const PluginError& e) {
        m.fail("solver", e.what());
      }
    }
    static constexpr std::string_view kGeometry[] = {"exact", "reduced_layers"};
    method.geometry = m.choice_or("geometry", kGeometry, "exact") == "exact" ? Geometry::exact : Geometry::reduced_layers;
    if (m.has("reflection")) {
      method.reflection = registry.create<LocalReflection>(m.child("reflection"), "model", context);
      method.reflection_note = m.child("reflection").text("model");
    } else {
      method.reflection = c.species.reflection;
      method.reflection_note = "species";
    }
    m.finish();
    c.methods.push_back(std::move(method));
  }
  if (c.methods.empty()) root.fail("methods", "no methods");
  const std::string reference = root.text_or("reference", c.methods.front().name);
  auto it = std::find_if(c.methods.begin(), c.methods.end(), [&](const Method& m) { return m.name == reference; });
  if (it == c.methods.end()) root.fail("reference", "no method named '" + reference + "'");
  c.reference = static_cast<std::size_t>(it - c.methods.begin());
  root.finish();
  return c;
}

// ---------------------------------------------------------------------------------------------
// Metrics

struct Metrics {
  double correlation = 0.0;  // Pearson correlation of the two patterns over φ_o
  double rel_l2 = 0.0;       // ‖a − b‖₂ / ‖b‖₂
  double total = 0.0;        // reflected fraction of the method (Eq. 8 / Eq. 9)
  double total_ref = 0.0;    // the reference's
};

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) { ma += a[i]; mb += b[i]; }
  ma /= n;
  mb /= n;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa > 0.0) || !(sbb > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return sab / std::sqrt(saa * sbb);
}

Metrics compare_patterns(const std::vector<double>& a, const std::vector<double>& b, double bin) {
  Metrics m;
  m.correlation = pearson(a, b);
  double d2 = 0.0, b2 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d2 += (a[i] - b[i]) * (a[i] - b[i]);
    b2 += b[i] * b[i];
    m.total += a[i] * bin;
    m.total_ref += b[i] * bin;
  }
  m.rel_l2 = b2 > 0.0 ? std::sqrt(d2 / b2) : std::numeric_limits<double>::quiet_NaN();
  return m;
}

// Reflectance density (Eq. 10) per direction: pol 0, 1, or 2 for the unpolarised mean.
std::vector<double> density(const FarField& ff, int pol) {
  std::vector<double> d(ff.phi_o_rad.size());
  for (std::size_t j = 0; j < d.size(); ++j) {
    d[j] = pol < 2 ? ff.reflectance_density(pol, j)
                   : 0.5 * (ff.reflectance_density(0, j) + ff.reflectance_density(1, j));
  }
  return d;
}

std::string incident_tag(const IncidentDirection& d) {
  std::ostringstream s;
  s << "theta" << rad_to_deg(d.theta_rad) << "_phi" << rad_to_deg(d.phi_rad);
  std::string t = s.str();
  std::replace(t.begin(), t.end(), '-', 'm');
  std::replace(t.begin(), t.end(), '.', 'p');
  return t;
}

std::string pol_name(int p) { return p == 2 ? "mean" : std::to_string(p + 1); }

// ---------------------------------------------------------------------------------------------

struct Options {
  std::string config;
  std::string out;
  bool no_pictures = false;
  std::vector<std::string> only;  // run only these methods (the reference always runs)
  std::string reference;          // overrides the config's reference
  std::vector<double> wavelengths;  // run only these of the config's wavelengths (nm)
  std::optional<std::int64_t> instance;  // overrides the config's instance (signed: -1 is refused, not wrapped)
};

struct MethodRun {
  // results[incident][λ]
  std::vector<std::vector<FarField>> results;
  double prepare_s = 0.0;
  double solve_s = 0.0;
  std::vector<double> solve_s_per_lambda;
  std::size_t regions = 0;
};

// Remaining wall time of the solve loop, for the progress line. A full-wave solve costs 10^5–10^6
// approximate ones, so a mean over all solves so far says nothing: each method's remaining solves
// are priced at its own mean so far, or, for a method not started yet, at the mean of the methods
// of the same solver type that have run (zero if none has: the estimate is then a lower bound).
double remaining_seconds(const std::vector<Method>& methods, const std::vector<MethodRun>& runs,
                         std::size_t current_method, std::size_t solves_done_in_current,
                         std::size_t solves_per_method) {
  const auto per_solve = [&](std::size_t mi) {
    const std::size_t solves = mi < current_method ? solves_per_method : solves_done_in_current;
    return runs[mi].solve_s / static_cast<double>(solves);
  };
  double eta = per_solve(current_method) * static_cast<double>(solves_per_method - solves_done_in_current);
  for (std::size_t mi = current_method + 1; mi < methods.size(); ++mi) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t k = 0; k <= current_method; ++k) {
      if (methods[k].solver_type == methods[mi].solver_type) {
        sum += per_solve(k);
        ++count;
      }
    }
    if (count > 0) eta += sum / count * static_cast<double>(solves_per_method);
  }
  return eta;
}

void run(AppContext& context, const Options& o) {
  Comparison c = load_comparison(o.config, context.registry());
  if (!o.reference.empty()) {
    auto it = std::find_if(c.methods.begin(), c.methods.end(), [&](const Method& m) { return m.name == o.reference; });
    if (it == c.methods.end()) throw UsageError("--reference: " + o.config + " has no method named '" + o.reference + "'");
    c.reference = static_cast<std::size_t>(it - c.methods.begin());
  }
  if (!o.only.empty()) {
    for (const auto& name : o.only) {
      if (std::none_of(c.methods.begin(), c.methods.end(), [&](const Method& m) { return m.name == name; })) {
        throw UsageError("--only: " + o.config + " has no method named '" + name + "'");
      }
    }
    const std::string reference = c.methods[c.reference].name;
    std::vector<Method> kept;
    for (auto& m : c.methods) {
      if (m.name == reference || std::find(o.only.begin(), o.only.end(), m.name) != o.only.end()) {
        if (m.name == reference) c.reference = kept.size();
        kept.push_back(std::move(m));
      }
    }
    c.methods = std::move(kept);
  }
  if (!o.wavelengths.empty()) {
    // A subset of the config's wavelengths: full-wave solves of a paper-size segment take tens of
    // minutes each, so long comparisons are run per wavelength (and merged, plugins/bem/tools).
    for (double l : o.wavelengths) {
      if (std::none_of(c.lambdas.begin(), c.lambdas.end(), [&](double x) { return std::abs(x - l) < 1e-9; })) {
        throw UsageError("--wavelengths: " + o.config + " has no wavelength " + format_number(l) + " nm");
      }
    }
    std::erase_if(c.lambdas, [&](double x) {
      return std::none_of(o.wavelengths.begin(), o.wavelengths.end(), [&](double l) { return std::abs(x - l) < 1e-9; });
    });
  }
  // Another barbule instance of the same comparison (a study over instances is one config and a
  // loop, not one config per instance).
  if (o.instance) {
    if (*o.instance < 0) throw UsageError("--instance: expected a non-negative integer, got " + std::to_string(*o.instance));
    c.instance = static_cast<std::uint64_t>(*o.instance);
  }
  const fs::path out_dir = o.out.empty() ? fs::path(c.name + "-compare") : fs::path(o.out);

  // The barbule segment, exact and reduced.
  const CrossSection exact = c.generator->generate(c.instance);
  if (const auto problems = validate(exact); !problems.empty()) {
    throw Error("compare: the generated cross section is invalid: " + problems.front());
  }
  std::optional<CrossSection> reduced;
  for (const auto& m : c.methods) {
    if (m.geometry != Geometry::reduced_layers || reduced) continue;
    if (!exact.layered) {
      throw ConfigError(m.geometry_mark, m.geometry_field,
                        "method '" + m.name + "' asks for reduced_layers, but " + c.species.species +
                            " barbules have no layered model (crystal-type)");
    }
    reduced = with_reduced_regions(exact, c.reduced);
    if (const auto problems = validate(*reduced); !problems.empty()) {
      throw Error("compare: the reduced layer regions are invalid: " + problems.front());
    }
  }

  // The preparation step (crystal tables) of every local reflection the running methods use, once,
  // after the segment is known to be valid.
  std::set<const LocalReflection*> prepared_models;
  for (const auto& m : c.methods)
    if (m.reflection && prepared_models.insert(m.reflection.get()).second) m.reflection->prepare(context.preparation());

  const DirectionSet directions = pattern_directions(c.pattern_samples);
  const double bin = kPi / c.pattern_samples;
  // Incident directions grouped by θ_i: one solve() serves all azimuths of a θ_i.
  std::map<double, std::vector<std::size_t>> by_theta;
  for (std::size_t i = 0; i < c.incidents.size(); ++i) by_theta[c.incidents[i].theta_rad].push_back(i);

  if (!context.quiet) {
    std::cerr << "compare " << c.name << ": " << c.species.common_name << " (" << c.species.variant
              << "), instance " << c.instance << ", segment " << c.segment_um << " um ("
              << exact.regions.size() << " exact regions"
              << (reduced ? ", " + std::to_string(reduced->regions.size()) + " reduced" : std::string()) << "), "
              << c.methods.size() << " methods x " << c.lambdas.size() << " wavelengths x "
              << c.incidents.size() << " incident directions\n";
  }
  std::vector<MethodRun> runs(c.methods.size());
  Progress progress("method-wavelength solves", c.methods.size() * c.lambdas.size() * by_theta.size(), context.quiet);
  std::size_t done = 0;
  using clock = std::chrono::steady_clock;
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const Method& m = c.methods[mi];
    MethodRun& r = runs[mi];
    const CrossSection& cs = m.geometry == Geometry::exact ? exact : *reduced;
    r.regions = cs.regions.size();
    r.results.assign(c.incidents.size(), std::vector<FarField>(c.lambdas.size()));
    r.solve_s_per_lambda.assign(c.lambdas.size(), 0.0);
    const auto t0 = clock::now();
    const auto prepared = m.solver->prepare(cs, m.reflection);
    r.prepare_s = std::chrono::duration<double>(clock::now() - t0).count();
    for (std::size_t l = 0; l < c.lambdas.size(); ++l) {
      for (const auto& [theta, members] : by_theta) {
        std::vector<double> phi_i;
        for (std::size_t i : members) phi_i.push_back(c.incidents[i].phi_rad);
        const auto t1 = clock::now();
        auto fields = m.solver->solve(*prepared, c.lambdas[l], theta, phi_i, directions.phi_o_rad);
        const double dt = std::chrono::duration<double>(clock::now() - t1).count();
        r.solve_s += dt;
        r.solve_s_per_lambda[l] += dt;
        if (fields.size() != members.size()) {
          throw Error("compare: method '" + m.name + "' returned " + std::to_string(fields.size()) +
                      " far fields for " + std::to_string(members.size()) + " incident azimuths");
        }
        for (std::size_t k = 0; k < members.size(); ++k) {
          if (fields[k].phi_o_rad.size() != directions.phi_o_rad.size()) {
            throw Error("compare: method '" + m.name + "' returned a far field on the wrong directions");
          }
          r.results[members[k]][l] = std::move(fields[k]);
        }
        ++done;
        const std::size_t solves_per_method = c.lambdas.size() * by_theta.size();
        progress.advance(done, remaining_seconds(c.methods, runs, mi, done - mi * solves_per_method, solves_per_method));
      }
    }
  }

  // Metrics and outputs (all computed before anything is written).
  const Method& ref = c.methods[c.reference];
  std::ostringstream metrics;
  metrics << std::setprecision(9)
          << "# plumage compare " << c.file.string() << " (" << kVersionString << "): " << c.species.common_name
          << " (" << c.species.variant << "), instance " << c.instance << ", segment " << c.segment_um << " um\n"
          << "# Each method against the reference '" << ref.name << "', per incident direction, wavelength and\n"
          << "# polarization (1, 2, mean = unpolarised), on " << c.pattern_samples
          << " outgoing azimuths phi_o on (-90, 90) deg of the specular cone:\n"
          << "#   correlation: Pearson correlation of the reflectance densities U(phi_o) (Eq. 10, per radian);\n"
          << "#   rel_l2: ||U_method - U_reference||_2 / ||U_reference||_2;\n"
          << "#   R = integral of U over phi_o (midpoint rule), the reflected fraction (Eq. 8 over Eq. 9);\n"
          << "#   dR = R_method - R_reference (absolute).\n"
          << "method,reference,theta_i_deg,phi_i_deg,lambda_nm,pol,correlation,rel_l2,R_method,R_reference,dR\n";
  std::ostringstream patterns;
  patterns << std::setprecision(9)
           << "# Reflectance density U(phi_o) per radian (Eq. 10) of every method; pol 1, 2, mean.\n"
           << "method,theta_i_deg,phi_i_deg,lambda_nm,pol,phi_o_deg,density_per_rad\n";
  struct Summary { double corr_min = 1e300, corr_sum = 0, l2_max = 0, l2_sum = 0, dr_max = 0; int n = 0; };
  std::vector<Summary> summary(c.methods.size());
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    for (std::size_t i = 0; i < c.incidents.size(); ++i) {
      for (std::size_t l = 0; l < c.lambdas.size(); ++l) {
        for (int p = 0; p < 3; ++p) {
          const auto a = density(runs[mi].results[i][l], p);
          const auto b = density(runs[c.reference].results[i][l], p);
          const Metrics mt = compare_patterns(a, b, bin);
          metrics << c.methods[mi].name << ',' << ref.name << ',' << rad_to_deg(c.incidents[i].theta_rad) << ','
                  << rad_to_deg(c.incidents[i].phi_rad) << ',' << c.lambdas[l] << ',' << pol_name(p) << ','
                  << mt.correlation << ',' << mt.rel_l2 << ',' << mt.total << ',' << mt.total_ref << ','
                  << mt.total - mt.total_ref << '\n';
          for (std::size_t j = 0; j < a.size(); ++j) {
            patterns << c.methods[mi].name << ',' << rad_to_deg(c.incidents[i].theta_rad) << ','
                     << rad_to_deg(c.incidents[i].phi_rad) << ',' << c.lambdas[l] << ',' << pol_name(p) << ','
                     << rad_to_deg(directions.phi_o_rad[j]) << ',' << a[j] << '\n';
          }
          if (p == 2) {
            Summary& s = summary[mi];
            s.corr_min = std::min(s.corr_min, mt.correlation);
            s.corr_sum += mt.correlation;
            s.l2_max = std::max(s.l2_max, mt.rel_l2);
            s.l2_sum += mt.rel_l2;
            s.dr_max = std::max(s.dr_max, std::abs(mt.total - mt.total_ref));
            ++s.n;
          }
        }
      }
    }
  }
  std::ostringstream times;
  times << std::setprecision(6)
        << "# Wall time of each method on this machine (prepare: instance-only work such as meshing;\n"
        << "# solve: all wavelengths and incident directions, both polarizations).\n"
        << "method,solver,options,geometry,reflection,regions,prepare_s,solve_s,total_s,solve_s_per_wavelength\n";
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const Method& m = c.methods[mi];
    const MethodRun& r = runs[mi];
    std::string options = m.solver_options;
    std::replace(options.begin(), options.end(), ',', ';');
    std::replace(options.begin(), options.end(), '"', '\'');
    times << m.name << ',' << m.solver_type << ',' << options << ','
          << (m.geometry == Geometry::exact ? "exact" : "reduced_layers") << ',' << m.reflection_note << ','
          << r.regions << ',' << r.prepare_s << ',' << r.solve_s << ',' << r.prepare_s + r.solve_s << ','
          << (r.solve_s / static_cast<double>(c.lambdas.size())) << '\n';
  }

  fs::create_directories(out_dir);
  const fs::path base = out_dir / c.name;
  write_text_atomically(fs::path(base).concat("-metrics.csv"), metrics.str());
  write_text_atomically(fs::path(base).concat("-patterns.csv"), patterns.str());
  write_text_atomically(fs::path(base).concat("-times.csv"), times.str());

  // Summary on stdout.
  std::cout << std::left << std::setw(30) << "method" << std::setw(16) << "geometry" << std::right
            << std::setw(10) << "time_s" << std::setw(12) << "corr_min" << std::setw(12) << "corr_mean"
            << std::setw(12) << "l2_mean" << std::setw(12) << "l2_max" << std::setw(12) << "|dR|_max" << "\n";
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const Summary& s = summary[mi];
    std::cout << std::left << std::setw(30) << c.methods[mi].name << std::setw(16)
              << (c.methods[mi].geometry == Geometry::exact ? "exact" : "reduced_layers") << std::right
              << std::fixed << std::setprecision(3) << std::setw(10) << runs[mi].prepare_s + runs[mi].solve_s
              << std::setprecision(5) << std::setw(12) << s.corr_min << std::setw(12) << s.corr_sum / s.n
              << std::setw(12) << s.l2_sum / s.n << std::setw(12) << s.l2_max << std::setw(12) << s.dr_max
              << std::defaultfloat << (mi == c.reference ? "  (reference)" : "") << "\n";
  }
  std::cout << "(unpolarised; per wavelength and polarization in " << fs::path(base).concat("-metrics.csv").string() << ")\n";

  if (o.no_pictures) return;
  {
    // Error against the reference versus cost, one point per method (scripts/plot_error_cost.py).
    std::ostringstream title;
    title << c.species.common_name << ", " << c.segment_um << " um segment: error against " << ref.name
          << " versus cost";
    const fs::path png = fs::path(base).concat("-error-vs-cost.png");
    draw_script_chart("plot_error_cost.py", {}, png, title.str(),
                      {"--run", c.name, fs::path(base).concat("-metrics.csv").string(),
                       fs::path(base).concat("-times.csv").string()});
    if (!context.quiet) std::cerr << "wrote " << png.string() << "\n";
  }
  // Pictures like Figs. 8–9, one pair per incident direction: the unpolarised patterns of all
  // methods overlaid per wavelength, and colour strips along the cone (spectrum → XYZ under
  // D65 → sRGB, one exposure shared by all methods so strips compare).
  for (std::size_t i = 0; i < c.incidents.size(); ++i) {
    std::ostringstream title;
    title << c.species.common_name << ", " << c.segment_um << " um segment, theta_i = "
          << rad_to_deg(c.incidents[i].theta_rad) << " deg, phi_i = " << rad_to_deg(c.incidents[i].phi_rad) << " deg";
    LineChart chart;
    chart.title = title.str();
    chart.x_label = "outgoing azimuth phi_o (deg)";
    chart.y_label = "reflectance per rad (Eq. 10), unpolarised";
    for (std::size_t l = 0; l < c.lambdas.size(); ++l) {
      std::ostringstream panel;
      panel << "lambda = " << c.lambdas[l] << " nm";
      for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
        const auto d = density(runs[mi].results[i][l], 2);
        for (std::size_t j = 0; j < d.size(); ++j) {
          chart.points.push_back({panel.str(), c.methods[mi].name, rad_to_deg(directions.phi_o_rad[j]), d[j]});
        }
      }
    }
    const fs::path pattern_png = fs::path(base).concat("-patterns-" + incident_tag(c.incidents[i]) + ".png");
    draw_line_chart(chart, pattern_png);
    if (!context.quiet) std::cerr << "wrote " << pattern_png.string() << "\n";

    if (c.lambdas.size() < 2) continue;  // colour needs a spectrum
    SpectralToXyz to_xyz(c.lambdas);
    const std::size_t dirs = directions.phi_o_rad.size();
    std::vector<std::vector<Xyz>> xyz(c.methods.size(), std::vector<Xyz>(dirs));
    double peak = 0.0;
    for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
      std::vector<std::vector<double>> per_lambda;
      for (std::size_t l = 0; l < c.lambdas.size(); ++l) per_lambda.push_back(density(runs[mi].results[i][l], 2));
      std::vector<double> spectrum(c.lambdas.size());
      for (std::size_t j = 0; j < dirs; ++j) {
        for (std::size_t l = 0; l < c.lambdas.size(); ++l) spectrum[l] = per_lambda[l][j];
        xyz[mi][j] = to_xyz.apply(spectrum);
        peak = std::max(peak, xyz[mi][j].y);
      }
    }
    const double exposure = peak > 0.0 ? 1.0 / peak : 1.0;
    const fs::path strips_png = fs::path(base).concat("-colours-" + incident_tag(c.incidents[i]) + ".png");
    const fs::path strips_csv = fs::path(strips_png).concat(".strips.csv.tmp");
    const fs::path lines_csv = fs::path(strips_png).concat(".lines.csv.tmp");
    {
      std::ofstream s(strips_csv);
      s << "row,phi_o_deg,r,g,b\n";
      for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
        for (std::size_t j = 0; j < dirs; ++j) {
          const Xyz v{xyz[mi][j].x * exposure, xyz[mi][j].y * exposure, xyz[mi][j].z * exposure};
          const Rgb8 rgb = to_srgb8(v, GamutMapping::desaturate);
          s << c.methods[mi].name << ',' << rad_to_deg(directions.phi_o_rad[j]) << ',' << int(rgb.r) << ','
            << int(rgb.g) << ',' << int(rgb.b) << '\n';
        }
      }
      // The reference pattern at up to four wavelengths under the strips.
      std::ofstream ln(lines_csv);
      ln << "lambda_nm,phi_o_deg,density\n";
      std::set<std::size_t> picks;
      for (std::size_t q = 0; q < 4; ++q) picks.insert(q * (c.lambdas.size() - 1) / 3);
      for (std::size_t l : picks) {
        const auto d = density(runs[c.reference].results[i][l], 2);
        for (std::size_t j = 0; j < dirs; ++j) ln << c.lambdas[l] << ',' << rad_to_deg(directions.phi_o_rad[j]) << ',' << d[j] << '\n';
      }
    }
    try {
      draw_script_chart("plot_pattern.py", {strips_csv.string(), lines_csv.string()}, strips_png,
                        title.str() + " (lines: reference " + ref.name + ")");
    } catch (...) {
      fs::remove(strips_csv);
      fs::remove(lines_csv);
      throw;
    }
    fs::remove(strips_csv);
    fs::remove(lines_csv);
    if (!context.quiet) std::cerr << "wrote " << strips_png.string() << "\n";
  }
}

}  // namespace

std::string check_comparison_config(const std::string& file, AppContext& context) {
  const Comparison c = load_comparison(file, context.registry());
  std::ostringstream out;
  out << "comparison " << c.name << ", " << c.methods.size() << " methods (reference " << c.methods[c.reference].name
      << "), " << c.lambdas.size() << " wavelengths, " << c.incidents.size() << " incident directions";
  return out.str();
}

void add_compare_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "compare", "Accuracy comparison of scattering solvers on one barbule segment (paper §6.1, Figs. 8-9)");
  cmd->add_option("config", o->config, "Comparison YAML (configs/compare/*.yaml; docs/formats.md)")->required();
  cmd->add_option("--out", o->out, "Output folder (default: <comparison>-compare)");
  cmd->add_flag("--no-pictures", o->no_pictures, "Write the CSV files only");
  cmd->add_option("--only", o->only, "Run only these methods (comma-separated; the reference always runs)")
      ->delimiter(',');
  cmd->add_option("--reference", o->reference, "Compare against this method instead of the config's reference");
  cmd->add_option("--wavelengths", o->wavelengths, "Run only these of the config's wavelengths (nm, comma-separated)")
      ->delimiter(',');
  cmd->add_option("--instance", o->instance, "Barbule instance to compare on instead of the config's `instance`");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
