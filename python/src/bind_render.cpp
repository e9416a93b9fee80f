// Scenes and rendering from Python (issue 24): load_scene (`plumage render --check` / `plumage
// check` of a scene) and render (`plumage render`), calling plumage/render_job.hpp and
// material_store.hpp step by step as core/cli/cmd_render.cpp does.
#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <optional>

#include "plumage/atomic_file.hpp"
#include "plumage/config_check.hpp"
#include "plumage/exr.hpp"
#include "plumage/material_store.hpp"
#include "plumage/render_job.hpp"
#include "py_common.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

namespace fs = std::filesystem;

// A scene as `plumage render` reads it: the job made (scene checked, renderer created), nothing run.
struct LoadedScene {
  RegistryPtr registry;  // the renderer's plug-in code lives in it
  std::unique_ptr<RenderJob> job;
  std::string summary;  // the `plumage check` line
};

// One rendered view: the files (when asked for), the renderer's radiance and the run's warnings.
struct RenderOutput {
  RenderedView view;                  // with the renderer's RenderResult (the radiance viewed)
  std::vector<std::string> warnings;  // the run's warnings (the EXR's plumage:warnings), one a line
};

py::list vec3(const Vec3f& v) { return py::cast(std::vector<double>{v.x, v.y, v.z}); }

py::dict view_dict(const SceneView& v) {
  py::dict d;
  d["name"] = v.name;
  d["width"] = v.camera.width;
  d["height"] = v.camera.height;
  d["fov_deg"] = v.camera.vertical_fov_rad * 180.0 / 3.14159265358979323846;
  d["position_mm"] = vec3(v.camera.position_mm);
  d["look_at_mm"] = vec3(v.camera.look_at_mm);
  d["point_lights"] = v.point_lights.size();
  d["distant_lights"] = v.distant_lights.size();
  d["area_lights"] = v.area_lights.size();
  d["environment_radiance"] = v.environment.radiance;
  return d;
}

py::dict material_dict(const SceneConfig& c, std::size_t k) {
  const SceneMaterial& m = c.materials[k];
  py::dict d;
  d["name"] = m.name;
  d["kind"] = m.kind == SceneMaterial::Kind::feather ? "feather" : m.kind == SceneMaterial::Kind::diffuse ? "diffuse" : "dielectric";
  if (const auto& q = c.feather_requests[k]) {
    // An empty path would read as Path('.') in Python: None says "not given".
    auto path_or_none = [](const fs::path& p) { return p.empty() ? py::none() : py::cast(p); };
    d["species_config"] = path_or_none(q->species_config);
    d["variant"] = q->variant;
    d["fidelity"] = q->fidelity;
    d["file"] = path_or_none(q->file);
  }
  return d;
}

py::dict object_dict(const SceneConfig& c, const SceneObjectSpec& o) {
  py::dict d;
  d["name"] = o.name;
  d["kind"] = o.kind == SceneObjectSpec::Kind::feather ? "feather" : o.kind == SceneObjectSpec::Kind::assembly ? "assembly" : "plane";
  d["material"] = c.materials.at(o.material).name;
  d["seed"] = o.seed;
  return d;
}

// The arguments as the job's options (render_job_options): the renderer's own table checks spp,
// seed, lod and threads, naming plumage.render(<key>=...) as their source.
RenderJobOptions job_options(const std::string& view, int width, int height, std::optional<int> spp,
                             std::optional<std::uint64_t> seed, const std::string& lod, int threads) {
  RenderFlags f;
  f.view = view;
  f.width = width, f.height = height;
  if (spp) f.spp = *spp;
  f.seed = seed;
  f.lod = lod;
  if (threads != 0) f.threads = threads;
  return render_job_options(f, "plumage.render({key}=...)");
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (end > start) out.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

struct RenderArgs {
  fs::path scene_file;
  RenderJobOptions job;
  MaterialStoreOptions store;
  std::optional<fs::path> out;
};

// `plumage render` without its printing: job, geometry, materials, then each view. Runs without
// the GIL (the progress and status functions take it themselves).
std::vector<RenderOutput> run_render(const RenderArgs& a, const PluginRegistry& registry, const fs::path& out_dir,
                                     const Renderer::Progress& progress) {
  RenderJob job(a.scene_file, a.job, registry);
  job.build_geometry();
  const MaterialStore store(registry, a.store);
  job.resolve_materials([&store](const FeatherMaterialRequest& q) {
    const ResolvedMaterial r = store.resolve({q.file, q.species_config, q.variant, q.fidelity, q.where});
    FeatherBsdfOptions bsdf;
    bsdf.transmission_albedo = q.transmission_albedo;
    return std::make_shared<const FeatherBsdf>(r.material, bsdf);
  });
  std::vector<RenderOutput> outputs;
  for (std::size_t k = 0; k < job.views().size(); ++k) {
    RenderOutput o;
    // An empty out_dir (no `out`): nothing written, the image only in o.view.result.
    o.view = job.render_view(k, out_dir, progress);
    o.warnings = lines_of(o.view.warnings);
    outputs.push_back(std::move(o));
  }
  return outputs;
}

void bind_scene(py::module_& m) {
  py::class_<LoadedScene, std::shared_ptr<LoadedScene>>(m, "Scene", R"doc(
A scene config (configs/scenes/*.yaml) read and checked as `plumage render` does before any
work: the renderer created from its `renderer:` section, views resolved. Made by plumage.load_scene.)doc")
      .def_property_readonly("file", [](const LoadedScene& s) { return s.job->config().file; })
      .def_property_readonly("name", [](const LoadedScene& s) { return s.job->config().name; })
      .def_property_readonly("content_hash", [](const LoadedScene& s) { return s.job->config().content_hash; })
      .def_property_readonly("renderer", [](const LoadedScene& s) { return s.job->renderer().describe(); },
                             "The renderer's settings line (e.g. '16 spp, lod auto, seed 5').")
      .def_property_readonly("exposure", [](const LoadedScene& s) { return s.job->config().exposure; }, "render.exposure (PNG only).")
      .def_property_readonly("views", [](const LoadedScene& s) {
        py::list out;
        for (const SceneView* v : s.job->views()) out.append(view_dict(*v));
        return out;
      }, "One dict per view: name, width, height (pixels), fov_deg, position_mm, look_at_mm, light counts.")
      .def_property_readonly("materials", [](const LoadedScene& s) {
        py::list out;
        for (std::size_t k = 0; k < s.job->config().materials.size(); ++k) out.append(material_dict(s.job->config(), k));
        return out;
      }, "One dict per material: name, kind (feather | diffuse | dielectric); feather ones also "
         "species_config, variant, fidelity, file (a path, or None when not given).")
      .def_property_readonly("objects", [](const LoadedScene& s) {
        py::list out;
        for (const SceneObjectSpec& o : s.job->config().objects) out.append(object_dict(s.job->config(), o));
        return out;
      }, "One dict per object: name, kind (feather | assembly | plane), material, seed.")
      .def_property_readonly("summary", [](const LoadedScene& s) { return s.summary; }, "The summary line of `plumage check FILE`.")
      .def("__repr__", [](const LoadedScene& s) {
        return "<plumage.Scene " + s.job->config().name + ", " + std::to_string(s.job->views().size()) + " view(s)>";
      });

  m.def("load_scene",
        [](const fs::path& file, const py::object& registry) {
          auto out = std::make_shared<LoadedScene>();
          out->registry = registry_or_default(registry);
          py::gil_scoped_release release;
          out->job = std::make_unique<RenderJob>(file, RenderJobOptions{}, *out->registry->registry);
          out->summary = check_config_file(file, *out->registry->registry).summary;
          return out;
        },
        py::arg("file"), py::arg("registry") = py::none(),
        "Read a scene and create its renderer, running nothing. Raises ConfigError (file, line, "
        "column, field) for a bad key or value, MemoryBudgetError for a view too large.");
}

void bind_rendered_view(py::module_& m) {
  py::class_<RenderOutput, std::shared_ptr<RenderOutput>>(m, "RenderedView", "One view rendered by plumage.render.")
      .def_property_readonly("name", [](const RenderOutput& o) { return o.view.name; }, "<scene>[-<view>]")
      .def_property_readonly("width", [](const RenderOutput& o) { return o.view.width; })
      .def_property_readonly("height", [](const RenderOutput& o) { return o.view.height; })
      .def_property_readonly("radiance", [](py::object self) {
        const LinearImage& rgb = self.cast<const RenderOutput&>().view.result.rgb;
        const auto h = static_cast<py::ssize_t>(rgb.height()), w = static_cast<py::ssize_t>(rgb.width());
        const py::ssize_t f = sizeof(float);
        static_assert(sizeof(RgbF) == 3 * sizeof(float), "RgbF must be three packed floats");
        py::array out(py::dtype::of<float>(), {h, w, py::ssize_t{3}}, {w * 3 * f, 3 * f, f},
                      reinterpret_cast<const float*>(rgb.pixels().data()), self);
        py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
        return out;
      }, "Linear sRGB radiance, float32 of shape (height, width, 3), the renderer's own buffer (the "
         "EXR's pixels bit for bit); a read-only zero-copy view.")
      .def_property_readonly("exr", [](const RenderOutput& o) { return o.view.exr.empty() ? py::none() : py::cast(o.view.exr); },
                             "The EXR written (None when render() had no `out`).")
      .def_property_readonly("png", [](const RenderOutput& o) { return o.view.png.empty() ? py::none() : py::cast(o.view.png); },
                             "The PNG preview written (None when render() had no `out`).")
      .def_property_readonly("stats", [](const RenderOutput& o) {
        py::dict d;
        d["seconds"] = o.view.stats.seconds;
        d["camera_paths"] = o.view.stats.camera_paths;
        d["rays"] = o.view.stats.rays;
        d["mean_lod_fraction"] = o.view.stats.mean_lod_fraction;
        d["cpu_s"] = o.view.cpu_s;
        return d;
      }, "seconds (wall), camera_paths (width x height x spp), rays, mean_lod_fraction, cpu_s.")
      .def_property_readonly("warnings", [](const RenderOutput& o) { return o.warnings; },
                             "The run's warnings as stored in the EXR (plumage:warnings), one per line.")
      .def_property_readonly("warning_shares", [](const RenderOutput& o) {
        py::list out;
        for (const WarningShare& w : o.view.warning_shares) {
          py::dict d;
          d["material"] = w.material, d["code"] = w.code, d["directions"] = w.directions;
          d["share"] = w.share(), d["evaluations_in"] = w.evaluations_in, d["evaluations"] = w.evaluations;
          d["above_threshold"] = w.evaluations > 0 && w.share() >= o.view.warning_share_threshold;
          out.append(d);
        }
        return out;
      }, "Per feather material and warning code: the share of its BSDF evaluations reaching where "
         "the warning was raised (dicts), against render.warning_share.")
      .def("__repr__", [](const RenderOutput& o) {
        return "<plumage.RenderedView " + o.view.name + " " + std::to_string(o.view.width) + " x " + std::to_string(o.view.height) + ">";
      });
}

}  // namespace

void bind_render(py::module_& m) {
  bind_scene(m);
  bind_rendered_view(m);

  m.def("read_exr",
        [](const fs::path& file) {
          LinearImage rgb;
          std::map<std::string, std::string> attributes;
          {
            py::gil_scoped_release release;
            rgb = read_exr_rgb(file);
            attributes = read_exr_string_attributes(file);
          }
          py::array_t<float> out({static_cast<py::ssize_t>(rgb.height()), static_cast<py::ssize_t>(rgb.width()), py::ssize_t{3}});
          std::memcpy(out.mutable_data(), rgb.pixels().data(), rgb.pixels().size() * sizeof(RgbF));
          return py::make_tuple(out, attributes);
        },
        py::arg("file"),
        "Read an EXR plumage wrote: (radiance, attributes) — float32 (height, width, 3) linear sRGB "
        "and the string attributes (plumage:warnings...).");

  m.def("render",
        [](const fs::path& scene_file, const py::object& view, int width, int height, std::optional<int> spp,
           std::optional<std::uint64_t> seed, const py::object& lod, int threads, const fs::path& materials,
           bool allow_characterize, const std::string& tables, const py::object& progress, const py::object& out,
           const py::object& registry) {
          RenderArgs a;
          a.scene_file = scene_file;
          a.job = job_options(view.is_none() ? "" : view.cast<std::string>(), width, height, spp, seed,
                              lod.is_none() ? "" : lod.cast<std::string>(), threads);
          a.store.directory = materials;
          a.store.allow_characterize = allow_characterize;
          a.store.preparation.tables = preparation_from(tables, py::none()).tables;
          const ProgressFn report = progress_from_python(progress);
          a.store.progress = report;
          a.store.preparation.progress = report;
          if (!out.is_none()) {
            a.out = out.cast<fs::path>();
            check_output_directory(*a.out, "out");
          }
          const RegistryPtr r = registry_or_default(registry);
          const fs::path out_dir = a.out ? *a.out : fs::path{};
          std::vector<RenderOutput> outputs;
          {
            py::gil_scoped_release release;
            outputs = run_render(a, *r->registry, out_dir, report);
          }
          py::list result;
          for (RenderOutput& o : outputs) result.append(std::make_shared<RenderOutput>(std::move(o)));
          return result;
        },
        py::arg("scene_file"), py::arg("view") = py::none(), py::arg("width") = 0, py::arg("height") = 0,
        py::arg("spp") = py::none(), py::arg("seed") = py::none(), py::arg("lod") = py::none(), py::arg("threads") = 0,
        py::arg("materials") = "build/materials", py::arg("allow_characterize") = true, py::arg("tables") = "build",
        py::arg("progress") = py::none(), py::arg("out") = py::none(), py::arg("registry") = py::none(),
        R"doc(`plumage render SCENE`: render every view of a scene (or only `view`) and return a list of
plumage.RenderedView (radiance as a (height, width, 3) float32 array, stats, warnings).

width/height (pixels, together) replace render.resolution; spp, seed, lod (auto | mean |
instance) and threads (0: all cores) are the renderer's own settings, read by its parameter table
as the command's flags are (a bad value is a ConfigError naming `plumage.render(<key>=...)`).
Feather materials come from the material store `materials` (a folder of .plm), characterised when
missing unless allow_characterize=False (then ConfigError naming the command); `tables` is
`plumage --tables` (build | preview | never) for such a characterisation. progress(done, total,
what) reports characterisation and rendering; an exception it raises, or Ctrl-C, stops the work.
With `out` (a folder) each view's <scene>[-<view>].exr and .png are written there exactly as the
command writes them; without it nothing is kept. Raises ConfigError for a bad scene,
OutputPathError for an `out` that is not a folder or an image path that is a symlink.)doc");
}

}  // namespace plumage::python
