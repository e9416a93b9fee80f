// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "plumage/barbule_outline.hpp"

#include "plumage/memory_budget.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "plumage/error.hpp"

namespace plumage {

namespace {

using Shape = OutlineSpec::Shape;

// thickness_um is optional in the table (a generator that computes T may omit it): given, it sets
// T and marks it given (an optional_number field: reset() keeps the default).
struct GivenThickness {
  OutlineSpec& spec;
  void reset() {}
  GivenThickness& operator=(double thickness_um) {
    spec.thickness_nm = 1000.0 * thickness_um;
    spec.thickness_given = true;
    return *this;
  }
};

bool is(const OutlineSpec& s, Shape shape) { return s.shape == shape; }

const ParamTable<BottomSpec>& bottom_table() {
  using M = BottomSpec::Mode;
  static const auto table =
      ParamTable<BottomSpec>{}
          .choice("mode", &BottomSpec::mode,
                  std::vector<std::pair<std::string_view, M>>{{"mirror", M::mirror}, {"arc", M::arc}, {"parallel", M::parallel}},
                  required,
                  "mirror: the top's base shape reflected (pillow) | arc: a new elliptic arc (elliptic_arc) | "
                  "parallel: the rough top moved down by T (flat)")
          .default_text("by shape")
          .number("slope_factor", &BottomSpec::slope_factor, "1", 0.9, Limits::positive(),
                  "arc: edge slope tan(beta') = factor * tan(beta)")
          .number("width_fraction", &BottomSpec::width_fraction, "1", 0.9, Limits{0.0, 1.0, true, false},
                  "arc: x-extent of the bottom / width")
          .section("roughness", &BottomSpec::roughness, roughness_table(), "roughness of the bottom (default: smooth)");
  return table;
}

}  // namespace

const ParamTable<RoughnessSpec>& roughness_table() {
  static const auto table =
      ParamTable<RoughnessSpec>{}
          .number("correlation_um", [](RoughnessSpec& r) { return Scaled{&r.rough.correlation_nm, nullptr, 1000.0}; },
                  "um", required, Limits::positive(), "correlation length of the rough profile")
          .interval("range_um", [](RoughnessSpec& r) { return Scaled{&r.rough.lo_nm, &r.rough.hi_nm, 1000.0}; }, "um",
                    required, {}, "the profile spans exactly [lo, hi]")
          .boolean("permute", &RoughnessSpec::permute, false, "permute the profile's values (keeps their distribution)");
  return table;
}

const ParamTable<OutlineSpec>& outline_table() {
  static const auto table =
      ParamTable<OutlineSpec>{}
          .choice("shape", &OutlineSpec::shape,
                  std::vector<std::pair<std::string_view, Shape>>{
                      {"elliptic_arc", Shape::elliptic_arc}, {"pillow", Shape::pillow}, {"flat", Shape::flat}},
                  required,
                  "elliptic_arc | pillow (flat top, rounded shoulders) | flat (rounded corners)")
          .number("width_um", scaled(&OutlineSpec::width_nm, 1000.0), "um", required, Limits{0.0, 10000.0, true, false},
                  "x-extent of the top surface (barbules are 10-100 um wide; up to 10 mm allowed)")
          .optional_number("thickness_um", [](OutlineSpec& s) { return GivenThickness{s}; }, "um",
                           "required (unless the generator computes T)", Limits{0.0, 1000.0, true, false},
                           "T: distance of the bottom below the top (barbules are 1-10 um thick; up to 1 mm allowed)")
          .number("spacing_nm", &OutlineSpec::spacing_nm, "nm", 30.0, Limits::closed(1.0, 10000.0),
                  "vertex spacing along the top (arc length), below a tenth of the width; at least 1 nm (finer "
                  "than any layer a barbule has)")
          .interval("edge_slope_deg", &OutlineSpec::edge_slope_deg, "deg", required, Limits{0.0, 80.0, true, false},
                    "edge slope angle beta ~ U[range]")
          .only_if([](const OutlineSpec& s) { return is(s, Shape::elliptic_arc); }, "shape: elliptic_arc")
          .interval("cap_ratio", &OutlineSpec::cap_ratio, "1", {2.0, 3.0}, Limits::positive(),
                    "shoulder length / half thickness ~ U[range]")
          .only_if([](const OutlineSpec& s) { return is(s, Shape::pillow); }, "shape: pillow")
          .number("shoulder_end", &OutlineSpec::shoulder_end, "1", 0.95, Limits{0.0, 1.0, true, true},
                  "the top stops at this fraction of the cap's half-axis")
          .only_if([](const OutlineSpec& s) { return is(s, Shape::pillow); }, "shape: pillow")
          .number("interior_shoulder", &OutlineSpec::interior_shoulder, "1", 0.5, Limits::unit_interval(),
                  "fraction of the shoulder usable by interior structures")
          .only_if([](const OutlineSpec& s) { return is(s, Shape::pillow); }, "shape: pillow")
          .number("corner_um", scaled(&OutlineSpec::corner_nm, 1000.0), "um", 1.0, Limits::non_negative(),
                  "rounded corner zone at each end")
          .only_if([](const OutlineSpec& s) { return is(s, Shape::flat); }, "shape: flat")
          .number("corner_angle_deg", &OutlineSpec::corner_angle_deg, "deg", 30.0, Limits::closed(0.0, 80.0),
                  "the corner arc turns by this angle")
          .only_if([](const OutlineSpec& s) { return is(s, Shape::flat); }, "shape: flat")
          .section("roughness", &OutlineSpec::roughness, roughness_table(), "rough profile added to the top", true)
          .section("bottom", &OutlineSpec::bottom, bottom_table(), "the bottom surface");
  return table;
}

BottomSpec::Mode bottom_mode(const OutlineSpec& s) {
  if (s.bottom.mode) return *s.bottom.mode;
  return s.shape == Shape::pillow ? BottomSpec::Mode::mirror
         : s.shape == Shape::elliptic_arc ? BottomSpec::Mode::arc
                                          : BottomSpec::Mode::parallel;
}

// Memory budget (issue 23, plumage/memory_budget.hpp): the outline's vertices (top, bottom and
// sides at spacing_nm) are held several times over by the generator, the regions cut from them and
// the pictures: 1 KiB per vertex bounds the measured peaks. `width_um: 1e12` or `spacing_nm: 1e-9`
// asked for ~1e16 vertices (std::bad_alloc); such a config is refused here, at its key.
static void check_outline_memory(const ParamView& node, const OutlineSpec& s) {
  const double perimeter_nm = 2.0 * (s.width_nm + (s.thickness_given ? s.thickness_nm : 0.0));
  const double vertices = perimeter_nm / s.spacing_nm;
  MemoryEstimate e;
  char thickness[32] = "?";
  if (s.thickness_given) std::snprintf(thickness, sizeof thickness, "%g", s.thickness_nm / 1000.0);
  char job[200];
  std::snprintf(job, sizeof job, "barbule outline of %g um x %s um at spacing_nm %g (~%.3g vertices)", s.width_nm / 1000.0,
                thickness, s.spacing_nm, vertices);
  e.job = node.mark().str() + ": " + job;
  e.add("outline vertices and their copies", 1024.0 * vertices);
  e.lower_with = {"outline.spacing_nm (larger)", "outline.width_um", "outline.thickness_um"};
  check_memory(e);
}

OutlineSpec parse_outline_spec(const ParamView& node, bool thickness_required) {
  const OutlineSpec s = outline_table().read(node);
  if (thickness_required && !s.thickness_given) node.fail("thickness_um", "missing required key 'thickness_um'");
  if (s.spacing_nm > s.width_nm / 10.0) node.fail("spacing_nm", "spacing must be below a tenth of the width");
  if (s.shape == Shape::pillow && s.cap_ratio.second * 0.5 * s.thickness_nm >= 0.5 * s.width_nm) {
    node.fail("cap_ratio", "the shoulders would be longer than half the width");
  }
  if (s.shape == Shape::flat && 2.0 * s.corner_nm >= s.width_nm) node.fail("corner_um", "corners wider than half the width");
  if (s.bottom.mode) {
    const ParamView b = node.child("bottom");
    if (*s.bottom.mode == BottomSpec::Mode::arc && s.shape != Shape::elliptic_arc) {
      b.fail("mode", "an arc bottom goes with an elliptic_arc top");
    }
    if (*s.bottom.mode == BottomSpec::Mode::mirror && s.shape != Shape::pillow) {
      b.fail("mode", "a mirror bottom goes with a pillow top");
    }
  }
  // The rough top must not reach the bottom.
  const double relief = (s.roughness.rough.hi_nm - s.roughness.rough.lo_nm) +
                        (s.bottom.roughness.rough.hi_nm - s.bottom.roughness.rough.lo_nm);
  if (s.thickness_given && relief >= s.thickness_nm) {
    node.fail("thickness_um", "thinner than the roughness relief of top and bottom");
  }
  check_outline_memory(node, s);
  return s;
}

namespace {

std::vector<double> xs_of(const Polyline& p) {
  std::vector<double> x(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x[i] = p[i].x;
  return x;
}

// Drop of a circular corner of angular extent `angle` over the zone length `zone`, at depth u
// into the zone (0 at the zone's inner edge).
double corner_drop(double u, double zone, double angle) {
  if (zone <= 0.0 || angle <= 0.0 || u <= 0.0) return 0.0;
  const double r = zone / std::sin(angle);
  return r - std::sqrt(std::max(0.0, r * r - u * u));
}

}  // namespace

Outline make_outline(const OutlineSpec& s, std::uint64_t seed, double thickness_nm) {
  const double T = thickness_nm > 0.0 ? thickness_nm : s.thickness_nm;
  const double W = s.width_nm, half = 0.5 * W;
  RandomStream shape_rng(seed, "outline.shape");
  RandomStream top_rng(seed, "outline.top");
  RandomStream bottom_rng(seed, "outline.bottom");
  Outline o;
  Polyline base;
  const bool flat = s.shape == OutlineSpec::Shape::flat;
  switch (s.shape) {
    case OutlineSpec::Shape::elliptic_arc: {
      o.edge_slope_rad = deg_to_rad(shape_rng.uniform(s.edge_slope_deg.first, s.edge_slope_deg.second));
      base = elliptic_arc(W, o.edge_slope_rad, shape_rng.uniform(), s.spacing_nm);
      o.interior_half_width = half * s.bottom.width_fraction;
      break;
    }
    case OutlineSpec::Shape::pillow: {
      const double h = 0.5 * T;
      const double a = shape_rng.uniform(s.cap_ratio.first, s.cap_ratio.second) * h;
      base = shoulder_top(W, a, h, s.shoulder_end, s.spacing_nm);
      // shoulder_top rescales x so the top spans W; the flat part scales with it.
      const double scale = half / ((half - a) + a * s.shoulder_end);
      o.interior_half_width = scale * ((half - a) + a * s.interior_shoulder);
      break;
    }
    case OutlineSpec::Shape::flat: {
      const int n = static_cast<int>(std::ceil(W / s.spacing_nm));
      const double inner = half - s.corner_nm;
      const double angle = deg_to_rad(s.corner_angle_deg);
      for (int k = 0; k <= n; ++k) {
        const double x = -half + W * k / n;
        base.push_back({x, -corner_drop(std::abs(x) - inner, s.corner_nm, angle)});
      }
      o.interior_half_width = inner;
      break;
    }
  }
  const auto xs = xs_of(base);
  // Rough heights: over all vertices, or (flat) over the vertices between the corners, frozen
  // at their edge values inside the corners.
  auto rough_on = [&](const RoughnessSpec& r, RandomStream& rng) {
    if (!flat) return rough_profile(xs, -half, half, r.rough, rng, r.permute);
    std::size_t i0 = 0, i1 = xs.size() - 1;
    while (i0 < i1 && xs[i0] < -o.interior_half_width) ++i0;
    while (i1 > i0 && xs[i1] > o.interior_half_width) --i1;
    std::vector<double> inner_x(xs.begin() + static_cast<std::ptrdiff_t>(i0),
                                xs.begin() + static_cast<std::ptrdiff_t>(i1) + 1);
    auto v = rough_profile(inner_x, -half, half, r.rough, rng, r.permute);
    std::vector<double> out(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) out[i] = v[std::clamp(i, i0, i1) - i0];
    return out;
  };
  o.top_roughness = rough_on(s.roughness, top_rng);
  o.top = base;
  for (std::size_t i = 0; i < o.top.size(); ++i) o.top[i].z += o.top_roughness[i];
  double mean = 0.0;
  for (const Vec2& p : o.top) mean += p.z;
  mean /= static_cast<double>(o.top.size());
  for (Vec2& p : o.top) p.z -= mean;

  const BottomSpec::Mode mode = bottom_mode(s);
  switch (mode) {
    case BottomSpec::Mode::mirror:
    case BottomSpec::Mode::parallel: {
      const auto rb = rough_on(s.bottom.roughness, bottom_rng);
      o.bottom.resize(base.size());
      for (std::size_t i = 0; i < base.size(); ++i) {
        // mirror: the base shape reflected about z = −T/2; parallel: the rough top moved down by
        // T, with the corners rounded the other way.
        const double z = mode == BottomSpec::Mode::mirror
                             ? -T - base[i].z
                             : o.top_roughness[i] - T - base[i].z;
        o.bottom[i] = {xs[i], z + rb[i] - mean};
      }
      break;
    }
    case BottomSpec::Mode::arc: {
      const double beta = std::atan(s.bottom.slope_factor * std::tan(o.edge_slope_rad));
      Polyline arc = elliptic_arc(W * s.bottom.width_fraction, beta, shape_rng.uniform(), s.spacing_nm);
      const auto bx = xs_of(arc);
      const double bh = 0.5 * W * s.bottom.width_fraction;
      const auto rb = rough_profile(bx, -bh, bh, s.bottom.roughness.rough, bottom_rng,
                                    s.bottom.roughness.permute);
      double bm = 0.0;
      for (std::size_t i = 0; i < arc.size(); ++i) {
        arc[i].z += rb[i];
        bm += arc[i].z;
      }
      bm /= static_cast<double>(arc.size());
      for (Vec2& p : arc) p.z -= bm + T;
      o.bottom = std::move(arc);
      break;
    }
  }
  return o;
}

}  // namespace plumage
