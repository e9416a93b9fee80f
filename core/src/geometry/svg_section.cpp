// Cross sections from SVG (issue 25 (c)): the subset a vector editor writes when outlines are
// traced over a TEM image with straight segments. A small reader of that subset (no XML
// library: plumage takes no new dependency): elements, their attributes and line numbers;
// <path d> with M L H V Z (absolute and relative), <polygon points>, <rect>, and a <line> or
// path as the scale bar. Everything else (<svg>, <g>, <image> of the micrograph, <text>...) is
// skipped, except a transform, which is refused: the traced geometry would silently move.
// The outlines become a CrossSection in svg_section_model.cpp.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "geometry/svg_section_detail.hpp"
#include "plumage/input_file.hpp"

namespace plumage::svg_detail {

namespace {

struct Element {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  int line = 0;
  const std::string* find(std::string_view key) const {
    for (const auto& [k, v] : attributes) {
      if (k == key) return &v;
    }
    return nullptr;
  }
};

class Reader {
 public:
  Reader(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  // The next start tag (or empty element), or false at the end.
  bool next(Element& e) {
    while (true) {
      const std::size_t lt = text_.find('<', at_);
      if (lt == std::string_view::npos) return false;
      advance(lt);
      if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("<?")) {
        skip_past("?>");
      } else if (starts("<!")) {
        skip_past(">");
      } else if (starts("</")) {
        skip_past(">");
      } else {
        read_tag(e);
        return true;
      }
    }
  }

 private:
  bool starts(std::string_view s) const { return text_.substr(at_, s.size()) == s; }
  void advance(std::size_t to) {
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<long>(at_), text_.begin() + static_cast<long>(to), '\n'));
    at_ = to;
  }
  void skip_past(std::string_view end) {
    const std::size_t e = text_.find(end, at_);
    if (e == std::string_view::npos) fail("line " + std::to_string(line_) + ": unterminated markup");
    advance(e + end.size());
  }
  [[noreturn]] void fail(const std::string& message) const { throw InputFileError(file_, message); }

  void read_tag(Element& e) {
    e = {};
    e.line = line_;
    std::size_t p = at_ + 1;
    while (p < text_.size() && !std::isspace(static_cast<unsigned char>(text_[p])) && text_[p] != '>' && text_[p] != '/') ++p;
    e.name = std::string(text_.substr(at_ + 1, p - at_ - 1));
    while (true) {
      while (p < text_.size() && std::isspace(static_cast<unsigned char>(text_[p]))) ++p;
      if (p >= text_.size()) fail("line " + std::to_string(e.line) + ": unterminated <" + e.name + ">");
      if (text_[p] == '>' || text_[p] == '/') break;
      const std::size_t eq = text_.find('=', p);
      if (eq == std::string_view::npos) fail("line " + std::to_string(e.line) + ": attribute without a value");
      std::string key(text_.substr(p, eq - p));
      while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
      std::size_t q = eq + 1;
      while (q < text_.size() && std::isspace(static_cast<unsigned char>(text_[q]))) ++q;
      if (q >= text_.size() || (text_[q] != '"' && text_[q] != '\'')) {
        fail("line " + std::to_string(e.line) + ": attribute '" + key + "' without a quoted value");
      }
      const std::size_t close = text_.find(text_[q], q + 1);
      if (close == std::string_view::npos) fail("line " + std::to_string(e.line) + ": unterminated attribute '" + key + "'");
      e.attributes.emplace_back(std::move(key), std::string(text_.substr(q + 1, close - q - 1)));
      p = close + 1;
    }
    const std::size_t gt = text_.find('>', p);
    if (gt == std::string_view::npos) fail("line " + std::to_string(e.line) + ": unterminated <" + e.name + ">");
    advance(gt + 1);
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t at_ = 0;
  int line_ = 1;
};

std::string element_name(const Element& e) {
  const std::string* id = e.find("id");
  return (id ? "element '" + *id + "'" : "element <" + e.name + ">") + " (line " + std::to_string(e.line) + ")";
}

// Numbers of a path or points list: separators are spaces and commas; "1.5.5" and "1-2" are two
// numbers each, as SVG allows.
class Numbers {
 public:
  explicit Numbers(std::string_view s) : s_(s) {}
  void skip_separators() {
    while (p_ < s_.size() && (std::isspace(static_cast<unsigned char>(s_[p_])) || s_[p_] == ',')) ++p_;
  }
  bool at_number() {
    skip_separators();
    return p_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[p_])) || s_[p_] == '-' || s_[p_] == '+' || s_[p_] == '.');
  }
  bool at_end() {
    skip_separators();
    return p_ >= s_.size();
  }
  char command() { return s_[p_++]; }
  bool number(double& out) {
    if (!at_number()) return false;
    const std::string rest(s_.substr(p_, std::min<std::size_t>(s_.size() - p_, 64)));
    char* end = nullptr;
    out = std::strtod(rest.c_str(), &end);
    if (end == rest.c_str() || !std::isfinite(out)) return false;
    p_ += static_cast<std::size_t>(end - rest.c_str());
    return true;
  }

 private:
  std::string_view s_;
  std::size_t p_ = 0;
};

// <path d>: one subpath of straight segments; `closed` when it ends with Z or returns to its start.
std::vector<Vec2> path_points(const Element& e, const std::string& d, bool& closed, const std::string& file) {
  auto fail = [&](const std::string& m) -> void { throw InputFileError(file, element_name(e) + ": " + m); };
  Numbers in(d);
  std::vector<Vec2> pts;
  Vec2 cur{};
  char cmd = 0;
  closed = false;
  while (!in.at_end()) {
    if (!in.at_number()) {
      cmd = in.command();
      if (closed) fail("more than one outline in one path (draw each region as its own element)");
      if (cmd == 'Z' || cmd == 'z') {
        closed = true;
        continue;
      }
      if (std::string_view("MmLlHhVv").find(cmd) == std::string_view::npos) {
        fail(std::string("path command '") + cmd + "' is not supported (only straight segments M L H V Z: "
             "flatten curves in the editor)");
      }
      if ((cmd == 'M' || cmd == 'm') && !pts.empty()) fail("more than one outline in one path (draw each region as its own element)");
    } else if (cmd == 0) {
      fail("path data does not start with a command");
    }
    const bool rel = std::islower(static_cast<unsigned char>(cmd)) != 0;
    double a = 0, b = 0;
    if (!in.number(a)) fail(std::string("a number expected after '") + cmd + "'");
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    if (up == 'H') {
      cur.x = rel ? cur.x + a : a;
    } else if (up == 'V') {
      cur.z = rel ? cur.z + a : a;
    } else {
      if (!in.number(b)) fail(std::string("a coordinate pair expected after '") + cmd + "'");
      cur = rel ? Vec2{cur.x + a, cur.z + b} : Vec2{a, b};
    }
    pts.push_back(cur);
    if (up == 'M') cmd = rel ? 'l' : 'L';  // pairs after a moveto are linetos
  }
  return pts;
}

std::vector<Vec2> polygon_points(const Element& e, const std::string& text, const std::string& file) {
  Numbers in(text);
  std::vector<Vec2> pts;
  double a = 0, b = 0;
  while (!in.at_end()) {
    if (!in.number(a) || !in.number(b)) throw InputFileError(file, element_name(e) + ": bad points list");
    pts.push_back({a, b});
  }
  return pts;
}

double attribute_number(const Element& e, std::string_view key, const std::string& file, bool required = true) {
  const std::string* v = e.find(key);
  if (!v) {
    if (!required) return 0.0;
    throw InputFileError(file, element_name(e) + ": no '" + std::string(key) + "'");
  }
  Numbers in(*v);
  double x = 0;
  if (!in.number(x) || !in.at_end()) {
    throw InputFileError(file, element_name(e) + ": '" + std::string(key) + "' is not a number (units are not supported)");
  }
  return x;
}

std::string fill_of(const Element& e) {
  std::string fill;
  if (const std::string* f = e.find("fill")) fill = *f;
  if (const std::string* style = e.find("style")) {  // a style property overrides the attribute
    const std::size_t at = style->find("fill:");
    if (at != std::string::npos) {
      const std::size_t end = style->find(';', at);
      fill = style->substr(at + 5, end == std::string::npos ? std::string::npos : end - at - 5);
    }
  }
  std::string out;
  for (char c : fill) {
    if (!std::isspace(static_cast<unsigned char>(c))) out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

}  // namespace

SvgDrawing read_svg_drawing(std::string_view text, const std::string& file) {
  Reader reader(text, file);
  SvgDrawing out;
  Element e;
  while (reader.next(e)) {
    const bool shape = e.name == "path" || e.name == "polygon" || e.name == "rect" || e.name == "line" || e.name == "polyline";
    if (e.find("transform") && (shape || e.name == "g")) {
      throw InputFileError(file, element_name(e) + ": transforms are not supported (apply them in the editor, "
                                 "e.g. Inkscape's Path > Object to Path)");
    }
    if (!shape) continue;
    const std::string* id = e.find("id");
    SvgOutline o{id ? *id : std::string{}, fill_of(e), element_name(e), {}, false};
    if (e.name == "path") {
      const std::string* d = e.find("d");
      if (!d) throw InputFileError(file, o.where + ": path without 'd'");
      o.points = path_points(e, *d, o.closed, file);
    } else if (e.name == "polygon" || e.name == "polyline") {
      const std::string* pts = e.find("points");
      if (!pts) throw InputFileError(file, o.where + ": no 'points'");
      o.points = polygon_points(e, *pts, file);
      o.closed = e.name == "polygon";
    } else if (e.name == "rect") {
      const double x = attribute_number(e, "x", file, false), y = attribute_number(e, "y", file, false);
      const double w = attribute_number(e, "width", file), h = attribute_number(e, "height", file);
      if (!(w > 0.0 && h > 0.0)) throw InputFileError(file, o.where + ": a rect needs a positive width and height");
      o.points = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
      o.closed = true;
    } else {
      o.points = {{attribute_number(e, "x1", file), attribute_number(e, "y1", file)},
                  {attribute_number(e, "x2", file), attribute_number(e, "y2", file)}};
    }
    if (o.id == "scale_bar") {
      if (o.points.size() < 2) throw InputFileError(file, o.where + ": a scale bar needs two points");
      const Vec2 d = o.points.back() - o.points.front();
      out.scale_bar_units = norm(d);
      if (!(out.scale_bar_units > 0.0)) throw InputFileError(file, o.where + ": the scale bar has no length");
      continue;
    }
    // A closing vertex equal to the first is the same corner, not an edge of length 0.
    if (o.points.size() > 1 && o.points.back() == o.points.front()) {
      o.points.pop_back();
      o.closed = true;
    }
    if (!o.closed) throw InputFileError(file, o.where + ": open outline (close it: end the path with Z)");
    if (o.points.size() < 3) throw InputFileError(file, o.where + ": an outline needs at least 3 points");
    out.outlines.push_back(std::move(o));
  }
  return out;
}

}  // namespace plumage::svg_detail
