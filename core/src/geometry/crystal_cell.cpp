// Bit-identical geometry on every machine: no fused multiply-add contraction (-march=native
// would otherwise decide per machine).
#pragma GCC optimize("fp-contract=off")
#include "plumage/crystal_cell.hpp"

#include <algorithm>
#include <cmath>

#include "plumage/config_document.hpp"
#include "plumage/config_sections.hpp"
#include "plumage/param_table.hpp"
#include "yaml_state.hpp"

namespace plumage {

namespace {

using Lattice = CrystalCell::Lattice;

// The `materials:` map: host, rod, core, channel, each a material name or map.
void read_materials(const ParamView& node, CrystalCell& c) {
  if (auto m = node.child_if("materials")) {
    if (m->has("host")) c.host = parse_material(*m, "host");
    if (m->has("rod")) c.rod = parse_material(*m, "rod");
    if (m->has("core")) c.core = parse_material(*m, "core");
    if (m->has("channel")) c.channel = parse_material(*m, "channel");
  }
}

const ParamTable<CrystalCell>& crystal_table() {
  static const auto table =
      ParamTable<CrystalCell>{}
          .text("name", &CrystalCell::name, required, "name of the cell (the table's crystal name)")
          .choice("lattice", &CrystalCell::lattice,
                  std::vector<std::pair<std::string_view, Lattice>>{{"hexagonal", Lattice::hexagonal},
                                                                    {"rectangular", Lattice::rectangular}},
                  required,
                  "hexagonal (odd rows shifted by a_x/2) | rectangular (rows above each other)")
          .number("a_x_nm", &CrystalCell::a_x_nm, "nm", required, Limits{0.0, 5000.0, true, false},
                  "period along the surface (birds' crystals: 100-500 nm; up to 5 um, the longest wavelength)")
          .number("a_z_nm", &CrystalCell::a_z_nm, "nm", required, Limits{0.0, 5000.0, true, false},
                  "row spacing in depth (up to 5 um, as a_x_nm)")
          .number("rod_diameter_nm", &CrystalCell::rod_diameter_nm, "nm", required, Limits{0.0, 5000.0, true, false},
                  "outer diameter of the rods (melanosomes; up to 5 um, as a_x_nm)")
          .number("core_diameter_nm", &CrystalCell::core_diameter_nm, "nm", 0.0, Limits::non_negative(),
                  "air core of hollow rods (0: solid)")
          .number("channel_diameter_nm", &CrystalCell::channel_diameter_nm, "nm", 0.0, Limits::non_negative(),
                  "channel at (a_x/2, z_j + a_z/2) below each row (rectangular lattices; 0: none)")
          .integer("rows", &CrystalCell::rows, "1", required, Limits::closed(1, 1000), "rows of rods")
          .number("cortex_nm", &CrystalCell::cortex_nm, "nm", required, Limits::closed(0.0, 100000.0),
                  "host material from the surface to the top of the first row")
          .number("expected_peak_nm", &CrystalCell::expected_peak_nm, "nm", 0.0, Limits::non_negative(),
                  "informational: expected reflectance peak at normal incidence (0: not given)")
          .custom("materials", "map", "-", "{}", "materials of the cell's parts", read_materials)
          .nested_specs({{"host", "material", "-", "keratin", "around the rods"},
                         {"rod", "material", "-", "melanin", "the rods"},
                         {"core", "material", "-", "air", "cores of hollow rods"},
                         {"channel", "material", "-", "air", "the channels"}});
  return table;
}

const ConfigSectionRegistration kCrystalSection{
    {"crystal", "crystal", "the photonic-crystal unit cell (a map under any other key is a table builder's section)",
     [] { return crystal_table().specs(); }}};

// Every map under a key the table does not declare is a table builder's section, kept unread (a
// view of its own, outside this map's bookkeeping, so that finish() leaves it to the builder). A
// key within a typo of a map-valued cell field (`materials`) is reported as the unknown key it
// is; scalar fields are no candidates (a map cannot be a misspelt `rows`, and `rcwa` is one typo
// of edit distance 2 away from it).
void collect_builder_sections(const ParamView& node, CrystalCell& c) {
  std::vector<std::string> fields;
  for (const ParamSpec& spec : crystal_table().specs())
    if (spec.type == "map") fields.push_back(spec.name);
  const std::vector<std::string> known = node.known_keys();
  for (const std::string& key : node.keys()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const YAML::Node& map = node.state()->node;
    const YAML::Node value = map[key];
    // A key yaml-cpp cannot look up again by its text (a null key spelt `NULL`, found by
    // fuzz_crystal) gives an invalid node, whose IsMap() throws: finish() reports the key instead.
    if (!value.IsDefined() || !value.IsMap()) continue;
    if (auto near = nearest_name(key, fields)) {
      node.fail(key, "unknown key (did you mean '" + *near + "'?); a map under any other key is a table builder's section");
    }
    auto state = std::make_shared<ParamView::State>();
    state->node = value;
    state->file = node.file();
    state->path = node.path_of(key);
    node.accept(key);
    c.builder_sections.emplace(key, ParamView(state));
  }
}

}  // namespace

CrystalCell parse_crystal_cell(const ParamView& node) {
  CrystalCell c = crystal_table().read(node);
  collect_builder_sections(node, c);
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
