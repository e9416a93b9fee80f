// Scene files (scene_config.hpp): the shipped scenes parse and build within their limits; bad
// input fails with file:line:column, the field and the nearest valid name.
#include <catch2/catch.hpp>

#include <fstream>

#include "plumage/scene_config.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

// A scene whose text is parsed with the name "test.yaml" (relative paths from the source tree).
SceneConfig parse(const std::string& text) {
  // Written beside the species configs' folder so `species: ../species/...` resolves.
  const fs::path dir = fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "scenes";
  const fs::path tmp = fs::temp_directory_path() / "plumage-test-scene";
  fs::create_directories(tmp);
  const fs::path file = tmp / "test.yaml";
  std::string t = text;
  for (std::string::size_type p; (p = t.find("@SPECIES@")) != std::string::npos;) t.replace(p, 9, (dir.parent_path() / "species").string());
  std::ofstream(file) << t;
  return load_scene_config(file);
}

const std::string kBase =
    "scene: tiny\n"
    "render: {resolution: [32, 24]}\n"
    "camera: {position_mm: [0, -20, 30], look_at_mm: [0, 5, 0], fov_deg: 40}\n"
    "lights:\n"
    "  - {type: distant, toward_light: [0, 0, 1], irradiance: 2}\n"
    "  - {type: environment, radiance: 0.1}\n"
    "materials:\n"
    "  starling: {type: feather, species: @SPECIES@/starling.yaml, variant: green}\n"
    "  ground: {type: diffuse, albedo: 0.3}\n"
    "objects:\n"
    "  - {type: feather, material: starling, detail: barb_level, shape: {length_mm: 10, vane_width_mm: 4}}\n"
    "  - {type: plane, material: ground, size_mm: 50}\n"
    "renderer: {type: pathtracer, spp: 4, seed: 3, lod: mean}\n";

std::string with(const std::string& from, const std::string& to) {
  std::string t = kBase;
  const auto p = t.find(from);
  REQUIRE(p != std::string::npos);
  return t.replace(p, from.size(), to);
}

}  // namespace

TEST_CASE("a small scene parses into settings, camera, lights, materials, objects", "[scene][config]") {
  const SceneConfig c = parse(kBase);
  CHECK(c.name == "tiny");
  // The renderer's section is the renderer's (render_job.hpp reads it through its table).
  CHECK(c.has_renderer_section);
  CHECK(c.exposure == 1.0);
  REQUIRE(c.views.size() == 1);
  CHECK(c.views[0].camera.width == 32);
  CHECK(c.views[0].camera.height == 24);
  CHECK(c.views[0].camera.vertical_fov_rad == Approx(40 * M_PI / 180));
  CHECK(c.views[0].distant_lights.size() == 1);
  CHECK(c.views[0].environment.radiance == 0.1);
  // starling, ground, and the implicit shaft material of the feather.
  REQUIRE(c.materials.size() == 3);
  CHECK(c.materials[0].kind == SceneMaterial::Kind::feather);
  REQUIRE(c.feather_requests[0].has_value());
  CHECK(c.feather_requests[0]->variant == "green");
  CHECK(c.feather_requests[0]->fidelity == "preview");
  CHECK(c.materials[1].albedo.at(500) == 0.3);
  CHECK(c.materials[2].name == "default_shaft");
  REQUIRE(c.objects.size() == 2);
  CHECK(c.objects[0].detail == FeatherDetail::barb_level);
  CHECK(c.objects[0].shape.length_mm == 10);
  SceneGeometryStats st;
  const auto meshes = build_scene_meshes(c, &st);
  CHECK(meshes.size() == 3);
  CHECK(st.feathers == 1);
  CHECK(st.triangles > 100);
}

TEST_CASE("scene errors name file:line:column, the field and the nearest name", "[scene][config]") {
  // Unknown key in a nested map (line 3 is the camera).
  CHECK_THROWS_WITH(parse(with("fov_deg: 40", "fov_dg: 40")),
                    Catch::Contains("test.yaml:3:") && Catch::Contains("camera.fov_dg") && Catch::Contains("did you mean 'fov_deg'"));
  // Unknown key inside a feather shape.
  CHECK_THROWS_WITH(parse(with("length_mm: 10", "lenght_mm: 10")),
                    Catch::Contains("test.yaml:11:") && Catch::Contains("lenght_mm") && Catch::Contains("did you mean 'length_mm'"));
  // Unknown light type, material reference, LOD word.
  CHECK_THROWS_WITH(parse(with("type: distant", "type: distnat")), Catch::Contains("test.yaml:5:") && Catch::Contains("distant"));
  CHECK_THROWS_WITH(parse(with("material: ground", "material: gruond")),
                    Catch::Contains("test.yaml:12:") && Catch::Contains("did you mean 'ground'"));
  // Wrong vector size, out-of-range value, missing species file, feather material on a plane.
  CHECK_THROWS_WITH(parse(with("toward_light: [0, 0, 1]", "toward_light: [0, 1]")), Catch::Contains("expected 3 numbers"));
  CHECK_THROWS_WITH(parse(with("resolution: [32, 24]", "resolution: [32, 24.5]")), Catch::Contains("render.resolution"));
  // A renderer setting left in `render:` says where it belongs now.
  CHECK_THROWS_WITH(parse(with("resolution: [32, 24]", "resolution: [32, 24], spp: 4")),
                    Catch::Contains("test.yaml:2:") && Catch::Contains("render.spp") && Catch::Contains("renderer: {type: pathtracer, spp"));
  CHECK_THROWS_WITH(parse(with("resolution: [32, 24]", "resolutoin: [32, 24]")), Catch::Contains("did you mean 'resolution'"));
  CHECK_THROWS_WITH(parse(with("starling.yaml", "starlin.yaml")), Catch::Contains("no such species config"));
  CHECK_THROWS_WITH(parse(with("material: ground", "material: starling")), Catch::Contains("plane takes a diffuse"));
  // A scene without light.
  CHECK_THROWS_WITH(parse(with("  - {type: distant, toward_light: [0, 0, 1], irradiance: 2}\n  - {type: environment, radiance: 0.1}\n", "  []\n")),
                    Catch::Contains("no light"));
}

TEST_CASE("views override the camera key by key and replace the lights", "[scene][config]") {
  const SceneConfig c = parse(kBase +
                              "views:\n"
                              "  - {name: front}\n"
                              "  - {name: side, camera: {position_mm: [30, 0, 10]}, lights: [{type: point, position_mm: [0, 0, 50]}]}\n");
  REQUIRE(c.views.size() == 2);
  CHECK(c.views[0].distant_lights.size() == 1);
  CHECK(c.views[1].camera.position_mm.x == 30);
  CHECK(c.views[1].camera.look_at_mm.y == 5);  // inherited
  CHECK(c.views[1].distant_lights.empty());
  CHECK(c.views[1].point_lights.size() == 1);
  CHECK(find_view(c, "side").name == "side");
  CHECK_THROWS_WITH(find_view(c, "sdie"), Catch::Contains("did you mean 'side'"));
}

TEST_CASE("a geometry limit names the object", "[scene][config]") {
  const SceneConfig c = parse(with("resolution: [32, 24]}", "resolution: [32, 24], max_triangles: 100}"));
  CHECK_THROWS_WITH(build_scene_meshes(c), Catch::Contains("object 'feather0'") && Catch::Contains("limit of 100 "));
}

TEST_CASE("every shipped scene parses and builds within its triangle limit", "[scene][config]") {
  int count = 0;
  for (const auto& e : fs::directory_iterator(fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "scenes")) {
    if (e.path().extension() != ".yaml") continue;
    INFO(e.path());
    SceneConfig c;
    REQUIRE_NOTHROW(c = load_scene_config(e.path()));
    SceneGeometryStats st;
    CHECK_NOTHROW(build_scene_meshes(c, &st));
    CHECK(st.triangles > 0);
    ++count;
  }
  CHECK(count >= 5);
}
