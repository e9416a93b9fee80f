// A scene's `objects:` list (scene_sections.hpp): procedural feathers, barb-level assemblies and
// planes; the feather shape (feather_geometry.hpp) and the assembly's body as nested tables.
#include <algorithm>
#include <optional>

#include "plumage/feather_geometry.hpp"
#include "scene_sections.hpp"

namespace plumage::scene_detail {

namespace {

// ---- feather shape ---------------------------------------------------------------------------

// The rows of a feather shape with the defaults of `d`: FeatherShape's own (feather_geometry.hpp)
// for a feather object, a smaller feather for an assembly's body feather.
ParamTable<FeatherShape> make_shape_table(const FeatherShape& d) {
  using S = FeatherShape;
  // Lengths within a kilometre (params.hpp, Limits::scene_length_mm: the renderer's float geometry).
  const auto pos = Limits::scene_length_mm(), nonneg = Limits::closed(0.0, 1e6);
  return ParamTable<S>{}
      .number("length_mm", &S::length_mm, "mm", d.length_mm, pos, "rachis length covered by the vane (base to tip)")
      .number("calamus_mm", &S::calamus_mm, "mm", d.calamus_mm, nonneg, "bare quill below the vane")
      .number("vane_width_mm", &S::vane_width_mm, "mm", d.vane_width_mm, pos, "full width of the vane at its widest")
      .number("vane_asymmetry", &S::vane_asymmetry, "1", d.vane_asymmetry, Limits::closed(-0.8, 0.8),
              "left half-width x (1 - a), right x (1 + a)")
      .number("camber_mm", &S::camber_mm, "mm", d.camber_mm, Limits::scene_coordinate_mm(), "the vane bends down (-z) by this much at its edges")
      .number("rachis_width_mm", &S::rachis_width_mm, "mm", d.rachis_width_mm, pos,
              "diameter at the base, tapering to 20 % at the tip")
      .number("barb_spacing_mm", &S::barb_spacing_mm, "mm", d.barb_spacing_mm, pos, "along the rachis, on each side")
      .number("barb_angle_deg", &S::barb_angle_deg, "deg", d.barb_angle_deg, Limits{1.0, 89.0, true, true},
              "barb direction against the rachis at the barb's base")
      .number("barb_curl_deg", &S::barb_curl_deg, "deg", d.barb_curl_deg, Limits{0.0, 80.0, false, true},
              "the barb turns this much toward the tip over its length")
      .number("barb_width_mm", &S::barb_width_mm, "mm", d.barb_width_mm, pos, "barb strip width (explicit barbules)")
      .number("barb_segment_mm", &S::barb_segment_mm, "mm", d.barb_segment_mm, pos, "target segment length along a barb")
      .number("barbule_length_mm", &S::barbule_length_mm, "mm", d.barbule_length_mm, pos, "barbule length")
      .number("barbule_width_mm", &S::barbule_width_mm, "mm", d.barbule_width_mm, pos, "barbule strip width")
      .number("barbule_spacing_mm", &S::barbule_spacing_mm, "mm", d.barbule_spacing_mm, pos,
              "along the barb, per side (also the level of detail's barbule spacing)")
      .number("barbule_angle_deg", &S::barbule_angle_deg, "deg", d.barbule_angle_deg, Limits{0.0, 90.0, false, true},
              "barbule axis against the barb axis, in the vane plane")
      .number("barbule_tilt_deg", &S::barbule_tilt_deg, "deg", d.barbule_tilt_deg, Limits{-90.0, 90.0, true, true},
              "rotation of the barbule about its axis (paper §7.3)")
      .number("barbule_elevation_deg", &S::barbule_elevation_deg, "deg", d.barbule_elevation_deg,
              Limits{-90.0, 90.0, true, true}, "axis raised out of the vane plane")
      .integer("barbule_segments", &S::barbule_segments, "1", d.barbule_segments, Limits::closed(1, 16),
               "quads per barbule strip")
      .boolean("proximal_barbules", &S::proximal_barbules, d.proximal_barbules,
               "also the barbules on the base side of each barb")
      .number("jitter", &S::jitter, "1", d.jitter, Limits::closed(0.0, 0.5),
              "relative random variation of barb angle, spacing and length");
}

// The assembly's default body feather: short, broad, coarser barbs (barb-level).
FeatherShape body_feather() {
  FeatherShape small;
  small.length_mm = 12, small.vane_width_mm = 9, small.barb_spacing_mm = 0.5, small.barb_segment_mm = 0.8;
  small.rachis_width_mm = 0.3, small.calamus_mm = 1.0, small.camber_mm = 0.5;
  return small;
}

const ParamTable<FeatherShape>& shape_table() {
  static const auto table = make_shape_table(FeatherShape{});
  return table;
}
const ParamTable<FeatherShape>& body_feather_table() {
  static const auto table = make_shape_table(body_feather());
  return table;
}

// The shape `f` (the table's defaults) with the keys of `s` read into it; checked as a whole.
FeatherShape read_shape(const ParamView& s, const ParamTable<FeatherShape>& table, FeatherShape f) {
  table.read_into(s, f);
  try {
    validate_feather_shape(f);
  } catch (const Error& e) {
    s.fail_here(e.what());
  }
  return f;
}

const ParamTable<BodyShape>& body_table() {
  static const auto table =
      ParamTable<BodyShape>{}
          .custom("center_mm", "vector", "mm", "[0, 0, 0]", "centre of the ellipsoid",
                  [](const ParamView& p, BodyShape& b) { b.center_mm = read_vec3_or(p, "center_mm", {}); })
          .custom("radii_mm", "vector", "mm", "required", "semi-axes x, y (the long axis), z; all > 0",
                  [](const ParamView& p, BodyShape& b) {
                    b.radii_mm = read_vec3(p, "radii_mm", Limits::scene_length_mm());
                    if (!(b.radii_mm.x > 0 && b.radii_mm.y > 0 && b.radii_mm.z > 0)) p.fail("radii_mm", "must all be > 0");
                  })
          .number("lat_min_deg", &BodyShape::lat_min_deg, "deg", -90.0, Limits::closed(-90, 90),
                  "latitude band covered (y/ry = sin lat), from")
          .number("lat_max_deg", &BodyShape::lat_max_deg, "deg", 90.0, Limits::closed(-90, 90), "to (> lat_min_deg)");
  return table;
}

// ---- objects ---------------------------------------------------------------------------------

using ObjectKind = SceneObjectSpec::Kind;

struct ObjectKeys {
  std::size_t index = 0;
  SceneObjectSpec spec;
  std::string material;                        // names; resolved after reading
  std::optional<std::string> shaft_material;  // absent: the implicit default_shaft
  Vec3f position_mm, rotate_deg;
  double scale = 1.0;
};

template <ObjectKind K>
bool is(const ObjectKeys& k) {
  return k.spec.kind == K;
}
bool has_shaft(const ObjectKeys& k) { return k.spec.kind != ObjectKind::plane; }

const ParamTable<ObjectKeys>& object_table() {
  using K = ObjectKind;
  using O = ObjectKeys;
  static const auto table = [] {
    const AssemblyShape a;
    return ParamTable<O>{}
        .choice("type", [](O& o) -> K& { return o.spec.kind; },
                std::vector<std::pair<std::string_view, K>>{
                    {"feather", K::feather}, {"assembly", K::assembly}, {"plane", K::plane}},
                required,
                "feather (one procedural feather) | assembly (barb-level feathers on a body) | plane (a square)")
        .custom("name", "text", "-", "<type><index>", "name of the object (its meshes and messages)",
                [](const ParamView& p, O& o) {
                  const char* type = o.spec.kind == K::feather ? "feather" : o.spec.kind == K::assembly ? "assembly" : "plane";
                  o.spec.name = p.text_or("name", type + std::to_string(o.index));
                })
        .text("material", &O::material, required, "a material of `materials:` (feather objects: a feather material)")
        .integer("seed", [](O& o) -> std::uint64_t& { return o.spec.seed; }, "1", 1, Limits::non_negative(),
                 "seed of the object's random jitter")
        .custom("shaft_material", "text", "-", "default_shaft",
                "material of rachis and barbs (default_shaft: an implicit dark diffuse, albedo 0.04)",
                [](const ParamView& p, O& o) {
                  if (p.has("shaft_material")) o.shaft_material = p.text("shaft_material");
                })
        .only_if(has_shaft, "type: feather or assembly")
        .choice("detail", [](O& o) -> FeatherDetail& { return o.spec.detail; },
                {{"barbules", FeatherDetail::barbules}, {"barb_level", FeatherDetail::barb_level}},
                FeatherDetail::barbules, "explicit barbules (paper §7.3) | barb-level strips (§7.4)")
        .only_if(is<K::feather>, "type: feather")
        .custom("shape", "map", "-", "{}", "the feather's shape (FeatherShape)",
                [](const ParamView& p, O& o) {
                  o.spec.shape = p.has("shape") ? read_shape(p.child("shape"), shape_table(), FeatherShape{}) : FeatherShape{};
                })
        .nested_specs(shape_table().specs())
        .only_if(is<K::feather>, "type: feather")
        .custom("position_mm", "vector", "mm", "[0, 0, 0]", "where the feather's base goes",
                [](const ParamView& p, O& o) { o.position_mm = read_vec3_or(p, "position_mm", {}); })
        .only_if(is<K::feather>, "type: feather")
        .custom("rotate_deg", "vector", "deg", "[0, 0, 0]", "Euler angles about x, then y, then z",
                [](const ParamView& p, O& o) { o.rotate_deg = read_vec3_or(p, "rotate_deg", {}, Limits::closed(-3600, 3600)); })
        .only_if(is<K::feather>, "type: feather")
        .number("scale", &O::scale, "1", 1.0, Limits{0.0, 1e4, true, false},
                "uniform scale of the feather (at most 1e4: its lengths stay within the scene's kilometre)")
        .only_if(is<K::feather>, "type: feather")
        .integer("count", [](O& o) -> int& { return o.spec.assembly.count; }, "1", a.count, Limits::closed(1, 100000),
                 "feathers on the body")
        .only_if(is<K::assembly>, "type: assembly")
        .number("lie_deg", [](O& o) -> double& { return o.spec.assembly.lie_deg; }, "deg", a.lie_deg,
                Limits::closed(0, 89), "feather plane against the local tangent plane")
        .only_if(is<K::assembly>, "type: assembly")
        .number("heading_jitter_deg", [](O& o) -> double& { return o.spec.assembly.heading_jitter_deg; }, "deg",
                a.heading_jitter_deg, Limits::closed(0, 180), "random heading")
        .only_if(is<K::assembly>, "type: assembly")
        .number("lie_jitter_deg", [](O& o) -> double& { return o.spec.assembly.lie_jitter_deg; }, "deg",
                a.lie_jitter_deg, Limits::closed(0, 45), "random lie")
        .only_if(is<K::assembly>, "type: assembly")
        .number("size_jitter", [](O& o) -> double& { return o.spec.assembly.size_jitter; }, "1", a.size_jitter,
                Limits::closed(0, 0.9), "relative random size")
        .only_if(is<K::assembly>, "type: assembly")
        .number("position_jitter", [](O& o) -> double& { return o.spec.assembly.position_jitter; }, "1",
                a.position_jitter, Limits::closed(0, 1), "random position, of the lattice spacing")
        .only_if(is<K::assembly>, "type: assembly")
        .custom("body", "map", "-", "required", "the ellipsoid the feathers sit on",
                [](const ParamView& p, O& o) {
                  const ParamView body = p.child("body");
                  BodyShape& b = o.spec.assembly.body;
                  b = body_table().read(body);
                  if (!(b.lat_min_deg < b.lat_max_deg)) body.fail("lat_max_deg", "must exceed lat_min_deg");
                })
        .nested_specs(body_table().specs())
        .only_if(is<K::assembly>, "type: assembly")
        .custom("feather", "map", "-", "{}", "the mean body feather (FeatherShape, smaller defaults)",
                [](const ParamView& p, O& o) {
                  o.spec.assembly.feather =
                      p.has("feather") ? read_shape(p.child("feather"), body_feather_table(), body_feather()) : body_feather();
                })
        .nested_specs(body_feather_table().specs())
        .only_if(is<K::assembly>, "type: assembly")
        .custom("center_mm", "vector", "mm", "[0, 0, 0]", "centre of the square",
                [](const ParamView& p, O& o) { o.spec.center_mm = read_vec3_or(p, "center_mm", {}); })
        .only_if(is<K::plane>, "type: plane")
        .custom("normal", "vector", "1", "[0, 0, 1]", "the side it faces (normalised)",
                [](const ParamView& p, O& o) {
                  if (p.has("normal")) o.spec.normal = read_unit3(p, "normal");
                })
        .only_if(is<K::plane>, "type: plane")
        .number("size_mm", [](O& o) -> double& { return o.spec.size_mm; }, "mm", 100.0, Limits::scene_length_mm(),
                "side of the square")
        .only_if(is<K::plane>, "type: plane");
  }();
  return table;
}

// Index of material `name` (the key `key` of `o`), or a ConfigError naming the nearest one.
std::uint32_t material_index(const ParamView& o, std::string_view key, const std::string& name,
                             const std::vector<SceneMaterial>& materials) {
  std::vector<std::string> names;
  for (const auto& m : materials) names.push_back(m.name);
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<std::uint32_t>(it - names.begin());
  std::string msg = "unknown material '" + name + "'";
  if (auto near = nearest_name(name, names)) msg += " (did you mean '" + *near + "'?)";
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
  o.fail(key, msg + "; materials: " + (all.empty() ? "(none)" : all));
}

// Implicit material for rachis and barbs when an object names none: dark keratin.
std::uint32_t default_shaft(SceneConfig& c) {
  for (std::size_t k = 0; k < c.materials.size(); ++k)
    if (c.materials[k].name == "default_shaft") return static_cast<std::uint32_t>(k);
  SceneMaterial m;
  m.name = "default_shaft";
  m.kind = SceneMaterial::Kind::diffuse;
  m.albedo.value = {0.04};
  m.albedo.lambda_nm = {550.0};
  c.materials.push_back(m);
  c.feather_requests.emplace_back();
  return static_cast<std::uint32_t>(c.materials.size() - 1);
}

}  // namespace

void read_objects(const ParamView& root, SceneConfig& c) {
  std::size_t index = 0;
  for (const ParamView& o : root.items("objects")) {
    ObjectKeys k = object_table().defaults();
    k.index = index++;
    object_table().read_into(o, k);
    SceneObjectSpec obj = std::move(k.spec);
    // Materials resolve against the explicit ones first (the implicit default_shaft comes last).
    obj.material = material_index(o, "material", k.material, c.materials);
    const bool feather_material = c.materials[obj.material].kind == SceneMaterial::Kind::feather;
    if (obj.kind != ObjectKind::plane) {
      obj.shaft_material =
          k.shaft_material ? material_index(o, "shaft_material", *k.shaft_material, c.materials) : default_shaft(c);
    }
    if (obj.kind == ObjectKind::feather) {
      obj.placement = placement_from_euler(k.position_mm, k.rotate_deg, k.scale);
      if (!feather_material) o.fail("material", "a feather object needs a feather material");
    } else if (obj.kind == ObjectKind::assembly) {
      if (!feather_material) o.fail("material", "an assembly needs a feather material");
    } else if (feather_material) {
      o.fail("material", "a plane takes a diffuse or dielectric material");
    }
    c.objects.push_back(std::move(obj));
  }
  if (c.objects.empty()) root.fail("objects", "a scene needs at least one object");
}

std::vector<ParamSpec> object_specs() { return object_table().specs(); }

}  // namespace plumage::scene_detail
