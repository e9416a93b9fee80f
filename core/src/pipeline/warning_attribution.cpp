// Warning codes per work group and the material's warnings (warning_attribution.hpp).
#include "warning_attribution.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "plumage/diagnostics.hpp"
#include "plumage/material_warnings.hpp"

namespace plumage {

RaiseCounts raise_counts() {
  RaiseCounts counts;
  for (const Warning& w : diagnostics().warnings()) counts[w.code] = w.count;
  return counts;
}

std::set<std::string> raised_since(const RaiseCounts& before) {
  std::set<std::string> codes;
  for (const auto& [code, count] : raise_counts()) {
    const auto it = before.find(code);
    if (it == before.end() || it->second < count) codes.insert(code);
  }
  return codes;
}

namespace {

// Longest cells line kept as it is (several codes must fit the .plm's 64 KiB warnings string).
constexpr std::size_t kMaxCellsText = 16384;

// What the worst value of a per-direction code measures (the solver's limit is in its message).
std::string measure_of(const std::string& code) {
  if (code == "approx.grazing") return "horizon spill ratio (lobe half-width over its distance to the horizon)";
  return "measure";
}

std::string percent(double part, double whole) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f %%", whole > 0.0 ? 100.0 * part / whole : 0.0);
  return buffer;
}

std::string number(double v) {
  if (std::isinf(v)) return "inf (specular direction beyond the horizon)";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

// A per-direction code: which units (w, a, b) raised it, their energy and worst measure.
struct DirectionalTally {
  std::size_t units = 0;
  double energy = 0.0, worst = 0.0;
  std::size_t instance_raises = 0;
  std::vector<std::uint8_t> cells;  // union over λ bins, [(a − 1)·G + (b − 1)]
};

// The summary of one per-direction code (plumage/material_warnings.hpp) and its cells line.
std::string directional_entry(const CharacterizeSettings& s, const std::string& code, std::size_t groups_raised,
                              std::size_t groups, const DirectionalTally& t, double energy_total) {
  const std::size_t units = groups * static_cast<std::size_t>(s.grid);
  std::ostringstream out;
  out << code << ": raised in " << t.units << " of " << units << " work units (" << percent(t.units, units) << "), in "
      << groups_raised << " of " << groups << " work groups; directions " << describe_cells(s.grid, t.cells) << "; "
      << percent(t.energy, energy_total) << " of the characterised reflected energy (sum of the units' E); worst "
      << measure_of(code) << " " << number(t.worst) << "; raised by "
      << percent(static_cast<double>(t.instance_raises), static_cast<double>(t.units) * s.instances)
      << " of those units' instance solves\n";
  std::string cells = format_cells(s.grid, t.cells);
  if (cells.size() > kMaxCellsText) {
    // The .plm's strings are at most 64 KiB: on a very fine grid with scattered cells each row
    // becomes one range from its first to its last flagged column (a superset: a render then
    // counts a few more of its evaluations as in the flagged directions, never fewer).
    std::vector<std::uint8_t> coarse(t.cells.size(), 0);
    const std::size_t G = static_cast<std::size_t>(s.grid);
    for (std::size_t a = 0; a < G; ++a) {
      std::size_t lo = G, hi = 0;
      for (std::size_t b = 0; b < G; ++b)
        if (t.cells[a * G + b]) lo = std::min(lo, b), hi = std::max(hi, b);
      for (std::size_t b = lo; b <= hi && lo < G; ++b) coarse[a * G + b] = 1;
    }
    cells = format_cells(s.grid, coarse);
  }
  out << code << " cells: " << cells << "\n";
  return out.str();
}

}  // namespace

// The messages with their numbers went to the computing processes' stderr; the material keeps
// where each code was raised and, for codes raised per incident direction (the records'
// unit_warnings), how much: units, directions, energy share, worst measure.
std::string material_warnings(const CharacterizeSettings& s, const std::vector<const GroupRecord*>& groups) {
  std::map<std::string, std::pair<std::size_t, const GroupRecord*>> by_code;
  std::map<std::string, DirectionalTally> directional;
  double energy_total = 0.0;
  const std::size_t G = static_cast<std::size_t>(s.grid);
  for (const GroupRecord* r : groups) {
    for (const UnitRecord& u : r->units) energy_total += u.energy;
    for (const std::string& code : r->warnings) {
      auto& [count, first] = by_code[code];
      ++count;
      if (!first || std::make_pair(r->w, r->a) < std::make_pair(first->w, first->a)) first = r;
    }
    for (const GroupRecord::UnitWarning& u : r->unit_warnings) {
      if (u.b < 1 || u.b > G || u.b > r->units.size()) continue;
      DirectionalTally& t = directional[u.code];
      if (t.cells.empty()) t.cells.assign(G * G, 0);
      ++t.units;
      t.energy += r->units[u.b - 1].energy;
      t.worst = std::max(t.worst, u.worst);
      t.instance_raises += u.instances;
      t.cells[(r->a - 1) * G + (u.b - 1)] = 1;
    }
  }
  std::ostringstream out;
  for (const auto& [code, entry] : by_code) {
    if (const auto d = directional.find(code); d != directional.end()) {
      out << directional_entry(s, code, entry.first, groups.size(), d->second, energy_total);
      continue;
    }
    out << code << ": raised while computing " << entry.first << " of " << groups.size()
        << " work groups, first at lambda = " << s.lambda_nm[entry.second->w] << " nm, cos theta_i = "
        << entry.second->a << "/" << s.grid << "\n";
  }
  return out.str();
}

void relay_rank_warnings(int rank, const std::string& summary) {
  std::istringstream lines(summary);
  for (std::string line; std::getline(lines, line);) {
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;
    warn(line.substr(0, colon), "rank " + std::to_string(rank) + ": " + line.substr(colon + 2));
  }
}

}  // namespace plumage
