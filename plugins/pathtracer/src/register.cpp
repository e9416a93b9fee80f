// Entry point of libplumage_pathtracer.so.
//
// Provides:
//   renderer "pathtracer"  hero-wavelength spectral path tracing on Embree 3 (NOTES.md)
//   accuracy_ladder "pathtracer"  spp ladder against a converged render (ladder/, issue 9)
#include "pathtracer.hpp"
#include "plumage/accuracy_ladder.hpp"
#include "plumage/plugin_export.hpp"

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
  registrar.add<plumage::Renderer>(
      {.kind = "",
       .type = "pathtracer",
       .version = "1.0.0",
       .summary = "spectral path tracer (Embree 3, hero wavelengths, NEE + MIS, feather/diffuse/dielectric "
                  "materials, mean/instance BRDF level of detail, oneTBB tiles); settings come from RenderSettings",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) {
        return std::make_unique<plumage::pathtracer::PathTracer>();
      });
  registrar.add<plumage::AccuracyLadder>(
      {.kind = "",
       .type = "pathtracer",
       .version = "1.0.0",
       .summary = "accuracy ladder: 1-1024 samples per pixel against a converged render (independent seed)",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) { return std::make_unique<RenderLadder>(); });
}

}  // namespace

PLUMAGE_PLUGIN(register_pathtracer)
