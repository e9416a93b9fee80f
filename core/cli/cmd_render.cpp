// `plumage render SCENE.yaml [--out DIR] [--view NAME] [--spp N] [--width W --height H]
// [--lod auto|mean|instance] [--threads N] [--seed N] [--materials DIR] [--no-characterize]
// [--check]`: the render pipeline of plumage/render_job.hpp (scene, renderer, feathers, materials,
// one EXR + PNG per view, <out>/<scene>[-<view>].exr and .png). --spp, --seed, --lod and
// --threads are settings of the renderer: they are written into the scene's `renderer:` section
// and read by the renderer's own parameter table.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "plumage/material_store.hpp"
#include "plumage/render_job.hpp"
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

RenderJobOptions job_options(const Options& o) {
  RenderFlags f;
  f.view = o.view;
  f.width = o.width, f.height = o.height;
  if (o.spp > 0) f.spp = o.spp;  // 0: the scene's
  f.seed = o.seed;
  f.lod = o.lod;
  if (o.threads != 0) f.threads = o.threads;
  return render_job_options(f, "command line --{key}");
}

// Feather materials: the library's material store (plumage/material_store.hpp) finds, validates
// or characterises them; a production request served at preview is a warning in the image.
struct MaterialResolver {
  std::unique_ptr<Progress> characterising;
  std::unique_ptr<MaterialStore> store;
};

FeatherResolver material_resolver(AppContext& context, const Options& o, MaterialResolver& state) {
  MaterialStoreOptions store_options;
  store_options.directory = o.materials;
  store_options.allow_characterize = !o.no_characterize;
  store_options.preparation = context.preparation();  // --tables, for a material characterised here
  if (!context.quiet) {
    store_options.status = [](std::string_view line) { std::cerr << line << "\n"; };
    store_options.progress = [&state](std::size_t done, std::size_t total, std::string_view what) {
      if (done == 0) state.characterising = std::make_unique<Progress>(std::string(what), total, false);  // a run starts
      else if (state.characterising) state.characterising->advance(done);
    };
  }
  state.store = std::make_unique<MaterialStore>(context.registry(), store_options);
  return [&state](const FeatherMaterialRequest& q) {
    const ResolvedMaterial r = state.store->resolve({q.file, q.species_config, q.variant, q.fidelity, q.where});
    FeatherBsdfOptions bsdf;
    bsdf.transmission_albedo = q.transmission_albedo;
    return std::make_shared<const FeatherBsdf>(r.material, bsdf);
  };
}

void print_written(const RenderedView& v) {
  const RenderStats& s = v.stats;
  const std::uint64_t pixels = static_cast<std::uint64_t>(v.width) * static_cast<std::uint64_t>(v.height);
  std::cout << "wrote " << v.exr.string() << " and " << v.png.string() << " (" << v.width << " x " << v.height << ", "
            << (pixels ? s.camera_paths / pixels : 0) << " spp, " << std::fixed << std::setprecision(1) << s.seconds
            << " s render, " << v.cpu_s << " s CPU, " << std::setprecision(2) << s.rays / std::max(1e-9, s.seconds) / 1e6
            << " Mrays/s, mean-BRDF share " << std::setprecision(3) << s.mean_lod_fraction << ")\n";
  // Whether the paths reach where a material's characterisation raised a per-direction warning.
  for (const WarningShare& w : v.warning_shares) {
    std::cout << "  material '" << w.material << "': " << std::setprecision(2) << 100.0 * w.share()
              << " % of its throughput-weighted feather BSDF evaluations (" << w.evaluations_in << " of " << w.evaluations
              << ") reach where " << w.code << " was raised (" << w.directions << "): "
              << (w.evaluations > 0 && w.share() >= v.warning_share_threshold ? "at or above" : "below")
              << " render.warning_share = " << 100.0 * v.warning_share_threshold << " %\n";
  }
}

void run(AppContext& context, const Options& o) {
  // An empty folder tells render_view to write nothing (the library's in-memory render).
  if (o.out.empty()) throw UsageError("--out: give the folder to write the images to");
  check_output_folder_flag("--out", o.out);
  const auto wall0 = std::chrono::steady_clock::now();
  RenderJob job(o.scene, job_options(o), context.registry());
  const SceneConfig& config = job.config();
  const SceneGeometryStats& st = job.build_geometry();
  if (!context.quiet) {
    std::cerr << config.name << ": " << st.triangles << " triangles, " << st.feathers << " feather(s), " << st.barbs << " barbs, "
              << st.barbule_ids << " barbule ids (built in " << std::fixed << std::setprecision(2) << job.geometry_seconds()
              << " s)\n";
  }
  if (o.check) {
    std::cout << "scene " << config.name << ": " << job.views().size() << " view(s), " << st.triangles << " triangles, "
              << st.feathers << " feathers, " << st.barbule_ids << " barbule ids\n";
    return;
  }
  MaterialResolver materials;
  job.resolve_materials(material_resolver(context, o, materials));
  for (std::size_t k = 0; k < job.views().size(); ++k) {
    const SceneView& view = *job.views()[k];
    if (!context.quiet) {
      std::cerr << (view.name.empty() ? config.name : config.name + "-" + view.name) << ": " << view.camera.width << " x "
                << view.camera.height << ", " << job.renderer().describe() << "\n";
    }
    std::unique_ptr<Progress> progress;
    auto report = [&](std::size_t done, std::size_t total, std::string_view what) {
      if (!progress) progress = std::make_unique<Progress>(std::string(what), total, context.quiet);
      progress->advance(done);
    };
    print_written(job.render_view(k, o.out, report));
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
  cmd->add_option("--spp", o->spp, "Samples per pixel (the renderer's `spp`)")->check(CLI::PositiveNumber);
  cmd->add_option("--width", o->width, "Image width in pixels (with --height)")->check(CLI::PositiveNumber);
  cmd->add_option("--height", o->height, "Image height in pixels (with --width)")->check(CLI::PositiveNumber);
  cmd->add_option("--lod", o->lod, "Level of detail (the renderer's `lod`): auto (mean BRDF where a pixel covers many barbules), mean, instance")
      ->check(CLI::IsMember({"auto", "mean", "instance"}));
  cmd->add_option("--threads", o->threads, "Worker threads (default: all cores; also the renderer's `threads`)")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", o->seed, "Seed of the image's random numbers (the renderer's `seed`)");
  cmd->add_option("--materials", o->materials, "Folder of cached feather materials (.plm)")->capture_default_str();
  cmd->add_flag("--no-characterize", o->no_characterize, "Fail instead of characterising a missing material");
  cmd->add_flag("--check", o->check, "Only validate the scene and build its geometry (prints counts)");
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
