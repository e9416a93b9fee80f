// The outlines of an SVG (svg_section.cpp) as a CrossSection: scale, flip (SVG y grows down,
// plumage's z up), materials by id prefix or fill, nesting by containment, and the two models
// of cross_section.hpp: the regions (for the full-wave solver) and, when every inner region is a
// full-width layer, the layered model (for the approximate solver).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/svg_section_detail.hpp"
#include "plumage/cross_section_io.hpp"
#include "plumage/geometry.hpp"
#include "plumage/input_file.hpp"

namespace plumage {

namespace {

using svg_detail::SvgOutline;

// A layer must reach this close to both sides of the body (fraction of its width): traced edges
// rarely meet the body's exactly, and layer_profile_at extends a boundary along its end segment.
constexpr double kLayerReach = 0.05;

double nm_per_unit(const svg_detail::SvgDrawing& d, const SvgImportOptions& o, const std::string& file) {
  if (o.um_per_unit) {
    if (!(*o.um_per_unit > 0.0) || !std::isfinite(*o.um_per_unit)) throw InputFileError(file, "um_per_unit must be positive");
    return 1000.0 * *o.um_per_unit;
  }
  if (!d.scale_bar_units) {
    throw InputFileError(file, "no scale: give um_per_unit, or draw a line with id 'scale_bar' and give scale_bar_um");
  }
  if (!o.scale_bar_um || !(*o.scale_bar_um > 0.0)) {
    throw InputFileError(file, "the drawing has a scale bar, but no (positive) scale_bar_um says how long it is");
  }
  return 1000.0 * *o.scale_bar_um / *d.scale_bar_units;
}

Material material_of(const SvgOutline& s, const SvgImportOptions& o, const std::string& file) {
  const Material* best = nullptr;
  std::size_t best_length = 0;
  for (const auto& [key, m] : o.materials) {
    if (!key.empty() && !s.id.empty() && s.id.starts_with(key) && key.size() > best_length) {
      best = &m;
      best_length = key.size();
    }
  }
  if (best) return *best;
  std::string fill;
  for (const auto& [key, m] : o.materials) {
    fill.clear();
    for (char c : key) fill.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    if (!s.fill.empty() && fill == s.fill) return m;
  }
  throw InputFileError(file, s.where + ": no material for fill '" + (s.fill.empty() ? "(none)" : s.fill) +
                                 "' (map its id prefix or fill colour to a material in `materials`)");
}

// A polyline with no edge longer than `max_nm` (each edge split evenly; the ends kept exactly).
Polyline refine(const Polyline& line, double max_nm, bool closed) {
  Polyline out;
  const std::size_t edges = closed ? line.size() : line.size() - 1;
  for (std::size_t k = 0; k < edges; ++k) {
    const Vec2 a = line[k], b = line[(k + 1) % line.size()];
    const int n = std::max(1, static_cast<int>(std::ceil(norm(b - a) / max_nm)));
    for (int j = 0; j < n; ++j) out.push_back({a.x + (b.x - a.x) * j / n, a.z + (b.z - a.z) * j / n});
  }
  if (!closed) out.push_back(line.back());
  return out;
}

// The vertices refine() makes of every outline, checked before any is made: coordinates in the
// thousands of µm at 10 nm edges would be millions of vertices per outline, and a damaged or
// mis-scaled file must be refused, not allocated (docs/architecture.md, "Readers").
inline constexpr double kMaxSvgRefinedVertices = 1e7;
void check_refined_size(const std::vector<SvgOutline>& outlines, double nm_per_unit, double max_nm,
                        const std::string& file) {
  double total = 0.0;
  for (const SvgOutline& s : outlines) {
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      const Vec2 a = s.points[k], b = s.points[(k + 1) % s.points.size()];
      const double edge = nm_per_unit * norm(b - a);
      if (!std::isfinite(edge)) throw InputFileError(file, s.where + ": a coordinate is too large");
      total += std::max(1.0, std::ceil(edge / max_nm));
    }
    if (total > kMaxSvgRefinedVertices)
      throw InputFileError(file, s.where + ": the outlines would need over 1e7 vertices of at most " +
                                     std::to_string(max_nm) + " nm (is the scale right? raise max_segment_nm)");
  }
}

struct Chains {
  Polyline upper, lower;  // left → right
  bool monotone = true;   // x strictly increasing along both
};

// A counter-clockwise outline's chains between its leftmost and rightmost vertices (the upper
// one of each if a side is vertical: the vertices of a vertical side between them are dropped,
// which does not change the outline).
Chains chains_of(const Polygon& p) {
  const std::size_t n = p.size();
  std::size_t lt = 0, lb = 0, rt = 0, rb = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (p[k].x < p[lt].x || (p[k].x == p[lt].x && p[k].z > p[lt].z)) lt = k;
    if (p[k].x < p[lb].x || (p[k].x == p[lb].x && p[k].z < p[lb].z)) lb = k;
    if (p[k].x > p[rt].x || (p[k].x == p[rt].x && p[k].z > p[rt].z)) rt = k;
    if (p[k].x > p[rb].x || (p[k].x == p[rb].x && p[k].z < p[rb].z)) rb = k;
  }
  Chains c;
  for (std::size_t k = lb;; k = (k + 1) % n) {  // counter-clockwise: the lower chain runs left → right
    c.lower.push_back(p[k]);
    if (k == rb) break;
  }
  for (std::size_t k = rt;; k = (k + 1) % n) {  // then the upper one right → left
    c.upper.push_back(p[k]);
    if (k == lt) break;
  }
  std::reverse(c.upper.begin(), c.upper.end());
  for (const Polyline* l : {&c.upper, &c.lower}) {
    for (std::size_t k = 1; k < l->size(); ++k) c.monotone = c.monotone && (*l)[k].x > (*l)[k - 1].x;
  }
  return c;
}

// A point just inside a counter-clockwise outline (left of the middle of its first edge).
Vec2 inner_point(const Polygon& p) {
  const Vec2 a = p[0], b = p[1], d = b - a;
  return a + 0.5 * d + 1e-6 * Vec2{-d.z, d.x};
}

bool same_line(const Polyline& a, const Polyline& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (norm(a[k] - b[k]) > 1e-6) return false;
  }
  return true;
}

RegionRole role_of(const Material& m) {
  if (m.kind() == Material::Kind::melanin) return RegionRole::melanosome;
  if (m.kind() == Material::Kind::air) return RegionRole::air_bubble;
  return RegionRole::film;
}

struct Shape {
  Polygon outline;
  Material material;
  const SvgOutline* source;
  double area;
};

// The layered model when every inner region is a full-width layer of the body; else the reason.
std::string add_layered_model(CrossSection& cs, const std::vector<Shape>& shapes, double max_nm) {
  const double left = cs.top.front().x, right = cs.top.back().x, reach = kLayerReach * (right - left);
  LayeredModel model;
  model.below_top = cs.regions[0].material;
  std::vector<std::pair<double, LayerBoundary>> inner;  // mean height, boundary
  auto mean_z = [](const Polyline& l) {
    double s = 0;
    for (const Vec2& v : l) s += v.z;
    return s / static_cast<double>(l.size());
  };
  for (std::size_t r = 1; r < cs.regions.size(); ++r) {  // all layers, or no layered model at all
    const Chains c = chains_of(shapes[r].outline);
    if (cs.regions[r].parent != 0 || !c.monotone || c.upper.front().x > left + reach || c.upper.back().x < right - reach) {
      return "region " + shapes[r].source->where + " is not a full-width layer";
    }
  }
  for (std::size_t r = 1; r < cs.regions.size(); ++r) {
    Chains c = chains_of(shapes[r].outline);
    c.upper = refine(c.upper, max_nm, false);
    c.lower = refine(c.lower, max_nm, false);
    cs.regions[r].outline = band_polygon(c.upper, c.lower);
    cs.regions[r].role = RegionRole::film;
    cs.regions[r].layer = static_cast<int>(r);
    if (same_line(c.upper, cs.top)) {
      model.below_top = cs.regions[r].material;
    } else {
      inner.push_back({mean_z(c.upper), {c.upper, cs.regions[r].material, {}, -1}});
    }
    if (!same_line(c.lower, cs.bottom)) inner.push_back({mean_z(c.lower), {c.lower, cs.regions[0].material, {}, -1}});
  }
  std::stable_sort(inner.begin(), inner.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (auto& b : inner) model.boundaries.push_back(std::move(b.second));
  model.boundaries.push_back({cs.bottom, Material::air(), {}, -1});
  cs.layered = std::move(model);
  return {};
}

}  // namespace

CrossSection parse_svg_cross_section(std::string_view text, const std::string& file, const SvgImportOptions& options) {
  const svg_detail::SvgDrawing drawing = svg_detail::read_svg_drawing(text, file);
  if (drawing.outlines.empty()) throw InputFileError(file, "no closed outline (<path>, <polygon> or <rect>)");
  if (!(options.max_segment_nm > 0.0)) throw InputFileError(file, "max_segment_nm must be positive");
  const double scale = nm_per_unit(drawing, options, file);
  check_refined_size(drawing.outlines, scale, options.max_segment_nm, file);
  std::vector<Shape> shapes;
  for (const SvgOutline& s : drawing.outlines) {
    Polygon p;
    for (const Vec2& v : s.points) p.push_back({scale * v.x, -scale * v.z});  // y down → z up
    if (signed_area(p) < 0.0) std::reverse(p.begin(), p.end());
    const double area = signed_area(p);
    shapes.push_back({std::move(p), material_of(s, options, file), &s, area});
  }
  // Largest first: the body, then every region after any region that can enclose it.
  std::stable_sort(shapes.begin(), shapes.end(), [](const Shape& a, const Shape& b) { return a.area > b.area; });
  double x_min = shapes[0].outline[0].x, x_max = x_min, z_max = shapes[0].outline[0].z;
  for (const Vec2& v : shapes[0].outline) {
    x_min = std::min(x_min, v.x);
    x_max = std::max(x_max, v.x);
    z_max = std::max(z_max, v.z);
  }
  const Vec2 shift{-0.5 * (x_min + x_max), -z_max};  // x centred on the body, its top at z = 0
  for (Shape& s : shapes) {
    for (Vec2& v : s.outline) v = v + shift;
  }

  CrossSection cs;
  cs.generator = "svg";
  cs.label = std::filesystem::path(file).stem().string();
  const Chains body = chains_of(shapes[0].outline);
  cs.top = refine(body.upper, options.max_segment_nm, false);
  cs.bottom = refine(body.lower, options.max_segment_nm, false);
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), shapes[0].material, RegionRole::body});
  for (std::size_t r = 1; r < shapes.size(); ++r) {
    int parent = 0;  // the smallest enclosing region (validate() reports one outside the body)
    const Vec2 probe = inner_point(shapes[r].outline);
    for (std::size_t q = 1; q < r; ++q) {
      if (point_in_polygon(probe, shapes[q].outline)) parent = static_cast<int>(q);
    }
    cs.regions.push_back({refine(shapes[r].outline, options.max_segment_nm, true), shapes[r].material,
                          role_of(shapes[r].material), parent});
  }
  const std::string why = add_layered_model(cs, shapes, options.max_segment_nm);
  if (!why.empty()) cs.label += " (no layered model: " + why + "; full-wave solver only)";
  return cs;
}

CrossSection read_svg_cross_section(const std::filesystem::path& file, const SvgImportOptions& options) {
  return parse_svg_cross_section(read_input_file(file, "SVG cross section"), file.string(), options);
}

}  // namespace plumage
