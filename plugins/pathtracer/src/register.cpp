// Entry point of libplumage_pathtracer.so.
//
// Provides:
//   renderer "pathtracer"  hero-wavelength spectral path tracing on Embree 3 (NOTES.md); its
//                          settings (settings.hpp) from the scene's `renderer:` section
//   accuracy_ladder "pathtracer"  spp ladder against a converged render (ladder/, issue 9)
//   benchmark "render"  one feather against Embree's raw traversal rate (bench/, `plumage bench render`)
#include "pathtracer.hpp"
#include "plumage/accuracy_ladder.hpp"
#include "plumage/plugin_export.hpp"
#include "render_bench.hpp"

namespace plumage::pathtracer {
std::vector<LadderPoint> run_render_ladder(const AccuracyLadder::Options& options);  // ladder/render_ladder.cpp
}

namespace {

class RenderLadder final : public plumage::AccuracyLadder {
 public:
  std::vector<plumage::LadderPoint> run(const Options& options) const override {
    return plumage::pathtracer::run_render_ladder(options);
  }
};

void register_pathtracer(plumage::Registrar& registrar) {
  namespace pt = plumage::pathtracer;
  registrar.add<plumage::Renderer>(
      {.type = "pathtracer",
       .version = "1.1.0",
       .summary = "spectral path tracer (Embree 3, hero wavelengths, NEE + MIS, feather/diffuse/dielectric "
                  "materials, mean/instance BRDF level of detail, oneTBB tiles)",
       .params = pt::settings_table().specs()},
      [](const plumage::ParamView& p, const plumage::PluginContext&) {
        return std::make_unique<pt::PathTracer>(pt::settings_table().read(p));
      });
  registrar.add<plumage::AccuracyLadder>(
      {.type = "pathtracer",
       .version = "1.0.0",
       .summary = "accuracy ladder: 1-1024 samples per pixel against a converged render (independent seed)",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) { return std::make_unique<RenderLadder>(); });
  registrar.add<plumage::Benchmark>(
      {.type = "render",
       .version = "1.0.0",
       .summary = "path tracer on a single feather: time, rays/s vs Embree's raw traversal (docs/benchmarks.md \"render\")",
       .params = pt::render_bench_table().specs()},
      [](const plumage::ParamView& p, const plumage::PluginContext&) { return pt::make_render_benchmark(p); });
}

}  // namespace

PLUMAGE_PLUGIN(register_pathtracer)
