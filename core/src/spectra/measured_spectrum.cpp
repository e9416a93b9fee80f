// The reader of measured reflectance spectra (plumage/measured_spectrum.hpp): text files from
// spreadsheets and spectrometer software, whose dialects differ in delimiter, decimal mark,
// header lines, units and layout; the file is refused with file:line rather than guessed at
// where the layout is ambiguous or the values are not a reflectance spectrum.
#include "plumage/measured_spectrum.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>

#include "plumage/input_file.hpp"

namespace plumage {

namespace {

constexpr char kWhitespace = ' ';  // "delimiter" meaning runs of spaces or tabs

struct Line {
  std::size_t number = 0;  // 1-based, as an editor shows it
  std::string text;
};

struct Row {
  std::size_t line = 0;
  std::vector<double> values;
};

struct Table {
  std::vector<std::string> header;  // empty without a header line matching the data's width
  std::vector<Row> rows;
  char delimiter = ',';
  bool decimal_comma = false;  // ',' read as the decimal mark
  bool saw_comma = false;      // ... and the data had one
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n\"'");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n\"'");
  return s.substr(b, e - b + 1);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<Line> split_lines(const std::string& text) {
  std::vector<Line> lines;
  std::size_t start = 0, number = 1;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back({number++, std::move(line)});
    start = end + 1;
  }
  return lines;
}

std::vector<std::string> split_fields(const std::string& line, char delimiter) {
  std::vector<std::string> fields;
  if (delimiter == kWhitespace) {
    std::istringstream in(line);
    for (std::string f; in >> f;) fields.push_back(f);
    return fields;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(delimiter, start);
    fields.push_back(trim(line.substr(start, end == std::string::npos ? std::string::npos : end - start)));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  // A trailing delimiter (spreadsheet exports) leaves an empty last field: not a column.
  while (!fields.empty() && fields.back().empty()) fields.pop_back();
  return fields;
}

// A number in C syntax ("1.5", "-2e-3"), with ',' as the decimal mark when `decimal_comma`.
std::optional<double> parse_number(std::string field, bool decimal_comma) {
  field = trim(field);
  if (decimal_comma) std::replace(field.begin(), field.end(), ',', '.');
  if (!field.empty() && field.front() == '+') field.erase(0, 1);
  if (field.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
  return value;
}

// The delimiter of a data line: tab, else ';', else ',', else whitespace. With ';' or tab a ','
// can only be a decimal mark (European spreadsheet and spectrometer exports), also in later rows.
std::pair<char, bool> detect_delimiter(const std::string& line) {
  if (line.find('\t') != std::string::npos) return {'\t', true};
  if (line.find(';') != std::string::npos) return {';', true};
  if (line.find(',') != std::string::npos) {
    // "400,5 12,3" is whitespace-delimited with decimal commas; "400,12.3" is comma-delimited.
    const bool spaced = trim(line).find_first_of(" ") != std::string::npos && line.find('.') == std::string::npos;
    return spaced ? std::pair{kWhitespace, true} : std::pair{',', false};
  }
  return {kWhitespace, false};
}

std::optional<std::vector<double>> numeric_row(const std::string& line, char delimiter, bool decimal_comma) {
  std::vector<double> values;
  for (const auto& f : split_fields(line, delimiter)) {
    const auto v = parse_number(f, decimal_comma);
    if (!v) return std::nullopt;
    values.push_back(*v);
  }
  if (values.empty()) return std::nullopt;
  return values;
}

std::vector<std::string> header_names(const std::vector<std::string>& lines, char delimiter, std::size_t width) {
  std::vector<std::string> names = split_fields(lines.back(), delimiter);
  if (names.size() != width) return {};
  if (lines.size() >= 2) {
    const std::vector<std::string> above = split_fields(lines[lines.size() - 2], delimiter);
    if (above.size() == width)
      for (std::size_t c = 0; c < width; ++c) names[c] = above[c] + " " + names[c];
  }
  return names;
}

bool is_marker(const std::string& text, const char* word) {
  return text.rfind(">>>>>", 0) == 0 && lower(text).find(word) != std::string::npos;
}

// Header lines, then data rows: the first line that is all numbers starts the data; the last
// line before it, if it has as many fields, names the columns (with the line above it, when that
// has as many too: a names line over a units line, "Wave;Reflectance" over "[nm];[%]").
Table read_table(const std::filesystem::path& file, const std::string& text) {
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw InputFileError(file.string() + ":" + std::to_string(line), what);
  };
  Table table;
  std::vector<std::string> header_lines;
  std::size_t single_number_line = 0;
  bool in_data = false;
  std::size_t width = 0;
  // With a begin marker, everything before it is header, numbers or not ("Number of Pixels: 2048").
  bool before_begin = lower(text).find(">>>>>begin") != std::string::npos;
  for (const Line& line : split_lines(text)) {
    const std::string t = trim(line.text);
    if (t.empty()) continue;
    if (before_begin) {
      before_begin = !is_marker(t, "begin");
      continue;
    }
    if (is_marker(t, "end")) {
      if (in_data) break;
      continue;
    }
    const bool comment = t.front() == '#';
    if (!in_data) {
      const auto [delimiter, decimal_comma] = detect_delimiter(t);
      const auto values = comment ? std::nullopt : numeric_row(t, delimiter, decimal_comma);
      // A lone number before the data is metadata ("2048" pixels), not a one-column spectrum.
      if (!values || values->size() < 2) {
        if (values && !single_number_line) single_number_line = line.number;
        header_lines.push_back(comment ? trim(t.substr(1)) : t);
        continue;
      }
      in_data = true;
      table.delimiter = delimiter;
      table.decimal_comma = decimal_comma;
      width = values->size();
      if (width > kMaxMeasuredSpectrumColumns)
        fail(line.number,
             std::to_string(width) + " columns (at most " + std::to_string(kMaxMeasuredSpectrumColumns) + ")");
      if (!header_lines.empty()) table.header = header_names(header_lines, delimiter, width);
      table.saw_comma = decimal_comma && t.find(',') != std::string::npos;
      table.rows.push_back({line.number, *values});
      continue;
    }
    if (comment) continue;
    const auto values = numeric_row(t, table.delimiter, table.decimal_comma);
    if (!values) fail(line.number, "not a row of numbers: '" + t.substr(0, 60) + "'");
    table.saw_comma = table.saw_comma || (table.decimal_comma && t.find(',') != std::string::npos);
    if (values->size() != width)
      fail(line.number, std::to_string(values->size()) + " fields where the data has " + std::to_string(width));
    if (table.rows.size() == kMaxMeasuredSpectrumRows)
      fail(line.number, "more than " + std::to_string(kMaxMeasuredSpectrumRows) + " data rows");
    table.rows.push_back({line.number, *values});
  }
  if (table.rows.empty() && single_number_line)
    fail(single_number_line, "one column: a spectrum needs wavelength and reflectance columns");
  if (table.rows.empty()) throw InputFileError(file.string(), "no numeric data (no line of numbers found)");
  return table;
}

// The angle a reflectance column's header names ("R_30deg", "30°", "theta=45", "AOI 15"), if any.
std::optional<double> header_angle(const std::string& name) {
  static const std::regex with_unit(R"(([-+]?\d+(?:[.,]\d+)?)\s*(?:deg|°|º))", std::regex::icase);
  static const std::regex with_word(R"((?:theta|angle|aoi)\s*[=:_ ]?\s*([-+]?\d+(?:[.,]\d+)?))", std::regex::icase);
  std::smatch m;
  if (std::regex_search(name, m, with_unit) || std::regex_search(name, m, with_word)) {
    std::string number = m[1].str();
    std::replace(number.begin(), number.end(), ',', '.');
    return parse_number(number, false);
  }
  return std::nullopt;
}

bool names_any(const std::string& name, std::initializer_list<const char*> words) {
  const std::string l = lower(name);
  return std::any_of(words.begin(), words.end(), [&](const char* w) { return l.find(w) != std::string::npos; });
}

bool is_angle_column(const std::string& name) {
  return names_any(name, {"theta", "angle", "aoi"}) && !header_angle(name);
}

struct Layout {
  std::size_t wavelength = 0;
  std::optional<std::size_t> angle;      // an angle per row
  std::vector<std::size_t> reflectance;  // the columns taken
  bool angles_in_headers = false;
};

Layout choose_columns(const Table& table, const MeasuredSpectrumOptions& options, MeasuredSpectrum& out) {
  const std::size_t width = table.rows.front().values.size();  // ≥ 2: read_table
  Layout layout;
  const auto& h = table.header;
  if (!h.empty()) {
    for (std::size_t c = 0; c < width; ++c) {
      if (names_any(h[c], {"wave", "lambda", "nm", "wl"}) && !names_any(h[c], {"%", "refl"})) {
        layout.wavelength = c;
        break;
      }
    }
    for (std::size_t c = 0; c < width; ++c)
      if (c != layout.wavelength && is_angle_column(h[c])) layout.angle = c;
  }
  std::vector<std::size_t> candidates;
  for (std::size_t c = 0; c < width; ++c)
    if (c != layout.wavelength && c != layout.angle) candidates.push_back(c);
  if (candidates.empty())
    throw InputFileError(out.file.string() + ":" + std::to_string(table.rows.front().line), "no reflectance column");
  const bool all_angled =
      !h.empty() && !layout.angle &&
      std::all_of(candidates.begin(), candidates.end(), [&](std::size_t c) { return header_angle(h[c]).has_value(); });
  if (candidates.size() > 1 && all_angled) {
    layout.reflectance = candidates;
    layout.angles_in_headers = true;
    return layout;
  }
  // Without a choice, the column named reflectance if exactly one is (spectrometer exports put
  // sample, dark and reference counts beside it), else the first.
  std::size_t chosen = 0;
  if (options.sample_column) {
    chosen = *options.sample_column;
  } else if (!h.empty()) {
    const auto named =
        std::count_if(candidates.begin(), candidates.end(), [&](std::size_t c) { return names_any(h[c], {"refl"}); });
    if (named == 1)
      chosen = static_cast<std::size_t>(
          std::find_if(candidates.begin(), candidates.end(), [&](std::size_t c) { return names_any(h[c], {"refl"}); }) -
          candidates.begin());
  }
  if (chosen >= candidates.size())
    throw InputFileError(out.file.string(), "reflectance column " + std::to_string(chosen) +
                                                " asked for; the file has " + std::to_string(candidates.size()));
  layout.reflectance = {candidates[chosen]};
  layout.angles_in_headers = !h.empty() && !layout.angle && header_angle(h[layout.reflectance[0]]).has_value();
  if (candidates.size() > 1) {
    out.notes.push_back(std::to_string(candidates.size()) +
                        " reflectance columns without angles (samples): took column " +
                        std::to_string(layout.reflectance[0] + 1) +
                        (h.empty() ? std::string() : " '" + h[layout.reflectance[0]] + "'"));
  }
  return layout;
}

bool says_percent(const std::string& name) {
  return name.find('%') != std::string::npos || names_any(name, {"percent"});
}

// Units (µm → nm, percent → fraction), the checks of each value with its line, and the split into
// one curve per reflectance column, or per angle when the angle is a column.
void build_curves(MeasuredSpectrum& out, const Table& table, const Layout& layout) {
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw InputFileError(out.file.string() + ":" + std::to_string(line), what);
  };
  const auto& rows = table.rows;
  const auto& h = table.header;
  const bool micrometres =
      std::all_of(rows.begin(), rows.end(), [&](const Row& r) { return r.values[layout.wavelength] < 10.0; });
  if (micrometres) out.notes.push_back("wavelengths all below 10: read as micrometres, converted to nm");
  bool percent = false;
  for (std::size_t c : layout.reflectance) percent = percent || (!h.empty() && says_percent(h[c]));
  if (percent) {
    out.notes.push_back("reflectance in percent (the header says %)");
  } else {
    for (const Row& r : rows)
      for (std::size_t c : layout.reflectance) percent = percent || r.values[c] > 1.5;
    out.notes.push_back(percent ? "reflectance in percent (values above 1.5)"
                                : "reflectance as a fraction (no value above 1.5)");
  }
  // (curve index, row lines) in order of first appearance
  std::map<double, std::size_t> by_angle;
  std::vector<std::vector<std::size_t>> lines;
  const auto curve_for = [&](const Row& r, std::size_t k) -> std::size_t {
    if (!layout.angle) return k;
    const double theta = r.values[*layout.angle];
    if (!std::isfinite(theta) || theta < -90 || theta > 90)
      fail(r.line, "angle " + std::to_string(theta) + "° outside [-90, 90]");
    const auto [it, added] = by_angle.emplace(theta, out.curves.size());
    if (added) {
      std::ostringstream label;
      label << "theta = " << theta << "°";
      out.curves.push_back({label.str(), theta, {}, {}});
      lines.emplace_back();
    }
    return it->second;
  };
  if (!layout.angle) {
    for (std::size_t c : layout.reflectance) {
      const std::string label = h.empty() ? "column " + std::to_string(c + 1) : h[c];
      out.curves.push_back({label, layout.angles_in_headers ? header_angle(h[c]) : std::nullopt, {}, {}});
      lines.emplace_back();
    }
  }
  for (const Row& r : rows) {
    const double lambda = r.values[layout.wavelength] * (micrometres ? 1000.0 : 1.0);
    if (!std::isfinite(lambda) || lambda <= 0 || lambda > kFileMaxWavelengthNm)
      fail(r.line, "wavelength " + std::to_string(lambda) + " nm is not in (0, 1e6]");
    for (std::size_t k = 0; k < layout.reflectance.size(); ++k) {
      const double value = r.values[layout.reflectance[k]] / (percent ? 100.0 : 1.0);
      if (!std::isfinite(value)) fail(r.line, "reflectance is not finite");
      if (value < 0) fail(r.line, "negative reflectance " + std::to_string(value));
      const std::size_t i = curve_for(r, k);
      out.curves[i].lambda_nm.push_back(lambda);
      out.curves[i].reflectance.push_back(value);
      lines[i].push_back(r.line);
    }
  }
  for (std::size_t i = 0; i < out.curves.size(); ++i) {
    auto& curve = out.curves[i];
    const auto& l = curve.lambda_nm;
    if (l.size() < kMinMeasuredSpectrumPoints)
      fail(lines[i].front(), curve.label + ": " + std::to_string(l.size()) + " points (at least " +
                                 std::to_string(kMinMeasuredSpectrumPoints) + " needed)");
    const bool decreasing = l[1] < l[0];
    for (std::size_t j = 1; j < l.size(); ++j) {
      if (decreasing ? !(l[j] < l[j - 1]) : !(l[j] > l[j - 1]))
        fail(lines[i][j],
             "wavelengths not monotonic (" + std::to_string(l[j - 1]) + " then " + std::to_string(l[j]) + " nm)");
    }
    if (decreasing) {
      std::reverse(curve.lambda_nm.begin(), curve.lambda_nm.end());
      std::reverse(curve.reflectance.begin(), curve.reflectance.end());
    }
  }
}

}  // namespace

MeasuredSpectrum read_measured_spectrum(const std::filesystem::path& file, const MeasuredSpectrumOptions& options) {
  MeasuredSpectrum out;
  out.file = file;
  std::string text = read_input_file(file, "measured spectrum", kMaxMeasuredSpectrumBytes);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // the UTF-8 byte-order mark of spreadsheet exports
  const Table table = read_table(file, text);
  const char* delimiter = table.delimiter == ','    ? "comma"
                          : table.delimiter == ';'  ? "semicolon"
                          : table.delimiter == '\t' ? "tab"
                                                    : "whitespace";
  out.notes.push_back(std::string(delimiter) + "-delimited" + (table.saw_comma ? ", decimal comma" : "") + ", " +
                      std::to_string(table.rows.size()) + " data rows from line " +
                      std::to_string(table.rows.front().line));
  const Layout layout = choose_columns(table, options, out);
  build_curves(out, table, layout);
  return out;
}

}  // namespace plumage
