// Entry point of libplumage_pathtracer.so.
//
// Provides:
//   renderer "pathtracer"  hero-wavelength spectral path tracing on Embree 3 (NOTES.md)
#include "pathtracer.hpp"
#include "plumage/plugin_export.hpp"

namespace {

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
}

}  // namespace

PLUMAGE_PLUGIN(register_pathtracer)
