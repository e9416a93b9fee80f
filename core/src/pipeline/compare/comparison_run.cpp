// Running a comparison: the selection of methods, wavelengths and instance, the preparation of
// the methods' reflections, the barbule segment (exact and reduced), and the solves with their
// wall times.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "plumage/comparison.hpp"
#include "plumage/memory_budget.hpp"

namespace plumage {

namespace {

// A selection that names something the comparison lacks: located at the flag that set it.
[[noreturn]] void refuse(const char* flag, const std::string& message) {
  throw ConfigError(SourceMark{flag, 0, 0}, "", message);
}

std::string format_wavelength(double x) {
  std::ostringstream s;
  s << std::setprecision(17) << x;
  return s.str();
}

std::size_t method_index(const Comparison& c, const std::string& name) {
  const auto it = std::find_if(c.methods.begin(), c.methods.end(),
                               [&](const ComparisonMethod& m) { return m.name == name; });
  return static_cast<std::size_t>(it - c.methods.begin());
}

// Incident directions grouped by θ_i: one solve() serves all azimuths of a θ_i.
std::map<double, std::vector<std::size_t>> incidents_by_theta(const Comparison& c) {
  std::map<double, std::vector<std::size_t>> by_theta;
  for (std::size_t i = 0; i < c.incidents.size(); ++i) by_theta[c.incidents[i].theta_rad].push_back(i);
  return by_theta;
}

bool near_wavelength(double a, double b) { return std::abs(a - b) < 1e-9; }

// Remaining wall time of the solve loop. A full-wave solve costs 10^5–10^6 approximate ones, so a
// mean over all solves so far says nothing: each method's remaining solves are priced at its own
// mean so far, or, for a method not started yet, at the mean of the methods of the same solver
// type that have run (zero if none has: the estimate is then a lower bound).
double remaining_seconds(const std::vector<ComparisonMethod>& methods, const std::vector<MethodRun>& runs,
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

}  // namespace

void select_in_comparison(Comparison& c, const ComparisonSelection& s) {
  const std::string file = c.file.string();
  if (!s.reference.empty()) {
    const std::size_t index = method_index(c, s.reference);
    if (index == c.methods.size()) refuse("--reference", file + " has no method named '" + s.reference + "'");
    c.reference = index;
  }
  if (!s.only.empty()) {
    for (const auto& name : s.only) {
      if (method_index(c, name) == c.methods.size()) refuse("--only", file + " has no method named '" + name + "'");
    }
    const std::string reference = c.methods[c.reference].name;
    std::vector<ComparisonMethod> kept;
    for (auto& m : c.methods) {
      if (m.name == reference || std::find(s.only.begin(), s.only.end(), m.name) != s.only.end()) {
        if (m.name == reference) c.reference = kept.size();
        kept.push_back(std::move(m));
      }
    }
    c.methods = std::move(kept);
  }
  if (!s.wavelengths_nm.empty()) {
    // A subset of the config's wavelengths: full-wave solves of a paper-size segment take tens of
    // minutes each, so long comparisons are run per wavelength (and merged, plugins/bem/tools).
    for (double l : s.wavelengths_nm) {
      if (std::none_of(c.lambdas.begin(), c.lambdas.end(), [&](double x) { return near_wavelength(x, l); })) {
        refuse("--wavelengths", file + " has no wavelength " + format_wavelength(l) + " nm");
      }
    }
    std::erase_if(c.lambdas, [&](double x) {
      return std::none_of(s.wavelengths_nm.begin(), s.wavelengths_nm.end(),
                          [&](double l) { return near_wavelength(x, l); });
    });
  }
  // Another barbule instance of the same comparison (a study over instances is one config and a
  // loop, not one config per instance).
  if (s.instance) {
    if (*s.instance < 0) {
      refuse("--instance", "expected a non-negative integer, got " + std::to_string(*s.instance));
    }
    c.instance = static_cast<std::uint64_t>(*s.instance);
  }
}

void prepare_comparison(const Comparison& c, const PreparationOptions& options) {
  std::set<const LocalReflection*> done;
  for (const auto& m : c.methods) {
    if (m.reflection && done.insert(m.reflection.get()).second) m.reflection->prepare(options);
  }
}

ComparisonSegment make_comparison_segment(const Comparison& c) {
  ComparisonSegment s{c.generator->generate(c.instance), std::nullopt};
  if (const auto problems = validate(s.exact); !problems.empty()) {
    throw Error("compare: the generated cross section is invalid: " + problems.front());
  }
  for (const auto& m : c.methods) {
    if (m.geometry != ComparisonMethod::Geometry::reduced_layers || s.reduced) continue;
    if (!s.exact.layered) {
      throw ConfigError(m.geometry_mark, m.geometry_field,
                        "method '" + m.name + "' asks for reduced_layers, but " + c.species.species +
                            " barbules have no layered model (crystal-type)");
    }
    s.reduced = with_reduced_regions(s.exact, c.reduced);
    if (const auto problems = validate(*s.reduced); !problems.empty()) {
      throw Error("compare: the reduced layer regions are invalid: " + problems.front());
    }
  }
  return s;
}

std::size_t comparison_solve_count(const Comparison& c) {
  return c.methods.size() * c.lambdas.size() * incidents_by_theta(c).size();
}

void check_comparison_memory(const Comparison& c, const ComparisonSegment& segment) {
  const auto by_theta = incidents_by_theta(c);
  std::size_t azimuths = 0;
  for (const auto& [theta, members] : by_theta) azimuths = std::max(azimuths, members.size());
  for (const ComparisonMethod& m : c.methods) {
    const CrossSection& cs = m.geometry == ComparisonMethod::Geometry::exact ? segment.exact : *segment.reduced;
    for (double lambda : c.lambdas) {
      MemoryEstimate e = m.solver->estimate_memory(cs, lambda, azimuths, c.pattern_samples);
      if (e.parts.empty()) continue;
      e.job = "compare method '" + m.name + "': " + e.job;
      check_memory(e);
    }
  }
}

std::vector<MethodRun> run_comparison(const Comparison& c, const ComparisonSegment& segment,
                                      const ComparisonProgress& progress) {
  const DirectionSet directions = pattern_directions(c.pattern_samples);
  const auto by_theta = incidents_by_theta(c);
  const std::size_t solves_per_method = c.lambdas.size() * by_theta.size();
  const std::size_t total = c.methods.size() * solves_per_method;

  check_comparison_memory(c, segment);
  std::vector<MethodRun> runs(c.methods.size());
  std::size_t done = 0;
  using clock = std::chrono::steady_clock;
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const ComparisonMethod& m = c.methods[mi];
    MethodRun& r = runs[mi];
    const CrossSection& cs = m.geometry == ComparisonMethod::Geometry::exact ? segment.exact : *segment.reduced;
    r.regions = cs.regions.size();
    r.results.assign(c.incidents.size(), std::vector<FarField>(c.lambdas.size()));
    r.solve_s_per_lambda.assign(c.lambdas.size(), 0.0);
    report_step("compare: method '" + m.name + "'", static_cast<double>(mi), static_cast<double>(c.methods.size()),
                std::to_string(c.lambdas.size()) + " wavelengths, " + std::to_string(cs.regions.size()) + " regions");
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
        if (progress) {
          progress(done, total, remaining_seconds(c.methods, runs, mi, done - mi * solves_per_method, solves_per_method));
        }
      }
    }
  }
  return runs;
}

}  // namespace plumage
