// Reading the shipped CIE tables (CSV: '#' comments, one header row, then numeric rows).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "plumage/colour.hpp"
#include "plumage/data_paths.hpp"
#include "plumage/error.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

constexpr const char* kObserverFile = "cie1931_2deg_5nm.csv";
constexpr const char* kIlluminantFile = "cie_d65_5nm.csv";

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Rows of `columns` numbers with a strictly increasing first column. Errors read
// "path:line: message" so a hand-edited table points at its own mistake.
std::vector<std::vector<double>> read_table(const fs::path& path, std::size_t columns) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open the CIE table");
  std::vector<std::vector<double>> rows;
  std::string line;
  bool header_seen = false;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    const std::string where = path.string() + ":" + std::to_string(number) + ": ";
    if (!header_seen) {  // names are for people; only the column count matters here
      header_seen = true;
      const auto names = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
      if (names != columns)
        throw Error(where + "header has " + std::to_string(names) + " columns, expected " +
                    std::to_string(columns));
      continue;
    }
    std::vector<double> row;
    std::string_view rest = text;
    while (true) {
      const auto comma = rest.find(',');
      const std::string_view field = trim(rest.substr(0, comma));
      double value = 0.0;
      const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (ec != std::errc() || ptr != field.data() + field.size() || !std::isfinite(value))
        throw Error(where + "'" + std::string(field) + "' is not a number");
      row.push_back(value);
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    if (row.size() != columns)
      throw Error(where + "expected " + std::to_string(columns) + " numbers, found " +
                  std::to_string(row.size()));
    if (!rows.empty() && !(row[0] > rows.back()[0]))
      throw Error(where + "wavelengths must increase");
    rows.push_back(std::move(row));
  }
  if (rows.size() < 2) throw Error(path.string() + ": fewer than two rows of data");
  return rows;
}

}  // namespace

CieTables load_cie_tables(const fs::path& folder) {
  const fs::path observer_path = folder / kObserverFile;
  const fs::path illuminant_path = folder / kIlluminantFile;
  const auto observer = read_table(observer_path, 4);
  const auto illuminant = read_table(illuminant_path, 2);
  // Both tables share one grid, so the weight functions are products sample by sample; a
  // mismatch means a wrong file, not something to paper over by interpolation.
  if (observer.size() != illuminant.size())
    throw Error(illuminant_path.string() + ": " + std::to_string(illuminant.size()) +
                " wavelengths, but " + observer_path.string() + " has " +
                std::to_string(observer.size()));
  CieTables t;
  for (std::size_t i = 0; i < observer.size(); ++i) {
    if (observer[i][0] != illuminant[i][0])
      throw Error(illuminant_path.string() + ": wavelength " + std::to_string(illuminant[i][0]) +
                  " nm where " + observer_path.string() + " has " +
                  std::to_string(observer[i][0]) + " nm");
    t.lambda_nm.push_back(observer[i][0]);
    t.xbar.push_back(observer[i][1]);
    t.ybar.push_back(observer[i][2]);
    t.zbar.push_back(observer[i][3]);
    t.d65.push_back(illuminant[i][1]);
  }
  return t;
}

const CieTables& cie_tables() {
  // A function-local static is initialised exactly once even under concurrent first calls; if
  // loading throws, the next call tries again.
  static const CieTables tables = load_cie_tables(data_directory());
  return tables;
}

}  // namespace plumage
