// FeatherLab's per-instance text files (featherlab_section.hpp) as curves: rows of numbers
// separated by commas (what MATLAB's writematrix writes) or by blanks, each row checked as it is
// read, and the curves of info cut out of the vertices of xyvals. Every refusal names the file,
// the line and the field.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "geometry/featherlab_detail.hpp"
#include "plumage/input_file.hpp"

namespace plumage::featherlab_detail {

namespace {

// One data row: its line number and its fields (views into the file's text).
struct Row {
  std::size_t line = 0;
  std::vector<std::string_view> fields;
};

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The fields of a line: comma-separated when it holds a comma (an empty field is kept, and
// refused by the caller), else blank-separated.
std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  if (line.find(',') != std::string_view::npos) {
    for (std::size_t at = 0;;) {
      const std::size_t comma = line.find(',', at);
      out.push_back(trim(line.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at)));
      if (comma == std::string_view::npos) break;
      at = comma + 1;
    }
    return out;
  }
  for (std::size_t at = line.find_first_not_of(" \t"); at != std::string_view::npos;
       at = line.find_first_not_of(" \t", at)) {
    const std::size_t end = std::min(line.find_first_of(" \t", at), line.size());
    out.push_back(line.substr(at, end - at));
    at = end;
  }
  return out;
}

// The non-blank lines of a file, each with `width` fields; at most `max_rows` of them.
std::vector<Row> read_rows(std::string_view text, const std::string& file, std::size_t width,
                           const std::string& layout, std::size_t max_rows) {
  std::vector<Row> rows;
  std::size_t line_no = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = trim(text.substr(at, end - at));
    at = end + 1;
    line_no += 1;
    if (line.empty()) continue;
    Row row{line_no, split_fields(line)};
    if (row.fields.size() != width) {
      throw InputFileError(file, "line " + std::to_string(line_no) + ": " + std::to_string(row.fields.size()) +
                                     " fields, expected " + std::to_string(width) + " (" + layout + ")");
    }
    if (rows.size() == max_rows) {
      throw InputFileError(file, "line " + std::to_string(line_no) + ": more than " + std::to_string(max_rows) +
                                     " rows (the limit for one instance)");
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw InputFileError(file, "no data (expected rows of " + layout + ")");
  return rows;
}

[[noreturn]] void fail_at(const std::string& file, std::size_t line, const std::string& message) {
  throw InputFileError(file, "line " + std::to_string(line) + ": " + message);
}

double number(const std::string& file, const Row& row, std::size_t k, std::string_view field) {
  const std::string_view text = row.fields[k];
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec == std::errc::result_out_of_range && r.ptr == text.data() + text.size()) {
    fail_at(file, row.line, std::string(field) + ": " + std::string(text) + " is not a finite number");
  }
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size()) {
    fail_at(file, row.line, std::string(field) + ": '" + std::string(text) + "' is not a number");
  }
  if (!std::isfinite(v)) fail_at(file, row.line, std::string(field) + ": " + std::string(text) + " is not a finite number");
  return v;
}

std::size_t count(const std::string& file, const Row& row, std::size_t k, std::string_view field) {
  const std::string_view text = row.fields[k];
  std::uint64_t v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size()) {
    fail_at(file, row.line, std::string(field) + ": '" + std::string(text) + "' is not a whole number");
  }
  if (v > kMaxFeatherLabVertices) {
    fail_at(file, row.line, std::string(field) + ": " + std::to_string(v) + " is over the limit of " +
                                std::to_string(kMaxFeatherLabVertices) + " vertices");
  }
  return static_cast<std::size_t>(v);
}

// The vertices of xyvals, nm (y is plumage's z: both point out of the feather).
std::vector<Vec2> read_vertices(const FeatherLabTexts& t, double nm_per_unit, std::vector<std::size_t>& lines) {
  const std::vector<Row> rows = read_rows(t.xyvals, t.xyvals_name, 2, "x,y", kMaxFeatherLabVertices);
  std::vector<Vec2> out;
  out.reserve(rows.size());
  for (const Row& row : rows) {
    const Vec2 v{nm_per_unit * number(t.xyvals_name, row, 0, "x"), nm_per_unit * number(t.xyvals_name, row, 1, "y")};
    if (!std::isfinite(v.x) || !std::isfinite(v.z)) fail_at(t.xyvals_name, row.line, "x,y: too large once scaled to nm");
    out.push_back(v);
    lines.push_back(row.line);
  }
  return out;
}

// The curves info cuts out of the vertices: consecutive, without gaps, covering every row.
std::vector<Polyline> cut_curves(const FeatherLabTexts& t, const std::vector<Vec2>& vertices,
                                 const std::vector<std::size_t>& vertex_lines, bool& reversed_top) {
  const std::vector<Row> rows = read_rows(t.info, t.info_name, 2, "start,count", kMaxFeatherLabVertices);
  if (rows.size() < 2) {
    fail_at(t.info_name, rows.front().line, "1 curve: a section needs at least the top and the bottom surface");
  }
  std::vector<Polyline> curves;
  std::size_t next = 0;
  for (const Row& row : rows) {
    const std::size_t start = count(t.info_name, row, 0, "start"), n = count(t.info_name, row, 1, "count");
    const std::string curve = "curve " + std::to_string(curves.size() + 1);
    if (start != next) {
      fail_at(t.info_name, row.line, "start: " + std::to_string(start) + ", but " + curve + " must start at row " +
                                         std::to_string(next) + " of xyvals (where the curve before it ends)");
    }
    if (n < 2) fail_at(t.info_name, row.line, "count: " + curve + " has " + std::to_string(n) + " vertices (at least 2)");
    if (n > vertices.size() - start) {
      fail_at(t.info_name, row.line, "count: " + curve + " ends at row " + std::to_string(start + n) + ", but " +
                                         t.xyvals_name + " has " + std::to_string(vertices.size()) + " rows");
    }
    Polyline line(vertices.begin() + static_cast<std::ptrdiff_t>(start),
                  vertices.begin() + static_cast<std::ptrdiff_t>(start + n));
    if (line.front() == line.back()) {
      fail_at(t.xyvals_name, vertex_lines[start + n - 1],
              curve + " is closed (a melanosome or bubble outline): only layered instances, open curves from the "
                      "top surface to the bottom surface, are read");
    }
    // Written right to left: the same curve, turned round.
    const bool reversed = line.back().x < line.front().x;
    if (reversed) std::reverse(line.begin(), line.end());
    // The top must be a graph over x (cross_section.hpp); a boundary below it may curl at its ends,
    // as the chain of a melanosome row does round its last melanosome.
    for (std::size_t k = 1; curves.empty() && k < line.size(); ++k) {
      if (!(line[k].x > line[k - 1].x)) {
        const std::size_t row = reversed ? start + n - 1 - k : start + k;
        fail_at(t.xyvals_name, vertex_lines[row], "x: curve 1, the top surface, is not monotone (x must increase, or "
                                                  "decrease, strictly along it)");
      }
    }
    if (curves.empty()) reversed_top = reversed;
    curves.push_back(std::move(line));
    next = start + n;
  }
  if (next != vertices.size()) {
    fail_at(t.info_name, rows.back().line, "the curves cover " + std::to_string(next) + " rows of " + t.xyvals_name +
                                               ", which has " + std::to_string(vertices.size()));
  }
  return curves;
}

std::vector<double> read_melanin_ratio(const FeatherLabTexts& t, std::size_t top_vertices) {
  const std::vector<Row> rows = read_rows(t.melanin_ratio, t.melanin_ratio_name, 1, "one melanin fraction",
                                          kMaxFeatherLabVertices);
  std::vector<double> out;
  for (const Row& row : rows) {
    const double f = number(t.melanin_ratio_name, row, 0, "melanin ratio");
    if (f < 0.0 || f > 1.0) fail_at(t.melanin_ratio_name, row.line, "melanin ratio: " + std::to_string(f) + " is outside [0, 1]");
    out.push_back(f);
  }
  if (out.size() + 2 != top_vertices) {
    fail_at(t.melanin_ratio_name, rows.back().line,
            std::to_string(out.size()) + " values, but the top surface has " + std::to_string(top_vertices) +
                " vertices (expected one per vertex but the two ends: " +
                std::to_string(top_vertices < 2 ? 0 : top_vertices - 2) + ")");
  }
  return out;
}

}  // namespace

FeatherLabCurves read_featherlab_curves(const FeatherLabTexts& t, const FeatherLabImportOptions& o) {
  if (!(o.um_per_unit > 0.0) || !std::isfinite(o.um_per_unit)) throw InputFileError(t.xyvals_name, "um_per_unit must be positive");
  std::vector<std::size_t> lines;
  const std::vector<Vec2> vertices = read_vertices(t, 1000.0 * o.um_per_unit, lines);
  FeatherLabCurves out;
  bool reversed_top = false;
  out.curves = cut_curves(t, vertices, lines, reversed_top);
  if (out.curves.size() != o.layers.size() + 1) {
    throw InputFileError(t.info_name, std::to_string(out.curves.size()) + " curves, so " +
                                          std::to_string(out.curves.size() - 1) + " layers between them, but `layers` gives " +
                                          std::to_string(o.layers.size()) + " materials");
  }
  if (o.melanin_ratio_layer) {
    out.melanin_ratio = read_melanin_ratio(t, out.curves.front().size());
    // The ratios follow the top's vertices as written.
    if (reversed_top) std::reverse(out.melanin_ratio.begin(), out.melanin_ratio.end());
  }
  return out;
}

}  // namespace plumage::featherlab_detail
