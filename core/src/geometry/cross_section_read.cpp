// Reading cross sections: the text format "plumage-cross-section 1" (docs/formats.md) that
// write_cross_section_text (cross_section_io.cpp) writes, back into a CrossSection, exactly.
//
// Hardening (docs/architecture.md, "Readers"): the file comes through InputFile; every count is
// checked against kMaxCrossSectionCount and against the bytes left in the file (each data line
// has a known least length) before anything it sizes is allocated; every number must be finite;
// every index must point where the solvers will follow it. Errors name the file and the line.
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include "plumage/cross_section_io.hpp"
#include "plumage/input_file.hpp"

namespace plumage {

namespace {

constexpr std::string_view kMagic = "plumage-cross-section";

// The words of one line: `word()` takes the next space-separated one, `rest()` all that is left
// (a label, a material name or a crystal path, which may hold spaces).
class Words {
 public:
  explicit Words(std::string_view line) : line_(line) {}
  std::string_view word() {
    const std::size_t end = std::min(line_.find(' ', pos_), line_.size());
    const std::string_view w = line_.substr(pos_, end - pos_);
    pos_ = end < line_.size() ? end + 1 : end;
    return w;
  }
  std::string_view rest() {
    const std::string_view r = line_.substr(pos_);
    pos_ = line_.size();
    return r;
  }
  bool done() const { return pos_ >= line_.size(); }

 private:
  std::string_view line_;
  std::size_t pos_ = 0;
};

// The file's lines, with the number of the current one for the messages.
class Lines {
 public:
  Lines(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  // The next line (without its '\n'); a file that ends first is truncated.
  std::string_view next(std::string_view expecting) {
    if (pos_ >= text_.size()) {
      line_no_ += 1;
      fail("truncated file: expected " + std::string(expecting));
    }
    const std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) {
      line_no_ += 1;
      fail("truncated file: the last line has no end (expected " + std::string(expecting) + ")");
    }
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    line_no_ += 1;
    return line;
  }
  std::string_view peek_word() const {
    const std::string_view rest = text_.substr(pos_);
    return rest.substr(0, std::min(rest.find_first_of(" \n"), rest.size()));
  }
  bool at_end() const { return pos_ >= text_.size(); }

  // A count read from the current line: at most kMaxCrossSectionCount, and no more lines of at
  // least `line_bytes` bytes each than the rest of the file holds.
  std::size_t count(std::string_view text, std::string_view field, std::size_t line_bytes) const {
    std::uint64_t n = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size()) {
      fail(std::string(field) + ": '" + std::string(text) + "' is not a count");
    }
    if (n > kMaxCrossSectionCount) {
      fail(std::string(field) + ": " + std::to_string(n) + " is over the limit of " +
           std::to_string(kMaxCrossSectionCount));
    }
    const std::size_t left = text_.size() - pos_;
    if (n > left / line_bytes) {
      fail(std::string(field) + ": " + std::to_string(n) + " lines cannot fit in the " + std::to_string(left) +
           " bytes left in the file (truncated or damaged)");
    }
    return static_cast<std::size_t>(n);
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw InputFileError(file_, "line " + std::to_string(line_no_) + ": " + message);
  }

 private:
  std::string_view text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  std::size_t line_no_ = 0;
};

// "'key suffix'" for the messages (appended: GCC 12 warns falsely on "'" + std::string(...)).
std::string quoted(std::string_view key, std::string_view suffix) {
  std::string s(1, '\'');
  s.append(key).append(suffix).push_back('\'');
  return s;
}

double number(const Lines& lines, std::string_view text, std::string_view field) {
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size()) {
    lines.fail(std::string(field) + ": '" + std::string(text) + "' is not a number");
  }
  if (!std::isfinite(v)) lines.fail(std::string(field) + ": " + std::string(text) + " is not finite");
  return v;
}

template <class Int>
Int integer(const Lines& lines, std::string_view text, std::string_view field) {
  Int v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size()) {
    lines.fail(std::string(field) + ": '" + std::string(text) + "' is not an integer");
  }
  return v;
}

// The next word must be `key`; returns the word after it.
std::string_view keyed(const Lines& lines, Words& words, std::string_view key) {
  const std::string_view w = words.word();
  if (w != key) lines.fail("expected '" + std::string(key) + "', found '" + std::string(w) + "'");
  return words.word();
}

// The next word must be `key`; returns all the line holds after it (a material name).
std::string_view keyed_rest(const Lines& lines, Words& words, std::string_view key) {
  const std::string_view w = words.word();
  if (w != key) lines.fail("expected '" + std::string(key) + "', found '" + std::string(w) + "'");
  return words.rest();
}

void no_more(const Lines& lines, const Words& words) {
  if (!words.done()) lines.fail("unexpected text at the end of the line");
}

Material material(const Lines& lines, std::string_view text) {
  try {
    return parse_material_text(text);
  } catch (const std::invalid_argument& e) {
    lines.fail(std::string("material: ") + e.what());
  }
}

RegionRole role(const Lines& lines, std::string_view text) {
  for (int r = 0; r <= static_cast<int>(RegionRole::film); ++r) {
    if (role_name(static_cast<RegionRole>(r)) == text) return static_cast<RegionRole>(r);
  }
  lines.fail("unknown region role '" + std::string(text) + "'");
}

// "KEY N" followed by N lines of one number each.
std::vector<double> values(Lines& lines, std::string_view key, std::string_view field, std::size_t n) {
  std::vector<double> out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    Words w(lines.next(std::string(key) + " value"));
    out.push_back(number(lines, w.word(), field));
    no_more(lines, w);
  }
  return out;
}

Polyline points(Lines& lines, std::string_view field, std::size_t n) {
  Polyline out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    Words w(lines.next(std::string(field) + " vertex 'x z'"));
    const double x = number(lines, w.word(), "x");
    const double z = number(lines, w.word(), "z");
    no_more(lines, w);
    out.push_back({x, z});
  }
  return out;
}

// "KEY N" then its N points; at least `least` of them.
Polyline polyline(Lines& lines, std::string_view key, std::size_t least) {
  Words w(lines.next(quoted(key, " N")));
  if (w.word() != key) lines.fail("expected '" + std::string(key) + " N'");
  const std::size_t n = lines.count(w.word(), key, 4);
  no_more(lines, w);
  if (n < least) lines.fail(std::string(key) + ": " + std::to_string(n) + " vertices, at least " + std::to_string(least) + " needed");
  return points(lines, key, n);
}

Region region(Lines& lines, std::size_t index) {
  Words w(lines.next("region " + std::to_string(index)));
  if (w.word() != "region") lines.fail("expected 'region " + std::to_string(index) + " ...'");
  if (integer<std::size_t>(lines, w.word(), "region index") != index) {
    lines.fail("region index out of order: expected " + std::to_string(index));
  }
  Region r;
  r.role = role(lines, w.word());
  r.parent = integer<int>(lines, keyed(lines, w, "parent"), "parent");
  // Parents precede their children: anything else would send validate() and the solvers outside
  // the list.
  if (r.parent < -1 || r.parent >= static_cast<int>(index)) {
    lines.fail("parent " + std::to_string(r.parent) + " of region " + std::to_string(index) +
               ": a parent is -1 (in air) or an earlier region");
  }
  r.layer = integer<int>(lines, keyed(lines, w, "layer"), "layer");
  r.members = integer<int>(lines, keyed(lines, w, "members"), "members");
  r.size_nm = number(lines, keyed(lines, w, "size_nm"), "size_nm");
  const std::size_t n = lines.count(keyed(lines, w, "vertices"), "vertices", 4);
  r.material = material(lines, keyed_rest(lines, w, "material"));
  if (n < 3) lines.fail("open outline: region " + std::to_string(index) + " has " + std::to_string(n) + " vertices, a closed polygon needs at least 3");
  r.outline = points(lines, "region", n);
  if (r.outline.front() == r.outline.back()) {
    lines.fail("region " + std::to_string(index) + ": the outline repeats its first vertex at its end (polygons are closed implicitly)");
  }
  return r;
}

LayerBoundary boundary(Lines& lines, std::size_t index, std::size_t count) {
  Words w(lines.next("boundary " + std::to_string(index)));
  if (w.word() != "boundary") lines.fail("expected 'boundary " + std::to_string(index) + " ...'");
  if (integer<std::size_t>(lines, w.word(), "boundary index") != index) {
    lines.fail("boundary index out of order: expected " + std::to_string(index));
  }
  LayerBoundary b;
  b.closes = integer<int>(lines, keyed(lines, w, "closes"), "closes");
  if (b.closes != -1 && (b.closes <= static_cast<int>(index) || b.closes >= static_cast<int>(count))) {
    lines.fail("closes " + std::to_string(b.closes) + ": a bracket closes at a later boundary (or -1 for none)");
  }
  const std::string_view n_text = keyed(lines, w, "points");
  const std::string_view f_text = keyed(lines, w, "fraction");
  if (f_text != "0" && f_text != "1") lines.fail("fraction: expected 0 or 1, found '" + std::string(f_text) + "'");
  const bool with_fraction = f_text == "1";
  const std::size_t n = lines.count(n_text, "points", with_fraction ? 6 : 4);
  b.below = material(lines, keyed_rest(lines, w, "below"));
  if (with_fraction && b.below.kind() != Material::Kind::mixture) {
    lines.fail("fraction 1 needs a mixture below the boundary, not " + b.below.name());
  }
  if (n < 2) lines.fail("boundary " + std::to_string(index) + ": " + std::to_string(n) + " points, at least 2 needed");
  b.points.reserve(n);
  if (with_fraction) b.fraction.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    Words p(lines.next(with_fraction ? "boundary point 'x z f'" : "boundary point 'x z'"));
    const double x = number(lines, p.word(), "x");
    const double z = number(lines, p.word(), "z");
    b.points.push_back({x, z});
    if (with_fraction) {
      const double f = number(lines, p.word(), "fraction");
      if (!(f >= 0.0 && f <= 1.0)) lines.fail("fraction " + std::to_string(f) + " is outside [0, 1]");
      b.fraction.push_back(f);
    }
    no_more(lines, p);
  }
  return b;
}

LayeredModel layered(Lines& lines, Words& w) {
  const std::size_t n = lines.count(w.word(), "layered", 16);
  LayeredModel model;
  model.below_top = material(lines, keyed_rest(lines, w, "below_top"));
  model.boundaries.reserve(n);
  for (std::size_t j = 0; j < n; ++j) model.boundaries.push_back(boundary(lines, j, n));
  return model;
}

CrystalModel crystal(Lines& lines, Words& w, std::size_t top_vertices) {
  CrystalModel c;
  c.crystal_name = std::string(w.word());
  const std::size_t n = lines.count(w.word(), "crystal regularity", 2);
  c.crystal = std::string(w.rest());
  if (c.crystal_name.empty()) lines.fail("crystal: the crystal's name is missing");
  if (n != top_vertices) {
    lines.fail("crystal: " + std::to_string(n) + " regularity values for " + std::to_string(top_vertices) +
               " top vertices (one per top vertex)");
  }
  c.regularity = values(lines, "crystal", "regularity", n);
  return c;
}

std::vector<Disc> melanosomes(Lines& lines, Words& w) {
  const std::size_t n = lines.count(w.word(), "melanosomes", 8);
  no_more(lines, w);
  std::vector<Disc> out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    Words d(lines.next("melanosome 'x z diameter_nm row'"));
    Disc disc;
    disc.center.x = number(lines, d.word(), "x");
    disc.center.z = number(lines, d.word(), "z");
    disc.diameter_nm = number(lines, d.word(), "diameter_nm");
    disc.row = integer<int>(lines, d.word(), "row");
    no_more(lines, d);
    out.push_back(disc);
  }
  return out;
}

// "KEY value" (the value to the end of the line).
std::string_view header_value(Lines& lines, std::string_view key) {
  Words w(lines.next(quoted(key, " ...")));
  if (w.word() != key) lines.fail("expected '" + std::string(key) + " ...'");
  return w.rest();
}

void read_header(Lines& lines, CrossSection& cs) {
  {
    Words w(lines.next("the header 'plumage-cross-section 1'"));
    if (w.word() != kMagic) lines.fail("not a plumage cross section (bad header; expected 'plumage-cross-section 1')");
    const std::string_view version = w.rest();
    if (version != "1") lines.fail("cross-section format version '" + std::string(version) + "', this build reads 1");
  }
  cs.label = std::string(header_value(lines, "label"));
  cs.generator = std::string(header_value(lines, "generator"));
  cs.instance = integer<std::uint64_t>(lines, header_value(lines, "instance"), "instance");
  cs.seed = integer<std::uint64_t>(lines, header_value(lines, "seed"), "seed");
  if (header_value(lines, "units") != "nm") lines.fail("units: only 'nm' is written by plumage");
}

}  // namespace

CrossSection parse_cross_section_text(std::string_view text, const std::string& file) {
  Lines lines(text, file);
  CrossSection cs;
  read_header(lines, cs);
  cs.top = polyline(lines, "top", 2);
  {
    Words w(lines.next("'top_roughness N'"));
    if (w.word() != "top_roughness") lines.fail("expected 'top_roughness N'");
    const std::size_t n = lines.count(w.word(), "top_roughness", 2);
    no_more(lines, w);
    if (n != 0 && n != cs.top.size()) {
      lines.fail("top_roughness: " + std::to_string(n) + " values for " + std::to_string(cs.top.size()) +
                 " top vertices (0 or one per top vertex)");
    }
    cs.top_roughness_nm = values(lines, "top_roughness", "top_roughness", n);
  }
  cs.bottom = polyline(lines, "bottom", 2);
  {
    Words w(lines.next("'regions R'"));
    if (w.word() != "regions") lines.fail("expected 'regions R'");
    const std::size_t n = lines.count(w.word(), "regions", 16);
    no_more(lines, w);
    cs.regions.reserve(n);
    for (std::size_t i = 0; i < n; ++i) cs.regions.push_back(region(lines, i));
  }
  // The optional reduced models, then the melanosomes and the end, in the writer's order.
  if (lines.peek_word() == "layered") {
    Words w(lines.next("'layered B below_top NAME'"));
    w.word();
    cs.layered = layered(lines, w);
  }
  if (lines.peek_word() == "crystal") {
    Words w(lines.next("'crystal NAME Q PATH'"));
    w.word();
    cs.crystal = crystal(lines, w, cs.top.size());
  }
  {
    Words w(lines.next("'melanosomes D'"));
    if (w.word() != "melanosomes") lines.fail("expected 'layered', 'crystal' or 'melanosomes D'");
    cs.melanosomes = melanosomes(lines, w);
  }
  {
    Words w(lines.next("'end'"));
    if (w.word() != "end" || !w.done()) lines.fail("expected 'end'");
  }
  if (!lines.at_end()) {
    lines.next("nothing");
    lines.fail("text after 'end'");
  }
  return cs;
}

CrossSection read_cross_section_text(const std::filesystem::path& file) {
  return parse_cross_section_text(read_input_file(file, "cross section"), file.string());
}

}  // namespace plumage
