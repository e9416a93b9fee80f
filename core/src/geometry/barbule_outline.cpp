// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "plumage/barbule_outline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "plumage/error.hpp"

namespace plumage {

RoughnessSpec parse_roughness(const ParamView& node) {
  RoughnessSpec r;
  r.rough.correlation_nm = 1000.0 * node.number("correlation_um", Limits::positive());
  const auto [lo, hi] = node.interval("range_um");
  r.rough.lo_nm = 1000.0 * lo;
  r.rough.hi_nm = 1000.0 * hi;
  r.permute = node.boolean_or("permute", false);
  return r;
}

OutlineSpec parse_outline_spec(const ParamView& node, bool thickness_required) {
  OutlineSpec s;
  static constexpr std::array<std::string_view, 3> shapes{"elliptic_arc", "pillow", "flat"};
  const std::string shape = node.choice("shape", shapes);
  s.shape = shape == "elliptic_arc" ? OutlineSpec::Shape::elliptic_arc
            : shape == "pillow"     ? OutlineSpec::Shape::pillow
                                    : OutlineSpec::Shape::flat;
  s.width_nm = 1000.0 * node.number("width_um", Limits::positive());
  if (thickness_required || node.has("thickness_um")) {
    s.thickness_nm = 1000.0 * node.number("thickness_um", Limits::positive());
  }
  s.spacing_nm = node.number_or("spacing_nm", 30.0, Limits::positive());
  if (s.spacing_nm > s.width_nm / 10.0) node.fail("spacing_nm", "spacing must be below a tenth of the width");
  if (s.shape == OutlineSpec::Shape::elliptic_arc) {
    s.edge_slope_deg = node.interval("edge_slope_deg", Limits{0.0, 80.0, true, false});
  }
  if (s.shape == OutlineSpec::Shape::pillow) {
    if (node.has("cap_ratio")) s.cap_ratio = node.interval("cap_ratio", Limits::positive());
    s.shoulder_end = node.number_or("shoulder_end", 0.95, Limits{0.0, 1.0, true, true});
    s.interior_shoulder = node.number_or("interior_shoulder", 0.5, Limits::unit_interval());
    if (s.cap_ratio.second * 0.5 * s.thickness_nm >= 0.5 * s.width_nm) {
      node.fail("cap_ratio", "the shoulders would be longer than half the width");
    }
  }
  if (s.shape == OutlineSpec::Shape::flat) {
    s.corner_nm = 1000.0 * node.number_or("corner_um", 1.0, Limits::non_negative());
    s.corner_angle_deg = node.number_or("corner_angle_deg", 30.0, Limits{0.0, 80.0, false, false});
    if (2.0 * s.corner_nm >= s.width_nm) node.fail("corner_um", "corners wider than half the width");
  }
  s.roughness = parse_roughness(node.child("roughness"));
  static constexpr std::array<std::string_view, 3> modes{"mirror", "arc", "parallel"};
  if (auto b = node.child_if("bottom")) {
    const std::string mode = b->choice("mode", modes);
    s.bottom = mode == "mirror" ? OutlineSpec::Bottom::mirror
               : mode == "arc"  ? OutlineSpec::Bottom::arc
                                : OutlineSpec::Bottom::parallel;
    s.bottom_slope_factor = b->number_or("slope_factor", 0.9, Limits::positive());
    s.bottom_width_fraction = b->number_or("width_fraction", 0.9, Limits{0.0, 1.0, true, false});
    if (b->has("roughness")) s.bottom_roughness = parse_roughness(b->child("roughness"));
    if (s.bottom == OutlineSpec::Bottom::arc && s.shape != OutlineSpec::Shape::elliptic_arc) {
      b->fail("mode", "an arc bottom goes with an elliptic_arc top");
    }
    if (s.bottom == OutlineSpec::Bottom::mirror && s.shape != OutlineSpec::Shape::pillow) {
      b->fail("mode", "a mirror bottom goes with a pillow top");
    }
  } else {
    s.bottom = s.shape == OutlineSpec::Shape::pillow         ? OutlineSpec::Bottom::mirror
               : s.shape == OutlineSpec::Shape::elliptic_arc ? OutlineSpec::Bottom::arc
                                                             : OutlineSpec::Bottom::parallel;
  }
  // The rough top must not reach the bottom.
  const double relief = (s.roughness.rough.hi_nm - s.roughness.rough.lo_nm) +
                        (s.bottom_roughness.rough.hi_nm - s.bottom_roughness.rough.lo_nm);
  if ((thickness_required || node.has("thickness_um")) && relief >= s.thickness_nm) {
    node.fail("thickness_um", "thinner than the roughness relief of top and bottom");
  }
  return s;
}

std::vector<ParamSpec> outline_param_table() {
  return {
      {"outline.shape", "text", "-", "required", "elliptic_arc, pillow or flat top"},
      {"outline.width_um", "number", "um", "required", "x-extent of the top surface"},
      {"outline.thickness_um", "number", "um", "required*", "distance of the bottom below the top"},
      {"outline.spacing_nm", "number", "nm", "30", "vertex spacing along the top"},
      {"outline.edge_slope_deg", "interval", "deg", "required (arc)", "edge slope angle ~ U[range]"},
      {"outline.cap_ratio", "interval", "-", "[2, 3]", "pillow: shoulder length / half thickness"},
      {"outline.shoulder_end", "number", "-", "0.95", "pillow: end of the top on the cap (0-1)"},
      {"outline.interior_shoulder", "number", "-", "0.5", "pillow: shoulder fraction open to interior"},
      {"outline.corner_um", "number", "um", "1.0", "flat: rounded corner zone at each end"},
      {"outline.corner_angle_deg", "number", "deg", "30", "flat: turn of the corner arc"},
      {"outline.roughness", "map", "-", "required", "{correlation_um, range_um, permute} of the top"},
      {"outline.bottom.mode", "text", "-", "by shape", "mirror, arc or parallel"},
      {"outline.bottom.slope_factor", "number", "-", "0.9", "arc: tan(bottom slope)/tan(beta)"},
      {"outline.bottom.width_fraction", "number", "-", "0.9", "arc: bottom width / width"},
      {"outline.bottom.roughness", "map", "-", "none", "roughness of the bottom"},
  };
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
      o.interior_half_width = half * s.bottom_width_fraction;
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

  switch (s.bottom) {
    case OutlineSpec::Bottom::mirror:
    case OutlineSpec::Bottom::parallel: {
      const auto rb = rough_on(s.bottom_roughness, bottom_rng);
      o.bottom.resize(base.size());
      for (std::size_t i = 0; i < base.size(); ++i) {
        // mirror: the base shape reflected about z = −T/2; parallel: the rough top moved down by
        // T, with the corners rounded the other way.
        const double z = s.bottom == OutlineSpec::Bottom::mirror
                             ? -T - base[i].z
                             : o.top_roughness[i] - T - base[i].z;
        o.bottom[i] = {xs[i], z + rb[i] - mean};
      }
      break;
    }
    case OutlineSpec::Bottom::arc: {
      const double beta = std::atan(s.bottom_slope_factor * std::tan(o.edge_slope_rad));
      Polyline arc = elliptic_arc(W * s.bottom_width_fraction, beta, shape_rng.uniform(), s.spacing_nm);
      const auto bx = xs_of(arc);
      const double bh = 0.5 * W * s.bottom_width_fraction;
      const auto rb = rough_profile(bx, -bh, bh, s.bottom_roughness.rough, bottom_rng,
                                    s.bottom_roughness.permute);
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
