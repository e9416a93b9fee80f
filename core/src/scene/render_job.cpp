// The render pipeline (render_job.hpp): scene → renderer from its own section → meshes →
// materials → one Scene per view → EXR + PNG.
#include "plumage/atomic_file.hpp"
#include "plumage/render_job.hpp"

#include "plumage/memory_budget.hpp"

#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <optional>

#include "plumage/config_document.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

std::string yaml_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// The scene's `renderer:` (a type name, a map with its settings, or absent: pathtracer) with the
// job's settings written into it, created through the registry: the renderer's table reads the
// file's keys and the overrides alike, and refuses keys it does not declare.
std::unique_ptr<Renderer> create_renderer(const SceneConfig& c,
                                          const std::vector<RenderJobOptions::RendererSetting>& settings,
                                          const PluginRegistry& registry) {
  std::vector<ConfigDocument::Override> overrides;
  const bool is_map = c.has_renderer_section && c.root.node("renderer").is_map();
  const bool named = c.has_renderer_section && !is_map;
  const std::string scene = c.file.string();
  if (!is_map) {
    const std::string type = named ? c.root.text("renderer") : std::string("pathtracer");
    overrides.push_back({"renderer", "{type: " + yaml_quoted(type) + "}", true, scene});
  } else if (!c.root.child("renderer").has("type")) {
    overrides.push_back({"renderer.type", "pathtracer", true, scene + " (default renderer)"});
  }
  for (const auto& s : settings) overrides.push_back({"renderer." + s.key, s.yaml, true, s.source});
  const ConfigDocument derived = ConfigDocument::derive(c.root, overrides, c.file.parent_path(), c.file.string());
  try {
    return registry.create<Renderer>(derived.root().child("renderer"), "type", registry.context(c.file.parent_path()));
  } catch (const ConfigError& e) {
    // `renderer: <name>` with an unknown name: point at the scene's line, not the derived map.
    if (named && e.field() == "renderer.type") c.root.fail("renderer", e.message());
    throw;
  }
}

// At most `max_threads` oneTBB threads while it lives (0: no cap).
class ThreadCap {
 public:
  explicit ThreadCap(std::size_t max_threads) {
    if (max_threads > 0) cap_.emplace(tbb::global_control::max_allowed_parallelism, max_threads);
  }

 private:
  std::optional<tbb::global_control> cap_;
};

// A material's per-direction warning matters to this image only if its paths reach those
// directions with weight (issue 23): raised at or above the threshold, with the number.
void warn_reached_directions(const RenderedView& view) {
  for (const WarningShare& w : view.warning_shares) {
    if (w.evaluations == 0 || w.share() < view.warning_share_threshold) continue;
    char share[96];
    std::snprintf(share, sizeof share, "%.1f %% (threshold render.warning_share = %.1f %%)", 100.0 * w.share(),
                  100.0 * view.warning_share_threshold);
    warn("material.warnings", view.name + ": material '" + w.material + "': " + share +
                                  " of its throughput-weighted feather BSDF evaluations (" +
                                  std::to_string(w.evaluations_in) + " of " + std::to_string(w.evaluations) +
                                  ") have their incident direction where its characterisation raised " + w.code +
                                  " (" + w.directions + ")");
  }
}

}  // namespace

struct RenderJob::State {
  RenderJobOptions options;
  SceneConfig config;
  std::unique_ptr<Renderer> renderer;
  std::vector<const SceneView*> views;
  std::vector<SceneMesh> meshes;
  SceneGeometryStats stats;
  double geometry_s = 0.0;
  bool built = false, meshes_moved = false;
};

RenderJobOptions render_job_options(const RenderFlags& f, const std::string& source) {
  auto source_of = [&source](const std::string& key) {
    std::string out = source;
    if (const auto at = out.find("{key}"); at != std::string::npos) out.replace(at, 5, key);
    return out;
  };
  if ((f.width != 0) != (f.height != 0) || f.width < 0 || f.height < 0)
    throw ConfigError(SourceMark{source_of("width"), 0, 0}, "", "width and height go together, both > 0 (or both 0: the scene's)");
  RenderJobOptions j;
  j.view = f.view;
  j.width = f.width, j.height = f.height;
  auto set = [&](const std::string& key, const std::string& value) { j.renderer_settings.push_back({key, value, source_of(key)}); };
  if (f.spp) set("spp", std::to_string(*f.spp));
  if (f.seed) set("seed", std::to_string(*f.seed));
  if (!f.lod.empty()) set("lod", f.lod);
  if (f.threads) {
    set("threads", std::to_string(*f.threads));
    if (*f.threads > 0) j.max_threads = static_cast<std::size_t>(*f.threads);
  }
  return j;
}

RenderJob::RenderJob(const fs::path& scene_file, RenderJobOptions options, const PluginRegistry& registry)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.options = std::move(options);
  s.config = load_scene_config(scene_file);
  if (s.options.width > 0 && s.options.height > 0) {
    for (SceneView& v : s.config.views) v.camera.width = s.options.width, v.camera.height = s.options.height;
  }
  if (!s.options.view.empty()) {
    s.views.push_back(&find_view(s.config, s.options.view));
  } else {
    for (const SceneView& v : s.config.views) s.views.push_back(&v);
  }
  s.renderer = create_renderer(s.config, s.options.renderer_settings, registry);
  for (const SceneView* v : s.views) check_memory(estimate_view_memory(*v));
}

// Memory budget (issue 23, plumage/memory_budget.hpp): a view's image buffers — the renderer's
// accumulation (double RGB and sample counts), the linear image (float RGB), the display image,
// the EXR and PNG rows and up to 64 spectral channels of float — about 320 bytes per pixel, before
// anything is built. `--width 100000 --height 100000` (1e10 pixels) is refused, not std::bad_alloc.
MemoryEstimate estimate_view_memory(const SceneView& view) {
  const double pixels = static_cast<double>(view.camera.width) * static_cast<double>(view.camera.height);
  MemoryEstimate e;
  e.job = "render of view '" + view.name + "' at " + std::to_string(view.camera.width) + " x " +
          std::to_string(view.camera.height) + " pixels";
  e.add("image buffers (RGB, spectral channels, EXR/PNG rows)", 320.0 * pixels);
  e.lower_with = {"--width/--height or the scene's render.resolution"};
  return e;
}

RenderJob::~RenderJob() = default;
RenderJob::RenderJob(RenderJob&&) noexcept = default;
RenderJob& RenderJob::operator=(RenderJob&&) noexcept = default;

const SceneConfig& RenderJob::config() const { return state_->config; }
const std::vector<const SceneView*>& RenderJob::views() const { return state_->views; }
const Renderer& RenderJob::renderer() const { return *state_->renderer; }
double RenderJob::geometry_seconds() const { return state_->geometry_s; }

const SceneGeometryStats& RenderJob::build_geometry() {
  State& s = *state_;
  if (!s.built) {
    const ThreadCap cap(s.options.max_threads);
    const auto t0 = std::chrono::steady_clock::now();
    s.meshes = build_scene_meshes(s.config, &s.stats);
    s.geometry_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    s.built = true;
  }
  return s.stats;
}

void RenderJob::resolve_materials(const FeatherResolver& resolve) {
  State& s = *state_;
  const ThreadCap cap(s.options.max_threads);
  for (std::size_t k = 0; k < s.config.materials.size(); ++k) {
    if (s.config.feather_requests[k]) s.config.materials[k].feather = resolve(*s.config.feather_requests[k]);
  }
}

RenderedView RenderJob::render_view(std::size_t k, const fs::path& out_dir, const Renderer::Progress& progress) {
  State& s = *state_;
  if (!s.built) throw Error("render job: build_geometry() must run before render_view()");
  if (s.meshes_moved) throw Error("render job: the scene's only view was rendered already");
  const bool last_use = s.views.size() == 1;
  Scene scene = make_scene(s.config, *s.views.at(k), last_use ? std::move(s.meshes) : s.meshes);
  s.meshes_moved = last_use;
  const ThreadCap cap(s.options.max_threads);
  const bool write = !out_dir.empty();
  // Output paths before the render, which may take hours.
  if (write) {
    check_output_directory(out_dir);
    check_output_path(out_dir / (scene.name + ".exr"));
    check_output_path(out_dir / (scene.name + ".png"));
  }
  const std::clock_t cpu0 = std::clock();
  RenderedView out;
  out.result = s.renderer->render(scene, progress);
  out.cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  out.name = scene.name;
  out.width = scene.camera.width, out.height = scene.camera.height;
  out.stats = out.result.stats;
  out.warning_shares = out.result.warning_shares;
  out.warning_share_threshold = s.config.warning_share;
  warn_reached_directions(out);
  out.warnings = diagnostics().summary();
  if (write) {
    out.exr = out_dir / (scene.name + ".exr");
    out.png = out_dir / (scene.name + ".png");
    create_output_directory(out_dir);
    write_render_images(out.result, s.config.exposure, out.exr, out.png);
  }
  return out;
}

}  // namespace plumage
