#include "slicing.hpp"

#include <algorithm>
#include <cmath>

namespace plumage::rcwa {

namespace {

struct Circle {
  double x, z, r;
  int material, under;
};

// ∫ chord width dz from the circle's top to depth z: r²(t√(1−t²) + asin t + π/2), t = (z − zc)/r.
double chord_integral(const Circle& c, double z) {
  const double t = std::clamp((z - c.z) / c.r, -1.0, 1.0);
  return c.r * c.r * (t * std::sqrt(1.0 - t * t) + std::asin(t) + 0.5 * kPi);
}

std::vector<Circle> circles_of(const CrystalCell& c) {
  std::vector<Circle> out;
  for (int j = 0; j < c.rows; ++j) {
    const double zj = c.rod_depth_nm(j);
    const double xj = c.shifted(j) ? 0.5 * c.a_x_nm : 0.0;
    out.push_back({xj, zj, 0.5 * c.rod_diameter_nm, 2, 1});
    if (c.core_diameter_nm > 0) out.push_back({xj, zj, 0.5 * c.core_diameter_nm, 3, 2});
    if (c.channel_diameter_nm > 0) out.push_back({0.5 * c.a_x_nm, zj + 0.5 * c.a_z_nm, 0.5 * c.channel_diameter_nm, 4, 1});
  }
  return out;
}

bool same_geometry(const Slice& a, const Slice& b) {
  if (std::abs(a.thickness_nm - b.thickness_nm) > 1e-9 || a.boxes.size() != b.boxes.size()) return false;
  for (std::size_t i = 0; i < a.boxes.size(); ++i) {
    const Box &p = a.boxes[i], &q = b.boxes[i];
    if (p.material != q.material || p.under != q.under || std::abs(p.x_center_nm - q.x_center_nm) > 1e-9 ||
        std::abs(p.width_nm - q.width_nm) > 1e-9)
      return false;
  }
  return true;
}

}  // namespace

void assign_slice_types(SlicedCell& cell) {
  std::vector<const Slice*> reps;
  for (Slice& s : cell.slices) {
    auto it = std::find_if(reps.begin(), reps.end(), [&](const Slice* r) { return same_geometry(*r, s); });
    s.type = static_cast<int>(it - reps.begin());
    if (it == reps.end()) reps.push_back(&s);
  }
  cell.n_types = static_cast<int>(reps.size());
  cell.half_shift_type.assign(reps.size(), -1);
  for (std::size_t t = 0; t < reps.size(); ++t) {
    Slice shifted = *reps[t];
    for (Box& b : shifted.boxes) b.x_center_nm = std::fmod(b.x_center_nm + 0.5 * cell.period_nm, cell.period_nm);
    for (std::size_t u = 0; u < reps.size(); ++u)
      if (same_geometry(*reps[u], shifted)) cell.half_shift_type[t] = static_cast<int>(u);
  }
}

SlicedCell slice_crystal(const CrystalCell& c, int slices_per_row) {
  SlicedCell out;
  out.period_nm = c.a_x_nm;
  out.materials = {Material::air(), c.host, c.rod, c.core, c.channel};
  const std::vector<Circle> circles = circles_of(c);
  std::vector<double> cuts = {0.0, c.cortex_nm};
  for (const Circle& k : circles) cuts.insert(cuts.end(), {k.z - k.r, k.z + k.r});
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }), cuts.end());
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double z0 = cuts[i], z1 = cuts[i + 1];
    bool crossed = false;
    for (const Circle& k : circles) crossed = crossed || (k.z - k.r < z1 - 1e-12 && k.z + k.r > z0 + 1e-12);
    const int n = crossed ? std::max(1, static_cast<int>(std::ceil(slices_per_row * (z1 - z0) / c.rod_diameter_nm - 1e-9))) : 1;
    for (int s = 0; s < n; ++s) {
      const double a = z0 + (z1 - z0) * s / n, b = z0 + (z1 - z0) * (s + 1) / n;
      Slice slice;
      slice.thickness_nm = b - a;
      for (const Circle& k : circles) {
        const double w = (chord_integral(k, b) - chord_integral(k, a)) / (b - a);
        if (w > 1e-12) slice.boxes.push_back({k.x, w, k.material, k.under});
      }
      out.slices.push_back(std::move(slice));
    }
  }
  assign_slice_types(out);
  return out;
}

}  // namespace plumage::rcwa
