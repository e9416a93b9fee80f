// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "plumage/crystal_cell.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "plumage/config_document.hpp"

namespace plumage {

CrystalCell parse_crystal_cell(const ParamView& node) {
  CrystalCell c;
  c.name = node.text("name");
  static constexpr std::array<std::string_view, 2> lattices{"hexagonal", "rectangular"};
  c.lattice = node.choice("lattice", lattices) == "hexagonal" ? CrystalCell::Lattice::hexagonal
                                                               : CrystalCell::Lattice::rectangular;
  c.a_x_nm = node.number("a_x_nm", Limits::positive());
  c.a_z_nm = node.number("a_z_nm", Limits::positive());
  c.rod_diameter_nm = node.number("rod_diameter_nm", Limits::positive());
  c.core_diameter_nm = node.number_or("core_diameter_nm", 0.0, Limits::non_negative());
  c.channel_diameter_nm = node.number_or("channel_diameter_nm", 0.0, Limits::non_negative());
  c.rows = static_cast<int>(node.integer("rows", Limits::closed(1, 1000)));
  c.cortex_nm = node.number("cortex_nm", Limits::non_negative());
  c.expected_peak_nm = node.number_or("expected_peak_nm", 0.0, Limits::non_negative());
  if (auto f = node.child_if("fdtd")) {
    c.fdtd_dispersion_correction = f->boolean_or("dispersion_correction", false);
    c.fdtd_exact_fill = f->boolean_or("exact_fill", false);
    c.fdtd_resolution_nm = f->number_or("resolution_nm", 0.0, Limits::non_negative());
    c.fdtd_grazing_anchors = static_cast<int>(f->integer_or("grazing_anchors", 2, Limits::closed(1, 5)));
  }
  if (auto m = node.child_if("materials")) {
    if (m->has("host")) c.host = parse_material(*m, "host");
    if (m->has("rod")) c.rod = parse_material(*m, "rod");
    if (m->has("core")) c.core = parse_material(*m, "core");
    if (m->has("channel")) c.channel = parse_material(*m, "channel");
  }
  const double d = c.rod_diameter_nm;
  if (c.core_diameter_nm >= d) node.fail("core_diameter_nm", "the air core must be smaller than the rod");
  if (d >= c.a_x_nm) node.fail("rod_diameter_nm", "rods of one row overlap (rod diameter >= a_x)");
  // Nearest rod of the next row: straight below (rectangular) or half a period aside (hexagonal).
  const double dx = c.lattice == CrystalCell::Lattice::hexagonal ? 0.5 * c.a_x_nm : 0.0;
  if (c.rows > 1 && std::hypot(dx, c.a_z_nm) <= d) {
    node.fail("a_z_nm", "rods of neighbouring rows overlap");
  }
  if (c.channel_diameter_nm > 0.0) {
    if (c.lattice != CrystalCell::Lattice::rectangular) {
      node.fail("channel_diameter_nm", "air channels belong to rectangular lattices");
    }
    // Channel centre (a_x/2, a_z/2) from the rods at (0, 0), (a_x, 0), (0, a_z), (a_x, a_z).
    const double gap = std::hypot(0.5 * c.a_x_nm, 0.5 * c.a_z_nm) - 0.5 * d - 0.5 * c.channel_diameter_nm;
    if (gap <= 0.0) node.fail("channel_diameter_nm", "channels overlap the rods");
  }
  return c;
}

CrystalCell load_crystal_cell(const std::filesystem::path& file) {
  auto doc = ConfigDocument::load(file);
  ParamView root = doc.root();
  CrystalCell cell = parse_crystal_cell(root.child("crystal"));
  root.accept("description");
  root.finish();
  return cell;
}

}  // namespace plumage
