// A material's warnings text and its cells (plumage/material_warnings.hpp).
#include "plumage/material_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "plumage/conventions.hpp"

namespace plumage {

namespace {

constexpr std::string_view kCellsTag = " cells: ";

int nearest_index(double cosine, int grid) {
  const double c = std::isfinite(cosine) ? std::clamp(cosine, 0.0, 1.0) : 0.0;
  return std::clamp(static_cast<int>(std::lround(c * grid)), 1, grid);
}

std::string degrees(int index, int grid) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", rad_to_deg(std::acos(static_cast<double>(index) / grid)));
  return buffer;
}

// "a:b0-b1,b0-b1 …" → cells; false if it does not parse.
bool parse_cells(std::string_view text, int grid, std::vector<std::uint8_t>& cells) {
  if (grid < 1) return false;
  cells.assign(static_cast<std::size_t>(grid) * static_cast<std::size_t>(grid), 0);
  std::istringstream in{std::string(text)};
  for (std::string row; in >> row;) {
    int a = 0;
    char colon = 0;
    std::istringstream r(row);
    if (!(r >> a >> colon) || colon != ':' || a < 1 || a > grid) return false;
    for (std::string range; std::getline(r, range, ',');) {
      int b0 = 0, b1 = 0;
      char dash = 0;
      std::istringstream g(range);
      if (!(g >> b0 >> dash >> b1) || dash != '-' || b0 < 1 || b1 < b0 || b1 > grid) return false;
      for (int b = b0; b <= b1; ++b) cells[static_cast<std::size_t>(a - 1) * grid + (b - 1)] = 1;
    }
  }
  return true;
}

}  // namespace

bool MaterialWarning::contains(double cos_theta_i, double cos_phi_i) const {
  if (cells.empty() || grid < 1) return false;
  const int a = nearest_index(cos_theta_i, grid), b = nearest_index(cos_phi_i, grid);
  return cells[static_cast<std::size_t>(a - 1) * grid + (b - 1)] != 0;
}

std::vector<MaterialWarning> parse_material_warnings(std::string_view text, int grid) {
  std::vector<MaterialWarning> out;
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    const auto tag = line.find(kCellsTag);
    const auto colon = line.find(": ");
    if (tag != std::string::npos && tag < colon && !out.empty() && out.back().code == line.substr(0, tag)) {
      MaterialWarning& w = out.back();
      w.grid = grid;
      if (!parse_cells(std::string_view(line).substr(tag + kCellsTag.size()), grid, w.cells)) w.cells.clear();
      continue;
    }
    MaterialWarning w;
    w.code = colon == std::string::npos ? line : line.substr(0, colon);
    w.summary = colon == std::string::npos ? std::string() : line.substr(colon + 2);
    out.push_back(std::move(w));
  }
  return out;
}

std::string format_cells(int grid, const std::vector<std::uint8_t>& cells) {
  std::string out;
  for (int a = 1; a <= grid; ++a) {
    std::string row;
    for (int b = 1; b <= grid; ++b) {
      if (!cells[static_cast<std::size_t>(a - 1) * grid + (b - 1)]) continue;
      int end = b;
      while (end < grid && cells[static_cast<std::size_t>(a - 1) * grid + end]) ++end;
      if (!row.empty()) row += ',';
      row += std::to_string(b);
      row += '-';
      row += std::to_string(end);
      b = end;
    }
    if (row.empty()) continue;
    if (!out.empty()) out += ' ';
    out += std::to_string(a);
    out += ':';
    out += row;
  }
  return out;
}

// θ_i = acos(a/G), φ_i = acos(b/G): small a and b are the grazing side. Rows 1 … A flagged at every
// azimuth are said once ("theta_i >= θ(A) at every phi_i"); of each other flagged row, its largest
// flagged column gives the smallest |φ_i| reached there, said for the rows nearest to and
// farthest from normal incidence ("|phi_i| >= 72.5 deg at theta_i 0.0 deg, widening to
// |phi_i| >= 36.9 deg at theta_i 84.3 deg"), or once with the θ_i span when every row agrees.
std::string describe_cells(int grid, const std::vector<std::uint8_t>& cells) {
  if (grid < 1 || cells.empty()) return "";
  auto flagged = [&](int a, int b) { return cells[static_cast<std::size_t>(a - 1) * grid + (b - 1)] != 0; };
  int full = 0;  // rows 1 … full are flagged at every b
  while (full < grid) {
    bool all = true;
    for (int b = 1; b <= grid && all; ++b) all = flagged(full + 1, b);
    if (!all) break;
    ++full;
  }
  int a_lo = 0, a_hi = 0, b_lo = 0, b_hi = 0;  // rows nearest grazing / normal and their largest b
  bool same = true;
  for (int a = full + 1; a <= grid; ++a) {
    int b_max = 0;
    for (int b = 1; b <= grid; ++b)
      if (flagged(a, b)) b_max = b;
    if (b_max == 0) continue;
    if (a_lo == 0) a_lo = a, b_lo = b_max;
    if (a_hi != 0 && b_max != b_hi) same = false;
    a_hi = a, b_hi = b_max;
    same = same && b_max == b_lo;
  }
  std::string out;
  if (full > 0) out = "theta_i >= " + degrees(full, grid) + " deg at every phi_i";
  if (a_lo > 0) {
    if (!out.empty()) out += "; ";
    out += "|phi_i| >= " + degrees(b_hi, grid) + " deg at theta_i ";
    if (same) out += degrees(a_hi, grid) + "-" + degrees(a_lo, grid) + " deg";
    else out += degrees(a_hi, grid) + " deg, widening to |phi_i| >= " + degrees(b_lo, grid) + " deg at theta_i " +
                degrees(a_lo, grid) + " deg";
  }
  return out.empty() ? "none" : out;
}

std::string material_warning_summaries(std::string_view text) {
  std::string out;
  for (const MaterialWarning& w : parse_material_warnings(text, 0)) out += w.code + ": " + w.summary + "\n";
  return out;
}

}  // namespace plumage
