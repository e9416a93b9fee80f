// The render pipeline as a library (render_job.hpp) with a stand-in renderer: the renderer reads
// its own section and the job's overrides through its table; unknown keys and bad values are
// located errors; views, materials and the two output files.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "plumage/config_document.hpp"
#include "plumage/exr.hpp"
#include "plumage/param_table.hpp"
#include "plumage/render_job.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

// A renderer with two settings of its own: every pixel = (spp, seed, 0.5); `bins` spectral bins
// of value spp.
struct StubSettings {
  int spp = 16;
  std::uint64_t seed = 1;
  int bins = 0;
};

const ParamTable<StubSettings>& stub_table() {
  static const auto t = ParamTable<StubSettings>{}
                            .integer("spp", &StubSettings::spp, "1", 16, Limits::closed(1, 64), "samples")
                            .integer("seed", &StubSettings::seed, "1", 1, Limits::non_negative(), "seed")
                            .integer("bins", &StubSettings::bins, "1", 0, Limits::closed(0, 8), "spectral bins");
  return t;
}

class StubRenderer final : public Renderer {
 public:
  explicit StubRenderer(StubSettings s) : s_(s) {}
  RenderResult render(const Scene& scene, Progress progress) const override {
    RenderResult r;
    r.rgb = LinearImage(scene.camera.width, scene.camera.height);
    for (RgbF& p : r.rgb.pixels()) p = {float(s_.spp), float(s_.seed), 0.5f};
    if (s_.bins > 0) {
      r.spectral.bins = s_.bins;
      r.spectral.values.assign(r.rgb.pixels().size() * static_cast<std::size_t>(s_.bins), float(s_.spp));
    }
    r.stats.camera_paths = static_cast<std::uint64_t>(scene.camera.width) * scene.camera.height * s_.spp;
    if (progress) progress(1, 1, "frames");
    return r;
  }
  std::string describe() const override { return std::to_string(s_.spp) + " spp, seed " + std::to_string(s_.seed); }

 private:
  StubSettings s_;
};

const PluginRegistry& stub_registry() {
  static const PluginRegistry r = [] {
    PluginRegistry reg;
    reg.builtin_registrar().add<Renderer>(
        {.type = "stub", .version = "1", .summary = "test stand-in", .params = stub_table().specs()},
        [](const ParamView& p, const PluginContext&) { return std::make_unique<StubRenderer>(stub_table().read(p)); });
    return reg;
  }();
  return r;
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-render-job";
  fs::create_directories(dir);
  return dir;
}

fs::path write_scene(const std::string& name, const std::string& renderer_line, const std::string& extra = "") {
  const fs::path file = scratch() / name;
  std::ofstream(file) << "scene: " << fs::path(name).stem().string() << "\n"
                      << "render: {resolution: [6, 4], exposure: 2}\n"
                      << "camera: {position_mm: [0, 0, 50], look_at_mm: [0, 0, 0], up: [0, 1, 0], fov_deg: 20}\n"
                      << "lights: [{type: distant, toward_light: [0, 0, 1]}]\n"
                      << "materials: {paper: {type: diffuse, albedo: 0.5}}\n"
                      << "objects: [{type: plane, material: paper}]\n"
                      << renderer_line << "\n"
                      << extra;
  return file;
}

RenderJobOptions with_settings(const std::vector<std::pair<std::string, std::string>>& settings) {
  RenderJobOptions o;
  for (const auto& [key, value] : settings) o.renderer_settings.push_back({key, value, "test --" + key});
  return o;
}

}  // namespace

TEST_CASE("render job: the renderer reads its section and the overrides through its own table", "[render][job]") {
  const fs::path scene = write_scene("own.yaml", "renderer: {type: stub, seed: 9}");
  CHECK(RenderJob(scene, {}, stub_registry()).renderer().describe() == "16 spp, seed 9");
  CHECK(RenderJob(scene, with_settings({{"spp", "4"}}), stub_registry()).renderer().describe() == "4 spp, seed 9");
  CHECK(RenderJob(scene, with_settings({{"seed", "2"}}), stub_registry()).renderer().describe() == "16 spp, seed 2");
  // `renderer: <type>` and a map without `type` take the same overrides.
  const fs::path named = write_scene("named.yaml", "renderer: stub");
  CHECK(RenderJob(named, with_settings({{"spp", "3"}}), stub_registry()).renderer().describe() == "3 spp, seed 1");
  // Out of range: the renderer's table names the key.
  CHECK_THROWS_WITH(RenderJob(scene, with_settings({{"spp", "100"}}), stub_registry()),
                    Catch::Contains("test --spp") && Catch::Contains("renderer.spp"));
  // A key the renderer does not have: refused with the nearest one.
  CHECK_THROWS_WITH(RenderJob(scene, with_settings({{"sed", "2"}}), stub_registry()), Catch::Contains("did you mean 'seed'"));
  // In the file: the line of the section.
  const fs::path typo = write_scene("typo.yaml", "renderer: {type: stub, spp: 4, sed: 2}");
  CHECK_THROWS_WITH(RenderJob(typo, {}, stub_registry()), Catch::Contains("typo.yaml:7:") && Catch::Contains("did you mean 'seed'"));
  // An unknown type, given by name: the scene's line and the nearest type.
  const fs::path unknown = write_scene("unknown.yaml", "renderer: stbu");
  try {
    RenderJob job(unknown, {}, stub_registry());
    FAIL("an unknown renderer type was accepted");
  } catch (const ConfigError& e) {
    CHECK(e.mark().line == 7);
    CHECK(e.field() == "renderer");
    CHECK(std::string(e.what()).find("did you mean 'stub'") != std::string::npos);
  }
}

TEST_CASE("render job: views, materials and the two files of a view", "[render][job]") {
  const fs::path scene = write_scene("views.yaml", "renderer: {type: stub, bins: 3}",
                                     "views: [{name: a}, {name: b, camera: {position_mm: [5, 0, 50]}}]\n");
  RenderJobOptions o;
  o.view = "b";
  o.width = 5, o.height = 3;
  RenderJob job(scene, o, stub_registry());
  REQUIRE(job.views().size() == 1);
  CHECK(job.views()[0]->name == "b");
  CHECK_THROWS_WITH(job.render_view(0, scratch(), {}), Catch::Contains("build_geometry"));
  CHECK(job.build_geometry().triangles == 2);
  int resolved = 0;
  job.resolve_materials([&](const FeatherMaterialRequest&) {
    ++resolved;
    return std::shared_ptr<const FeatherBsdf>();
  });
  CHECK(resolved == 0);  // no feather material in this scene
  const fs::path out = scratch() / "out";
  fs::remove_all(out);
  int calls = 0;
  const RenderedView v = job.render_view(0, out, [&](std::size_t, std::size_t, std::string_view) { ++calls; });
  CHECK(calls == 1);
  CHECK(v.name == "views-b");
  CHECK(v.width == 5);
  CHECK(v.height == 3);
  CHECK(v.stats.camera_paths == 5u * 3u * 16u);
  REQUIRE(fs::exists(out / "views-b.exr"));
  REQUIRE(fs::exists(out / "views-b.png"));
  const LinearImage img = read_exr_rgb(v.exr);
  CHECK(img.width() == 5);
  CHECK(img.at(0, 0).r == 16.0f);
  for (const auto& e : fs::directory_iterator(out)) CHECK(e.path().string().find("partial") == std::string::npos);
  // The single view's meshes moved into its scene: it renders once.
  CHECK_THROWS_WITH(job.render_view(0, out, {}), Catch::Contains("rendered already"));
  // An unknown view is bad input naming the nearest one.
  o.view = "c";
  CHECK_THROWS_AS(RenderJob(scene, o, stub_registry()), ConfigError);
  o.view = "bb";
  CHECK_THROWS_WITH(RenderJob(scene, o, stub_registry()), Catch::Contains("did you mean 'b'"));
}

TEST_CASE("render job: a failed write leaves neither file", "[render][job]") {
  const fs::path dir = scratch() / "blocked";
  fs::remove_all(dir);
  fs::create_directories(dir / "x.png");  // a folder where the PNG should go: its rename fails
  RenderResult r;
  r.rgb = LinearImage(2, 2);
  CHECK_THROWS(write_render_images(r, 1.0, dir / "x.exr", dir / "x.png"));
  CHECK_FALSE(fs::exists(dir / "x.exr"));
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().string().find("partial") == std::string::npos);
}
