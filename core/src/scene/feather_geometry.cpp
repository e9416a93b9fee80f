// Procedural feathers (feather_geometry.hpp; paper §7.3 single feathers with explicit barbules,
// §7.4 barb-level feathers).
#include "plumage/feather_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "plumage/error.hpp"
#include "plumage/random.hpp"
#include "vec3d.hpp"

namespace plumage {

using namespace scene_detail;

namespace {

// Half-width of the vane at s = y / length ∈ [0, 1]: 0 at base and tip, widest near s = 0.4
// (an ovate contour; sin(π s^0.75)^0.7 peaks at 1 where s^0.75 = 1/2).
double outline(double s) {
  if (s <= 0.0 || s >= 1.0) return 0.0;
  return std::pow(std::sin(kPiD * std::pow(s, 0.75)), 0.7);
}

struct Vane {
  const FeatherShape& f;
  double half_width(double y, int side) const {
    return 0.5 * f.vane_width_mm * (1.0 + side * f.vane_asymmetry) * outline(y / f.length_mm);
  }
  // Height of the cambered vane and its slope dz/dx.
  double z(double x) const {
    const double h = 0.5 * f.vane_width_mm;
    return -f.camber_mm * (x / h) * (x / h);
  }
  double slope(double x) const {
    const double h = 0.5 * f.vane_width_mm;
    return -2.0 * f.camber_mm * x / (h * h);
  }
  V3 point(double x, double y) const { return {x, y, z(x)}; }
  V3 normal(double x) const { return normalized({-slope(x), 0.0, 1.0}); }
  // A direction (dx, dy) of the vane plane lifted onto the cambered surface at x.
  V3 lift(double x, double dx, double dy) const { return normalized({dx, dy, slope(x) * dx}); }
  double rachis_radius(double y) const {
    const double s = std::clamp(y / f.length_mm, 0.0, 1.0);
    return 0.5 * f.rachis_width_mm * (1.0 - 0.8 * s);
  }
};

// One barb: the centre line in the vane plane, x(u), y(u) for arclength u, with the direction
// angle from +y decreasing linearly (the barb curls toward the tip): α(u) = α0 − c·u.
struct Barb {
  int side = 1;  // +1 right (x > 0), −1 left
  double x0 = 0, y0 = 0, alpha0 = 0, curl_rate = 0, length = 0;
  std::uint64_t seed = 0;
  double alpha(double u) const { return alpha0 - curl_rate * u; }
  double x(double u) const {
    if (std::abs(curl_rate) < 1e-12) return x0 + side * u * std::sin(alpha0);
    return x0 + side * (std::cos(alpha(u)) - std::cos(alpha0)) / curl_rate;
  }
  double y(double u) const {
    if (std::abs(curl_rate) < 1e-12) return y0 + u * std::cos(alpha0);
    return y0 + (std::sin(alpha0) - std::sin(alpha(u))) / curl_rate;
  }
};

// Frame of a barbule leaving the barb at arclength u: `distal` +1 toward the tip side, −1 the
// base side. Returns (axis t, mean normal n), unit and orthogonal.
struct Frame {
  V3 t, n;
};
Frame barbule_frame(const Vane& vane, const Barb& b, double u, int distal) {
  const FeatherShape& f = vane.f;
  const double a = b.alpha(u), beta = rad(f.barbule_angle_deg);
  const double tx = b.side * std::sin(a), ty = std::cos(a);  // barb tangent
  const double dx = -b.side * std::cos(a), dy = std::sin(a);  // toward the tip side of the barb
  const double ax = std::cos(beta) * tx + distal * std::sin(beta) * dx;
  const double ay = std::cos(beta) * ty + distal * std::sin(beta) * dy;
  const double x = b.x(u);
  const V3 nv = vane.normal(x);
  const double e = rad(f.barbule_elevation_deg);
  const V3 t = normalized(std::cos(e) * vane.lift(x, ax, ay) + std::sin(e) * nv);
  const V3 n0 = normalized(nv - dot(nv, t) * t);
  // Positive tilt leans the normal toward the rachis on both sides (mirror-symmetric vane):
  // n0 × t points to −x for a barbule along +y, so the side factor makes it inward.
  const V3 s = b.side * normalized(cross(n0, t));
  const double tau = rad(f.barbule_tilt_deg);
  return {t, normalized(std::cos(tau) * n0 + std::sin(tau) * s)};
}

void add_quad_strip(SceneMesh& m, const std::vector<V3>& centre, const std::vector<double>& half_width,
                    const std::vector<V3>& across, std::uint32_t id, const Frame* frames, bool with_frames) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (std::size_t k = 0; k < centre.size(); ++k) {
    m.positions.push_back(to_f(centre[k] - half_width[k] * across[k]));  // left
    m.positions.push_back(to_f(centre[k] + half_width[k] * across[k]));  // right
  }
  for (std::uint32_t k = 0; k + 1 < centre.size(); ++k) {
    const std::uint32_t l0 = base + 2 * k, r0 = l0 + 1, l1 = l0 + 2, r1 = l0 + 3;
    // across = n × t, so (r0, l0, l1) and (r0, l1, r1) wind counter-clockwise about n.
    m.triangles.push_back({r0, l0, l1});
    m.triangles.push_back({r0, l1, r1});
    if (with_frames) {
      for (int q = 0; q < 2; ++q) {
        m.frame_axis.push_back(to_f(frames[k].t));
        m.frame_normal.push_back(to_f(frames[k].n));
        m.barbule_id.push_back(id + k);
      }
    }
  }
}

// A tapered tube; barb-level feathers (bird-scale scenes) get a coarse one.
void build_rachis(const Vane& vane, SceneMesh& m, bool coarse) {
  const FeatherShape& f = vane.f;
  const int kSides = coarse ? 4 : 6;
  const double y_start = -f.calamus_mm, y_end = f.length_mm;
  const double step = coarse ? f.length_mm / 8.0 : std::max(0.5, f.length_mm / 40.0);
  const int rings = std::max(4, static_cast<int>(std::ceil((y_end - y_start) / step))) + 1;
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (int r = 0; r < rings; ++r) {
    const double y = y_start + (y_end - y_start) * r / (rings - 1);
    const double radius = vane.rachis_radius(std::max(y, 0.0));
    for (int k = 0; k < kSides; ++k) {
      const double th = 2.0 * kPiD * (k + 0.5) / kSides;
      m.positions.push_back(to_f({radius * std::cos(th), y, radius * std::sin(th)}));
    }
  }
  for (int r = 0; r + 1 < rings; ++r) {
    for (int k = 0; k < kSides; ++k) {
      const std::uint32_t a = base + static_cast<std::uint32_t>(r * kSides + k);
      const std::uint32_t b = base + static_cast<std::uint32_t>(r * kSides + (k + 1) % kSides);
      m.triangles.push_back({a, b + kSides, b});
      m.triangles.push_back({a, a + kSides, b + kSides});
    }
  }
}

// Barbs of both sides: base positions along the rachis, angles, lengths up to the outline.
std::vector<Barb> make_barbs(const Vane& vane, std::uint64_t seed) {
  const FeatherShape& f = vane.f;
  std::vector<Barb> barbs;
  const int per_side = static_cast<int>(std::floor(f.length_mm / f.barb_spacing_mm));
  for (int side : {-1, 1}) {
    for (int j = 0; j < per_side; ++j) {
      Barb b;
      b.side = side;
      b.seed = splitmix64(seed ^ splitmix64(static_cast<std::uint64_t>(j) * 2 + (side > 0)));
      RandomStream rs(b.seed, "barb");
      b.y0 = (j + 0.5 + f.jitter * (rs.uniform() - 0.5)) * f.barb_spacing_mm;
      const double hw = vane.half_width(b.y0, side);
      b.x0 = side * vane.rachis_radius(b.y0);
      if (hw <= std::abs(b.x0) + 2.0 * f.barb_width_mm) continue;
      b.alpha0 = rad(f.barb_angle_deg) * (1.0 + f.jitter * (rs.uniform() - 0.5));
      const double expected = (hw - std::abs(b.x0)) / std::sin(b.alpha0);
      b.curl_rate = rad(f.barb_curl_deg) * (1.0 + f.jitter * (rs.uniform() - 0.5)) / expected;
      // March to the outline (or the tip, or until the barb would turn backwards), then bisect.
      const double step = std::min(0.05, expected / 20.0);
      double u = 0.0;
      auto inside = [&](double v) {
        const double y = b.y(v);
        return b.alpha(v) > 0.0 && y < f.length_mm && std::abs(b.x(v)) < vane.half_width(y, side);
      };
      while (u < 3.0 * expected && inside(u + step)) u += step;
      double lo = u, hi = u + step;
      for (int it = 0; it < 30; ++it) {
        const double mid = 0.5 * (lo + hi);
        (inside(mid) ? lo : hi) = mid;
      }
      b.length = lo;
      if (b.length < 4.0 * f.barb_width_mm) continue;
      barbs.push_back(b);
    }
  }
  return barbs;
}

int segments_of(double length, double target) { return std::max(1, static_cast<int>(std::lround(length / target))); }

void place(SceneMesh& m, const Placement& p) {
  const V3 X = from_f(p.x_axis), Y = from_f(p.y_axis), Z = from_f(p.z_axis), O = from_f(p.origin_mm);
  auto rot = [&](Vec3f v) { return v.x * X + v.y * Y + v.z * Z; };
  for (auto& q : m.positions) q = to_f(O + p.scale * rot(q));
  for (auto& q : m.frame_axis) q = to_f(normalized(rot(q)));
  for (auto& q : m.frame_normal) q = to_f(normalized(rot(q)));
}

}  // namespace

std::uint64_t object_item_seed(std::uint64_t seed, const std::string& object_name, std::uint64_t index) {
  const std::uint64_t s = splitmix64(seed ^ splitmix64(name_hash(object_name)));
  return splitmix64(s ^ splitmix64(index + 0x632be59bd9b4e019ULL));
}

Placement placement_from_euler(const Vec3f& origin_mm, const Vec3f& rotate_deg, double scale) {
  const V3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
  auto R = [&](V3 v) {
    v = rotated(v, ex, rad(rotate_deg.x));
    v = rotated(v, ey, rad(rotate_deg.y));
    return rotated(v, ez, rad(rotate_deg.z));
  };
  Placement p;
  p.origin_mm = origin_mm;
  p.x_axis = to_f(R(ex));
  p.y_axis = to_f(R(ey));
  p.z_axis = to_f(R(ez));
  p.scale = scale;
  return p;
}

void validate_feather_shape(const FeatherShape& f) {
  auto need = [](bool ok, const char* field, const std::string& what) {
    if (!ok) throw Error(std::string("feather shape: ") + field + " " + what);
  };
  need(f.length_mm > 0, "length_mm", "must be > 0");
  need(f.calamus_mm >= 0, "calamus_mm", "must be >= 0");
  need(f.vane_width_mm > 0, "vane_width_mm", "must be > 0");
  need(std::abs(f.vane_asymmetry) <= 0.8, "vane_asymmetry", "must be in [-0.8, 0.8]");
  need(f.rachis_width_mm > 0 && f.rachis_width_mm < f.vane_width_mm, "rachis_width_mm", "must be in (0, vane_width_mm)");
  need(f.barb_spacing_mm > 0, "barb_spacing_mm", "must be > 0");
  need(f.barb_angle_deg > 1 && f.barb_angle_deg < 89, "barb_angle_deg", "must be in (1, 89)");
  need(f.barb_curl_deg >= 0 && f.barb_curl_deg < 80, "barb_curl_deg", "must be in [0, 80)");
  need(f.barb_width_mm > 0, "barb_width_mm", "must be > 0");
  need(f.barb_segment_mm > 0, "barb_segment_mm", "must be > 0");
  need(f.barbule_length_mm > 0, "barbule_length_mm", "must be > 0");
  need(f.barbule_width_mm > 0, "barbule_width_mm", "must be > 0");
  need(f.barbule_spacing_mm > 0, "barbule_spacing_mm", "must be > 0");
  need(f.barbule_angle_deg >= 0 && f.barbule_angle_deg < 90, "barbule_angle_deg", "must be in [0, 90)");
  need(std::abs(f.barbule_tilt_deg) < 90, "barbule_tilt_deg", "must be in (-90, 90)");
  need(std::abs(f.barbule_elevation_deg) < 90, "barbule_elevation_deg", "must be in (-90, 90)");
  need(f.barbule_segments >= 1 && f.barbule_segments <= 16, "barbule_segments", "must be in [1, 16]");
  need(f.jitter >= 0 && f.jitter <= 0.5, "jitter", "must be in [0, 0.5]");
}

FeatherGeometry build_feather(const FeatherShape& f, FeatherDetail detail, std::uint64_t seed, const Placement& placement,
                              std::size_t max_triangles) {
  validate_feather_shape(f);
  const Vane vane{f};
  FeatherGeometry g;
  g.shaft.name = "shaft";
  g.vane.name = "vane";
  g.vane.barbule_spacing_mm = f.barbule_spacing_mm * placement.scale;
  build_rachis(vane, g.shaft, detail == FeatherDetail::barb_level);
  const std::vector<Barb> barbs = make_barbs(vane, seed);
  g.barb_count = barbs.size();

  // Count before building (explicit barbules dominate).
  std::size_t estimate = g.shaft.triangles.size();
  const int sides = f.proximal_barbules ? 2 : 1;
  for (const Barb& b : barbs) {
    estimate += 2 * static_cast<std::size_t>(segments_of(b.length, f.barb_segment_mm));
    if (detail == FeatherDetail::barbules)
      estimate += static_cast<std::size_t>(sides) * static_cast<std::size_t>(b.length / f.barbule_spacing_mm + 1) *
                  2 * static_cast<std::size_t>(f.barbule_segments);
  }
  if (estimate > max_triangles) {
    throw Error("feather: about " + std::to_string(estimate) + " triangles exceed the limit of " +
                std::to_string(max_triangles) +
                " (raise barbule_spacing_mm or barb_spacing_mm, or use detail: barb_level)");
  }

  std::vector<V3> centre, across;
  std::vector<double> half;
  std::vector<Frame> frames;
  for (const Barb& b : barbs) {
    const int segs = segments_of(b.length, f.barb_segment_mm);
    centre.clear(), across.clear(), half.clear(), frames.clear();
    // Barb-level strips cover the gap to the neighbouring barbs (the vane stays closed).
    const double width = detail == FeatherDetail::barb_level ? 1.1 * f.barb_spacing_mm * std::sin(b.alpha0) : f.barb_width_mm;
    for (int k = 0; k <= segs; ++k) {
      const double u = b.length * k / segs, x = b.x(u);
      const V3 t = vane.lift(x, b.side * std::sin(b.alpha(u)), std::cos(b.alpha(u)));
      centre.push_back(vane.point(x, b.y(u)));
      across.push_back(normalized(cross(vane.normal(x), t)));
      // Taper the last 30 % of the barb to 40 % of its width.
      const double s = static_cast<double>(k) / segs;
      half.push_back(0.5 * width * (s < 0.7 ? 1.0 : 1.0 - 0.6 * (s - 0.7) / 0.3));
      if (k < segs) frames.push_back(barbule_frame(vane, b, b.length * (k + 0.5) / segs, +1));
    }
    if (detail == FeatherDetail::barb_level) {
      add_quad_strip(g.vane, centre, half, across, static_cast<std::uint32_t>(g.barbule_count), frames.data(), true);
      g.barbule_count += static_cast<std::size_t>(segs);
      continue;
    }
    add_quad_strip(g.shaft, centre, half, across, 0, nullptr, false);
    // Explicit barbules (paper §7.3): strips from the barb edge along their axis t.
    RandomStream rs(b.seed, "barbules");
    for (int distal : {+1, -1}) {
      if (distal < 0 && !f.proximal_barbules) continue;
      const double first = 0.5 * f.barbule_spacing_mm;
      for (double u = first; u < b.length - 0.25 * f.barbule_spacing_mm; u += f.barbule_spacing_mm) {
        const double uu = std::clamp(u + f.jitter * f.barbule_spacing_mm * (rs.uniform() - 0.5), 0.0, b.length);
        const double length = f.barbule_length_mm * (1.0 + f.jitter * (rs.uniform() - 0.5)) *
                              (uu > 0.8 * b.length ? 0.5 + 0.5 * (b.length - uu) / (0.2 * b.length) : 1.0);
        const Frame fr = barbule_frame(vane, b, uu, distal);
        const double a = b.alpha(uu), x = b.x(uu);
        const V3 side_dir = vane.lift(x, -b.side * std::cos(a) * distal, std::sin(a) * distal);
        const V3 root = vane.point(x, b.y(uu)) + (0.5 * f.barb_width_mm) * side_dir;
        const V3 w = normalized(cross(fr.n, fr.t));
        centre.clear(), across.clear(), half.clear(), frames.assign(static_cast<std::size_t>(f.barbule_segments), fr);
        for (int k = 0; k <= f.barbule_segments; ++k) {
          const double s = static_cast<double>(k) / f.barbule_segments;
          centre.push_back(root + (length * s) * fr.t);
          across.push_back(w);
          half.push_back(0.5 * f.barbule_width_mm * (1.0 - 0.4 * s));
        }
        // One barbule = one BRDF instance: every triangle of the strip shares its id and frame.
        const auto id = static_cast<std::uint32_t>(g.barbule_count);
        const std::size_t before = g.vane.barbule_id.size();
        add_quad_strip(g.vane, centre, half, across, id, frames.data(), true);
        std::fill(g.vane.barbule_id.begin() + static_cast<std::ptrdiff_t>(before), g.vane.barbule_id.end(), id);
        ++g.barbule_count;
      }
    }
  }
  place(g.shaft, placement);
  place(g.vane, placement);
  return g;
}

namespace {

void append_with_id_offset(SceneMesh& into, const SceneMesh& part, std::uint32_t id_offset) {
  const auto offset = static_cast<std::uint32_t>(into.positions.size());
  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  for (const auto& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  into.frame_axis.insert(into.frame_axis.end(), part.frame_axis.begin(), part.frame_axis.end());
  into.frame_normal.insert(into.frame_normal.end(), part.frame_normal.begin(), part.frame_normal.end());
  for (std::uint32_t id : part.barbule_id) into.barbule_id.push_back(id + id_offset);
}

}  // namespace

void append_mesh(SceneMesh& into, const SceneMesh& part) {
  std::uint32_t id_offset = 0;
  for (std::uint32_t id : into.barbule_id) id_offset = std::max(id_offset, id + 1);
  append_with_id_offset(into, part, id_offset);
}

AssemblyGeometry build_feather_assembly(const AssemblyShape& a, std::uint64_t seed, std::size_t max_triangles) {
  validate_feather_shape(a.feather);
  if (a.count < 1) throw Error("assembly: count must be >= 1");
  if (!(a.body.radii_mm.x > 0 && a.body.radii_mm.y > 0 && a.body.radii_mm.z > 0))
    throw Error("assembly: body radii_mm must be > 0");
  if (!(a.body.lat_min_deg >= -90 && a.body.lat_max_deg <= 90 && a.body.lat_min_deg < a.body.lat_max_deg))
    throw Error("assembly: body latitude range must satisfy -90 <= lat_min_deg < lat_max_deg <= 90");
  AssemblyGeometry g;
  g.shaft.name = "assembly shaft";
  g.vane.name = "assembly vane";
  const V3 c = from_f(a.body.center_mm), r = from_f(a.body.radii_mm);
  const double t0 = std::sin(rad(a.body.lat_min_deg)), t1 = std::sin(rad(a.body.lat_max_deg));
  const double golden = kPiD * (3.0 - std::sqrt(5.0));
  // Lattice spacing on the unit sphere (area 2π(t1 − t0) shared by `count` points).
  const double spacing = std::sqrt(2.0 * kPiD * (t1 - t0) / a.count);
  double spacing_sum = 0.0;
  for (int i = 0; i < a.count; ++i) {
    const std::uint64_t fs = object_item_seed(seed, "feather", static_cast<std::uint64_t>(i));
    RandomStream rs(fs, "placement");
    // Fibonacci lattice (even coverage), jittered by a fraction of its spacing.
    const double t = std::clamp(t0 + (t1 - t0) * (i + 0.5) / a.count + a.position_jitter * spacing * (rs.uniform() - 0.5), -1.0, 1.0);
    const double lon = i * golden + a.position_jitter * spacing * (rs.uniform() - 0.5) / std::max(0.2, std::sqrt(1 - t * t));
    const double ct = std::sqrt(std::max(0.0, 1.0 - t * t));
    const V3 q{ct * std::cos(lon), t, ct * std::sin(lon)};
    const V3 p = c + V3{r.x * q.x, r.y * q.y, r.z * q.z};
    const V3 n = normalized({q.x / r.x, q.y / r.y, q.z / r.z});
    // Feathers point toward −y (the tail); near the poles, where that is normal to the
    // surface, any tangent will do.
    V3 flow = V3{0, -1, 0} - dot(V3{0, -1, 0}, n) * n;
    if (norm(flow) < 1e-6) flow = V3{1, 0, 0} - dot(V3{1, 0, 0}, n) * n;
    flow = rotated(normalized(flow), n, rad(a.heading_jitter_deg) * (2.0 * rs.uniform() - 1.0));
    const double lie = rad(a.lie_deg + a.lie_jitter_deg * (2.0 * rs.uniform() - 1.0));
    const V3 y = normalized(std::cos(lie) * flow + std::sin(lie) * n);
    const V3 z = normalized(n - dot(n, y) * y);
    Placement pl;
    pl.origin_mm = to_f(p);
    pl.y_axis = to_f(y);
    pl.z_axis = to_f(z);
    pl.x_axis = to_f(cross(y, z));
    pl.scale = 1.0 + a.size_jitter * (2.0 * rs.uniform() - 1.0);
    const FeatherGeometry f = build_feather(a.feather, FeatherDetail::barb_level, fs, pl, max_triangles);
    append_with_id_offset(g.shaft, f.shaft, 0);
    append_with_id_offset(g.vane, f.vane, static_cast<std::uint32_t>(g.barbule_count));
    spacing_sum += f.vane.barbule_spacing_mm;
    g.barb_count += f.barb_count;
    g.barbule_count += f.barbule_count;
    ++g.feather_count;
    if (g.shaft.triangles.size() + g.vane.triangles.size() > max_triangles) {
      throw Error("assembly: more than " + std::to_string(max_triangles) + " triangles after " + std::to_string(i + 1) +
                  " of " + std::to_string(a.count) + " feathers (fewer feathers, or larger barb_spacing_mm)");
    }
  }
  g.vane.barbule_spacing_mm = spacing_sum / a.count;  // mean over the size jitter
  return g;
}

}  // namespace plumage
