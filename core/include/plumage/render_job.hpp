// The render pipeline of `plumage render` as a library (issue 22): a scene file, its renderer and
// its views, step by step, so that a program (or `plumage render --check`) can stop after any
// step and report between them.
//
//   RenderJob job(file, options, registry);       // scene read and checked, renderer created
//   job.build_geometry();                           // procedural feathers → meshes
//   job.resolve_materials(resolver);                // every `type: feather` material
//   for (k < job.views().size()) job.render_view(k, out_dir, progress);  // EXR + PNG per view
//
// Everything bad input can break fails in the constructor, before the expensive steps. The
// renderer is created from the scene's `renderer:` section with the options' settings written
// into it (ConfigDocument::derive), so a command-line override goes through the renderer's own
// parameter table exactly like a value in the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plumage/feather_bsdf.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/renderer.hpp"
#include "plumage/scene_config.hpp"

namespace plumage {

struct RenderJobOptions {
  std::string view;           // render only this view of the scene's `views:` (empty: every view)
  int width = 0, height = 0;  // both > 0: every view's image size instead of render.resolution
  // Keys of the renderer's own section, e.g. {"spp", "4", "command line --spp"}: written over the
  // scene's `renderer:` and read by the renderer's table (an unknown key or a bad value is a
  // ConfigError naming the key and the setting's source).
  struct RendererSetting {
    std::string key, yaml;
    std::string source = "override";
  };
  std::vector<RendererSetting> renderer_settings;
  std::size_t max_threads = 0;  // > 0: at most this many oneTBB threads in every step of the job
};

// The FeatherBsdf of a scene's `type: feather` material: looked up in a material store,
// characterised, or read from the named .plm. Throwing stops the job.
// `plumage render`'s flags (plumage.render's arguments) as job options. spp, seed, lod and
// threads become keys of the renderer's section (its parameter table checks them), each with
// the source `source` with "{key}" replaced by the key ("command line --{key}"); threads also
// caps the job's oneTBB threads. width and height go together (ConfigError otherwise).
struct RenderFlags {
  std::string view;
  int width = 0, height = 0;  // both 0: the scene's render.resolution
  std::optional<long long> spp, threads;
  std::optional<std::uint64_t> seed;
  std::string lod;  // empty: the scene's
};
RenderJobOptions render_job_options(const RenderFlags& flags, const std::string& source);

using FeatherResolver = std::function<std::shared_ptr<const FeatherBsdf>(const FeatherMaterialRequest&)>;

struct RenderedView {
  std::string name;  // <scene>[-<view>]
  std::filesystem::path exr, png;
  int width = 0, height = 0;
  RenderStats stats;
  double cpu_s = 0.0;  // process CPU time of the render
  // Per feather material and per-direction warning code: how much of the paths reached where it
  // was raised (renderer.hpp); those at or above the scene's render.warning_share were raised as
  // material.warnings before the EXR was written (its plumage:warnings attribute).
  std::vector<WarningShare> warning_shares;
  double warning_share_threshold = 0.01;
  // The renderer's output itself (radiance, spectral channels), what the files hold; the Python
  // package hands it out as arrays without reading the EXR back.
  RenderResult result;
  // The run's warnings when the view was done (diagnostics summary, the EXR's plumage:warnings).
  std::string warnings;
};

// The image buffers of one view (memory_budget.hpp); RenderJob refuses views that would not fit
// (MemoryBudgetError, exit status 2) when it is made, before any geometry or material.
MemoryEstimate estimate_view_memory(const SceneView& view);

class RenderJob {
 public:
  RenderJob(const std::filesystem::path& scene_file, RenderJobOptions options, const PluginRegistry& registry);
  ~RenderJob();
  RenderJob(RenderJob&&) noexcept;
  RenderJob& operator=(RenderJob&&) noexcept;

  const SceneConfig& config() const;
  // The views to render (the one asked for, or all), in file order.
  const std::vector<const SceneView*>& views() const;
  const Renderer& renderer() const;

  // Builds every object's meshes (deterministic; Error naming the object over a limit).
  const SceneGeometryStats& build_geometry();
  double geometry_seconds() const;
  // Resolves every feather material through `resolve`.
  void resolve_materials(const FeatherResolver& resolve);
  // Renders views()[k] and writes <out_dir>/<name>.exr and .png (write_render_images); an empty
  // out_dir writes nothing (the image is in RenderedView::result). With a single view the meshes
  // move into its scene, so each view renders once.
  RenderedView render_view(std::size_t k, const std::filesystem::path& out_dir, const Renderer::Progress& progress);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The EXR (radiance, spectral channels when the result has them, the run's warnings from
// plumage/diagnostics.hpp as the string attribute "plumage:warnings") and the PNG preview
// (radiance × png_exposure, sRGB) of one render. Both are written under temporary names and
// renamed together: they appear together or not at all.
void write_render_images(const RenderResult& result, double png_exposure, const std::filesystem::path& exr,
                         const std::filesystem::path& png);

}  // namespace plumage
