// `plumage render SCENE.yaml [--out DIR] [--view NAME] [--spp N] [--width W --height H]
// [--lod auto|mean|instance] [--threads N] [--seed N] [--materials DIR] [--no-characterize]
// [--check]`: read a scene (scene_config.hpp), build its feathers, resolve every feather material
// (the library's material store, plumage/material_store.hpp), render each view with the renderer
// plug-in (kind "renderer", default "pathtracer") and write <out>/<scene>[-<view>].exr and .png.
// Both files of a view appear together or not at all (temporary names, then renames).
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/material_store.hpp"
#include "plumage/exr.hpp"
#include "plumage/image.hpp"
#include "plumage/renderer.hpp"
#include "plumage/scene_config.hpp"
#include "progress.hpp"

namespace plumage::cli {

namespace fs = std::filesystem;

namespace {

struct Options {
  std::string scene, out = "build/render", view, lod, materials = "build/materials";
  int spp = 0, width = 0, height = 0, threads = 0;
  std::optional<std::uint64_t> seed;
  bool no_characterize = false, check = false;
};

std::unique_ptr<Renderer> create_renderer(const SceneConfig& c, AppContext& context) {
  const PluginRegistry& registry = context.registry();
  const PluginContext pc = registry.context(c.file.parent_path());
  if (!c.has_renderer_section) return registry.create_named<Renderer>("pathtracer", ParamView{}, pc);
  const ParamView node = c.root.node("renderer");
  if (node.is_map()) return registry.create<Renderer>(node, "type", pc);
  const std::string type = c.root.text("renderer");
  try {
    return registry.create_named<Renderer>(type, ParamView{}, pc);
  } catch (const PluginError& e) {
    c.root.fail("renderer", e.what());
  }
}

// Writes the EXR and PNG of one view under temporary names, then renames both.
void write_outputs(const RenderResult& r, const RenderSettings& s, double exposure, const fs::path& exr, const fs::path& png) {
  const fs::path tmp_exr = fs::path(exr).concat(".partial.exr"), tmp_png = fs::path(png).concat(".partial.png");
  try {
    SpectralChannels spectral;
    if (s.spectral_bins > 0) {
      spectral.bins = s.spectral_bins;
      spectral.lambda_min_nm = s.lambda_min_nm;
      spectral.lambda_max_nm = s.lambda_max_nm;
      spectral.values = r.spectral;
    }
    // The run's warnings (plumage/diagnostics.hpp: materials' own warnings included) travel with
    // the image.
    std::map<std::string, std::string> attributes;
    if (!diagnostics().empty()) attributes["plumage:warnings"] = diagnostics().summary();
    write_exr(r.rgb, tmp_exr, s.spectral_bins > 0 ? &spectral : nullptr, attributes);
    LinearImage scaled = r.rgb;
    for (RgbF& p : scaled.pixels()) p = {p.r * float(exposure), p.g * float(exposure), p.b * float(exposure)};
    write_png(to_display(scaled), tmp_png);
    fs::rename(tmp_exr, exr);
    fs::rename(tmp_png, png);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp_exr, ec);
    fs::remove(tmp_png, ec);
    throw;
  }
}

void run(AppContext& context, const Options& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  SceneConfig config = load_scene_config(o.scene);
  // Command-line overrides of the scene's render settings.
  RenderSettings& s = config.settings;
  if (o.spp > 0) s.samples_per_pixel = o.spp;
  if (o.seed) s.seed = *o.seed;
  if (o.threads > 0) s.threads = o.threads;
  if (!o.lod.empty()) s.lod = o.lod == "mean" ? LevelOfDetail::mean : o.lod == "instance" ? LevelOfDetail::instance : LevelOfDetail::automatic;
  if ((o.width > 0) != (o.height > 0)) throw UsageError("--width and --height go together");
  for (SceneView& v : config.views) {
    if (o.width > 0) v.camera.width = o.width, v.camera.height = o.height;
  }
  std::vector<const SceneView*> views;
  if (!o.view.empty()) {
    try {
      views.push_back(&find_view(config, o.view));
    } catch (const Error& e) {
      throw UsageError(e.what());
    }
  } else {
    for (const SceneView& v : config.views) views.push_back(&v);
  }
  // Everything that can fail on bad input fails before the expensive steps.
  std::unique_ptr<Renderer> renderer = create_renderer(config, context);
  std::optional<tbb::global_control> threads;
  if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(o.threads));

  SceneGeometryStats st;
  const auto g0 = std::chrono::steady_clock::now();
  std::vector<SceneMesh> meshes = build_scene_meshes(config, &st);
  const double geometry_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count();
  if (!context.quiet) {
    std::cerr << config.name << ": " << st.triangles << " triangles, " << st.feathers << " feather(s), " << st.barbs << " barbs, "
              << st.barbule_ids << " barbule ids (built in " << std::fixed << std::setprecision(2) << geometry_s << " s)\n";
  }
  if (o.check) {
    std::cout << "scene " << config.name << ": " << views.size() << " view(s), " << st.triangles << " triangles, " << st.feathers
              << " feathers, " << st.barbule_ids << " barbule ids\n";
    return;
  }

  MaterialStoreOptions store_options;
  store_options.directory = o.materials;
  store_options.allow_characterize = !o.no_characterize;
  store_options.preparation = context.preparation();  // --tables, for a material characterised here
  std::unique_ptr<Progress> characterising;
  if (!context.quiet) {
    store_options.status = [](std::string_view line) { std::cerr << line << "\n"; };
    store_options.progress = [&](std::size_t done, std::size_t total, std::string_view what) {
      if (done == 0) characterising = std::make_unique<Progress>(std::string(what), total, false);  // a run starts
      else if (characterising) characterising->advance(done);
    };
  }
  const MaterialStore store(context.registry(), store_options);
  for (std::size_t k = 0; k < config.materials.size(); ++k) {
    if (!config.feather_requests[k]) continue;
    const FeatherMaterialRequest& q = *config.feather_requests[k];
    const ResolvedMaterial r = store.resolve({q.file, q.species_config, q.variant, q.fidelity, q.where});
    FeatherBsdfOptions bsdf;
    bsdf.transmission_albedo = q.transmission_albedo;
    config.materials[k].feather = std::make_shared<const FeatherBsdf>(r.material, bsdf);
  }

  fs::create_directories(o.out);
  for (const SceneView* v : views) {
    Scene scene = make_scene(config, *v, views.size() == 1 ? std::move(meshes) : meshes);
    if (!context.quiet) {
      std::cerr << scene.name << ": " << scene.camera.width << " x " << scene.camera.height << ", " << s.samples_per_pixel
                << " spp, lod " << (s.lod == LevelOfDetail::mean ? "mean" : s.lod == LevelOfDetail::instance ? "instance" : "auto")
                << ", seed " << s.seed << "\n";
    }
    std::unique_ptr<Progress> progress;
    auto report = [&](std::size_t done, std::size_t total, std::string_view what) {
      if (!progress) progress = std::make_unique<Progress>(std::string(what), total, context.quiet);
      progress->advance(done);
    };
    const std::clock_t cpu0 = std::clock();
    const RenderResult result = renderer->render(scene, s, report);
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
    const fs::path exr = fs::path(o.out) / (scene.name + ".exr"), png = fs::path(o.out) / (scene.name + ".png");
    write_outputs(result, s, config.exposure, exr, png);
    std::cout << "wrote " << exr.string() << " and " << png.string() << " (" << scene.camera.width << " x " << scene.camera.height
              << ", " << s.samples_per_pixel << " spp, " << std::fixed << std::setprecision(1) << result.stats.seconds
              << " s render, " << cpu << " s CPU, " << std::setprecision(2) << result.stats.rays / std::max(1e-9, result.stats.seconds) / 1e6
              << " Mrays/s, mean-BRDF share " << std::setprecision(3) << result.stats.mean_lod_fraction << ")\n";
  }
  if (!context.quiet) {
    std::cerr << "total " << std::fixed << std::setprecision(1)
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count() << " s\n";
  }
}

}  // namespace

void add_render_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("render", "Render a scene (configs/scenes/*.yaml) to EXR + PNG with the renderer plug-in");
  cmd->add_option("scene", o->scene, "Scene YAML file")->required();
  cmd->add_option("--out", o->out, "Output folder (<scene>[-<view>].exr and .png)")->capture_default_str();
  cmd->add_option("--view", o->view, "Render only this view of the scene's `views:` (default: all)");
  cmd->add_option("--spp", o->spp, "Samples per pixel (default: the scene's render.spp)")->check(CLI::PositiveNumber);
  cmd->add_option("--width", o->width, "Image width in pixels (with --height)")->check(CLI::PositiveNumber);
  cmd->add_option("--height", o->height, "Image height in pixels (with --width)")->check(CLI::PositiveNumber);
  cmd->add_option("--lod", o->lod, "Level of detail: auto (mean BRDF where a pixel covers many barbules), mean, instance")
      ->check(CLI::IsMember({"auto", "mean", "instance"}));
  cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", o->seed, "Seed of the image's random numbers (default: the scene's render.seed)");
  cmd->add_option("--materials", o->materials, "Folder of cached feather materials (.plm)")->capture_default_str();
  cmd->add_flag("--no-characterize", o->no_characterize, "Fail instead of characterising a missing material");
  cmd->add_flag("--check", o->check, "Only validate the scene and build its geometry (prints counts)");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
