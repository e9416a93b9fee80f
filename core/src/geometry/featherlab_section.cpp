// The curves of a FeatherLab instance (featherlab_read.cpp) as a CrossSection: the layered model
// (curve 1 the top, curves 2 .. K the layer boundaries with the config's material below each,
// curve K the bottom, air below it; the melanin ratio as the per-vertex fraction of one mixture
// layer) and the region model (the body between the top and the bottom, and one band per layer
// whose material is not the body's), checked by validate() like every section.
#include <algorithm>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "geometry/featherlab_detail.hpp"
#include "plumage/error.hpp"
#include "plumage/geometry.hpp"
#include "plumage/input_file.hpp"

namespace plumage {

namespace {

// A layer band stops this many top spacings short of the outermost common x of all curves:
// near the barbule's ends the curves pinch together (FeatherLab's offset curves lean inward),
// and the band must stay inside the body, as the procedural layered_barbule's do.
constexpr double kBandMarginSpacings = 4.0;

// The melanin ratio per top vertex: FeatherLab gives every vertex but the two ends, which take
// their neighbour's value.
std::vector<double> ratio_per_top_vertex(const std::vector<double>& ratio) {
  std::vector<double> v;
  v.reserve(ratio.size() + 2);
  v.push_back(ratio.front());
  v.insert(v.end(), ratio.begin(), ratio.end());
  v.push_back(ratio.back());
  return v;
}

// The fraction at every vertex of `curve`: vertex j takes top vertex j's value when the curve has
// the top's vertices (FeatherLab's boundaries are offsets of the top, vertex by vertex), else the
// value interpolated linearly in x between the top's vertices (clamped at the ends).
std::vector<double> fraction_on(const Polyline& curve, const Polyline& top, const std::vector<double>& per_top) {
  if (curve.size() == top.size()) return per_top;
  std::vector<double> out;
  out.reserve(curve.size());
  for (const Vec2& p : curve) {
    const auto it = std::lower_bound(top.begin(), top.end(), p.x, [](const Vec2& v, double x) { return v.x < x; });
    if (it == top.begin()) {
      out.push_back(per_top.front());
    } else if (it == top.end()) {
      out.push_back(per_top.back());
    } else {
      const std::size_t j = static_cast<std::size_t>(it - top.begin());
      const double s = (p.x - top[j - 1].x) / (top[j].x - top[j - 1].x);
      out.push_back((1.0 - s) * per_top[j - 1] + s * per_top[j]);
    }
  }
  return out;
}

RegionRole role_of(const Material& m) {
  switch (m.kind()) {
    case Material::Kind::air: return RegionRole::air_gap;
    case Material::Kind::mixture: return RegionRole::granular_layer;
    default: return RegionRole::film;
  }
}

void check_options(const FeatherLabImportOptions& o) {
  if (o.layers.empty()) throw Error("featherlab import: `layers` gives no material");
  if (o.melanin_ratio_layer) {
    const std::size_t k = *o.melanin_ratio_layer;
    if (k < 1 || k >= o.layers.size()) {
      throw Error("featherlab import: melanin_ratio_layer " + std::to_string(k + 1) + " is not a layer below the "
                  "first (layers 2 to " + std::to_string(o.layers.size()) + ")");
    }
    if (o.layers[k].kind() != Material::Kind::mixture) {
      throw Error("featherlab import: the melanin ratio layer's material must be a mixture ({mix: [host, melanin], ...})");
    }
  }
}

// The bands of the layers whose material is not the body's, cut to the x that all curves share.
void add_layer_regions(CrossSection& cs, const std::vector<Polyline>& curves, const LayeredModel& model,
                       const Material& body) {
  double lo = curves.front().front().x, hi = curves.front().back().x;
  for (const Polyline& c : curves) {
    lo = std::max(lo, c.front().x);
    hi = std::min(hi, c.back().x);
  }
  const double spacing = cs.width_nm() / static_cast<double>(cs.top.size() - 1);
  lo += kBandMarginSpacings * spacing;
  hi -= kBandMarginSpacings * spacing;
  for (std::size_t k = 0; k + 1 < curves.size(); ++k) {
    const Material& m = k == 0 ? model.below_top : model.boundaries[k - 1].below;
    if (m.name() == body.name()) continue;
    const Polyline upper = keep_x(curves[k], lo, hi), lower = keep_x(curves[k + 1], lo, hi);
    if (upper.size() < 2 || lower.size() < 2) continue;  // a layer that pinches out entirely; validate() judges the rest
    cs.regions.push_back({band_polygon(upper, lower), m, role_of(m), 0, static_cast<int>(k)});
  }
}

}  // namespace

FeatherLabFiles featherlab_files_of(const std::filesystem::path& folder, std::uint64_t number) {
  const std::string n = std::to_string(number) + ".txt";
  return {folder / ("xyvals" + n), folder / ("info" + n), folder / ("melaninRatio" + n)};
}

CrossSection parse_featherlab_instance(const FeatherLabTexts& t, const FeatherLabImportOptions& o) {
  check_options(o);
  featherlab_detail::FeatherLabCurves read = featherlab_detail::read_featherlab_curves(t, o);
  std::vector<Polyline>& curves = read.curves;

  CrossSection cs;
  cs.generator = "featherlab";
  cs.label = std::filesystem::path(t.xyvals_name).stem().string();
  cs.top = curves.front();
  cs.bottom = curves.back();
  LayeredModel model;
  model.below_top = o.layers.front();
  for (std::size_t k = 1; k < curves.size(); ++k) {
    LayerBoundary b{curves[k], k + 1 < curves.size() ? o.layers[k] : Material::air(), {}, -1};
    if (o.melanin_ratio_layer && *o.melanin_ratio_layer == k) {
      b.fraction = fraction_on(curves[k], cs.top, ratio_per_top_vertex(read.melanin_ratio));
      const double mean = std::accumulate(b.fraction.begin(), b.fraction.end(), 0.0) / static_cast<double>(b.fraction.size());
      b.below = b.below.with_fraction(mean);
    }
    model.boundaries.push_back(std::move(b));
  }
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), o.body, RegionRole::body});
  add_layer_regions(cs, curves, model, o.body);
  cs.layered = std::move(model);

  const std::vector<std::string> problems = validate(cs);
  if (!problems.empty()) {
    std::string message = "the curves do not make a valid cross section: " + problems.front();
    for (std::size_t k = 1; k < std::min<std::size_t>(problems.size(), 3); ++k) message += "; " + problems[k];
    throw InputFileError(t.xyvals_name, message);
  }
  return cs;
}

// The largest file read (1 GiB): 2^24 rows of "x,y" at full double precision are about 700 MB.
constexpr std::uintmax_t kMaxFeatherLabFileBytes = std::uintmax_t{1} << 30;

CrossSection read_featherlab_instance(const FeatherLabFiles& files, const FeatherLabImportOptions& o) {
  FeatherLabTexts t;
  t.xyvals_name = files.xyvals.string();
  t.info_name = files.info.string();
  t.xyvals = read_input_file(files.xyvals, "FeatherLab xyvals", kMaxFeatherLabFileBytes);
  t.info = read_input_file(files.info, "FeatherLab info", kMaxFeatherLabFileBytes);
  if (o.melanin_ratio_layer) {
    t.melanin_ratio_name = files.melanin_ratio.string();
    t.melanin_ratio = read_input_file(files.melanin_ratio, "FeatherLab melanin ratio", kMaxFeatherLabFileBytes);
  }
  return parse_featherlab_instance(t, o);
}

CrossSection read_featherlab_instance(const std::filesystem::path& folder, std::uint64_t number,
                                      const FeatherLabImportOptions& o) {
  return read_featherlab_instance(featherlab_files_of(folder, number), o);
}

}  // namespace plumage
