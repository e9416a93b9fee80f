// structure_generator "crystal_barbule": barbules whose interior is a photonic crystal (types
// 5–7 of spec geometry-and-brdf §1.3; cells of spec photonic-crystals.md). The approximate
// solver sees the rough top, the crystal reference and a per-vertex regularity; the exact model
// places the crystal's rods, hollow cores and air channels under the rough top, row j at depth
// cortex + D/2 + j·a_z along the top's normal, at the top's arc-length positions k·a_x (odd rows
// of hexagonal cells shifted by a_x/2), so the lattice follows the surface as in a real barbule.
// Where the curvature of the top would squeeze two bodies closer than `min_gap_nm`, the later
// one is left out (a lattice defect), so the exact model never overlaps.
// The parameters are declared once in crystal_barbule_table() below.
// Bit-identical geometry on every machine: no fused multiply-add contraction.
#pragma GCC optimize("fp-contract=off")
#include "crystal_barbule.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "plumage/geometry.hpp"

namespace plumage::photonic_crystal {

namespace {

struct Body {
  Vec2 c;
  double r;
};

// Uniform hash grid of placed bodies for overlap checks.
class Occupancy {
 public:
  explicit Occupancy(double cell) : cell_(cell) {}
  bool clear(Vec2 c, double r, double gap, double r_max) const {
    const long ix = key(c.x), iz = key(c.z);
    const long reach = static_cast<long>(std::ceil((r + r_max + gap) / cell_));
    for (long dz = -reach; dz <= reach; ++dz) {
      for (long dx = -reach; dx <= reach; ++dx) {
        auto it = cells_.find(pack(ix + dx, iz + dz));
        if (it == cells_.end()) continue;
        for (const Body& b : it->second) {
          if (norm(b.c - c) < b.r + r + gap) return false;
        }
      }
    }
    return true;
  }
  void add(Vec2 c, double r) { cells_[pack(key(c.x), key(c.z))].push_back({c, r}); }

 private:
  long key(double v) const { return static_cast<long>(std::floor(v / cell_)); }
  static long long pack(long a, long b) { return (static_cast<long long>(a) << 32) ^ (b & 0xffffffffLL); }
  double cell_;
  std::unordered_map<long long, std::vector<Body>> cells_;
};

}  // namespace

const ParamTable<CrystalBarbuleParams>& crystal_barbule_table() {
  using P = CrystalBarbuleParams;
  static const auto table =
      ParamTable<P>{}
          .text("crystal", &P::crystal, required, "crystal cell file (configs/crystals/*.yaml), relative to the config")
          .custom("outline", "map", "-", "required", "top and bottom surfaces (core barbule_outline.hpp)",
                  [](const ParamView& p, P& o) { o.outline = parse_outline_spec(p.child("outline")); })
          .nested_specs(outline_table().specs())
          .custom("body", "material", "-", "crystal host", "material of the barbule body",
                  [](const ParamView& p, P& o) {
                    if (p.has("body")) o.body = parse_material(p, "body");
                  })
          .number("regularity", &P::regularity, "1", 1.0, Limits{0.0, 1.0, true, false},
                  "mean regularity rho in (0, 1]; 1: a perfect crystal")
          .number("regularity_correlation_um", scaled(&P::regularity_correlation_nm, 1000.0), "um", 0.5,
                  Limits::positive(), "correlation of the regularity profile (rho < 1)")
          .number("regularity_half_range", &P::regularity_half_range, "1", 0.1, Limits::non_negative(),
                  "the regularity spans exactly [rho - h, rho + h] (rho < 1)")
          .number("min_gap_nm", &P::min_gap_nm, "nm", 1.0, Limits::non_negative(),
                  "smallest gap kept between bodies of the exact model")
          .integer("rod_segments", &P::rod_segments, "1", 24, Limits::closed(8, 256), "polygon vertices per rod")
          .boolean("exact_lattice", &P::exact_lattice, true, "place rods and channels in the exact model");
  return table;
}

CrystalBarbule::CrystalBarbule(const ParamView& p, const PluginContext& context) {
  const CrystalBarbuleParams o = crystal_barbule_table().read(p);
  std::filesystem::path path(o.crystal);
  if (path.is_relative()) path = context.config_dir / path;
  if (!std::filesystem::exists(path)) p.fail("crystal", "no such crystal file: " + path.string());
  crystal_file_ = path.lexically_normal().string();
  cell_ = load_crystal_cell(path);
  outline_ = o.outline;
  body_ = o.body ? *o.body : cell_.host;
  regularity_ = o.regularity;
  const double h = o.regularity_half_range;
  if (regularity_ < 1.0) {
    if (regularity_ - h <= 0.0 || regularity_ + h > 1.0) {
      p.fail("regularity_half_range", "the regularity must stay in (0, 1]: rho +- half range");
    }
  }
  regularity_profile_ = {o.regularity_correlation_nm, regularity_ - h, regularity_ + h};
  min_gap_nm_ = o.min_gap_nm;
  rod_segments_ = o.rod_segments;
  place_lattice_ = o.exact_lattice;
  if (cell_.depth_nm() + cell_.a_z_nm >= outline_.thickness_nm) {
    p.child("outline").fail("thickness_um", "the crystal (" + std::to_string(cell_.depth_nm()) +
                                                " nm deep) does not fit in the barbule");
  }
}

CrossSection CrystalBarbule::generate(std::uint64_t index) const {
  CrossSection cs = start("crystal_barbule", index);
  Outline o = make_outline(outline_, cs.seed);
  cs.top = std::move(o.top);
  cs.top_roughness_nm = std::move(o.top_roughness);
  cs.bottom = std::move(o.bottom);
  cs.regions.push_back({band_polygon(cs.top, cs.bottom), body_, RegionRole::body});

  CrystalModel crystal;
  crystal.crystal = crystal_file_;
  crystal.crystal_name = cell_.name;
  if (regularity_ >= 1.0) {
    crystal.regularity.assign(cs.top.size(), 1.0);
  } else {
    RandomStream rng(cs.seed, "crystal.regularity");
    std::vector<double> xs(cs.top.size());
    for (std::size_t i = 0; i < xs.size(); ++i) xs[i] = cs.top[i].x;
    crystal.regularity = rough_profile(xs, -0.5 * outline_.width_nm, 0.5 * outline_.width_nm,
                                       regularity_profile_, rng);
  }
  cs.crystal = std::move(crystal);
  if (!place_lattice_) return cs;

  // The lattice spans the interior of the outline, kept a crystal depth away from the ends.
  const double depth = cell_.depth_nm();
  const double x_lim = o.interior_half_width - depth - 500.0;
  const ArcLengthCurve top(cs.top);
  const double L = top.length();
  const double r_rod = 0.5 * cell_.rod_diameter_nm, r_core = 0.5 * cell_.core_diameter_nm;
  const double r_ch = 0.5 * cell_.channel_diameter_nm;
  const double r_max = std::max(r_rod, r_ch);
  Occupancy occupied(std::max(cell_.a_x_nm, 2.0 * r_max));
  const double window = 2.0 * outline_.spacing_nm;
  auto frame = [&](double s, Vec2& p, Vec2& n) {
    p = top.point(s);
    Vec2 t = top.point(std::min(L, s + window)) - top.point(std::max(0.0, s - window));
    t = (1.0 / norm(t)) * t;
    n = {-t.z, t.x};
  };
  auto inside = [&](Vec2 c, double r) {
    if (std::abs(c.x) > x_lim) return false;
    return c.z - r - min_gap_nm_ > z_at(cs.bottom, c.x);
  };
  const int n_sites = static_cast<int>(std::floor(L / cell_.a_x_nm)) + 1;
  // Unit circles, computed once per instance: rods and channels are scaled copies.
  auto unit_circle = [](int segments) { return circle_polygon({0.0, 0.0}, 1.0, segments); };
  const Polygon unit_rod = unit_circle(rod_segments_), unit_channel = unit_circle(std::max(8, rod_segments_ / 2));
  auto disc = [](const Polygon& unit, Vec2 c, double r) {
    Polygon p(unit.size());
    for (std::size_t i = 0; i < unit.size(); ++i) p[i] = {c.x + r * unit[i].x, c.z + r * unit[i].z};
    return p;
  };
  for (int row = 0; row < cell_.rows; ++row) {
    const double z_row = cell_.rod_depth_nm(row);
    const double shift = cell_.shifted(row) ? 0.5 * cell_.a_x_nm : 0.0;
    for (int k = 0; k < n_sites; ++k) {
      const double s = k * cell_.a_x_nm + shift;
      if (s > L) break;
      Vec2 p, n;
      frame(s, p, n);
      const Vec2 c = p - z_row * n;
      if (!inside(c, r_rod) || !occupied.clear(c, r_rod, min_gap_nm_, r_max)) continue;
      occupied.add(c, r_rod);
      const int rod_index = static_cast<int>(cs.regions.size());
      cs.regions.push_back({disc(unit_rod, c, r_rod), cell_.rod, RegionRole::rod, 0, row, 1,
                            cell_.rod_diameter_nm});
      if (r_core > 0.0) {
        cs.regions.push_back({disc(unit_rod, c, r_core), cell_.core, RegionRole::core,
                              rod_index, row, 1, cell_.core_diameter_nm});
      }
    }
    if (r_ch > 0.0) {
      // Channels at the cell centre below the row: (a_x/2, z_row + a_z/2).
      const double z_ch = z_row + 0.5 * cell_.a_z_nm;
      for (int k = 0; k < n_sites; ++k) {
        const double s = (k + 0.5) * cell_.a_x_nm;
        if (s > L) break;
        Vec2 p, n;
        frame(s, p, n);
        const Vec2 c = p - z_ch * n;
        if (!inside(c, r_ch) || !occupied.clear(c, r_ch, min_gap_nm_, r_max)) continue;
        occupied.add(c, r_ch);
        cs.regions.push_back({disc(unit_channel, c, r_ch), cell_.channel,
                              RegionRole::channel, 0, row, 1, cell_.channel_diameter_nm});
      }
    }
  }
  return cs;
}

}  // namespace plumage::photonic_crystal
