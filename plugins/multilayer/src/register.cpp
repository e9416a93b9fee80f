// Entry point of libplumage_multilayer.so.
//
// Provides:
//   local_reflection "multilayer"   planar stack reflection (no parameters)
#include "multilayer_reflection.hpp"
#include "plumage/plugin_export.hpp"

namespace {

void register_multilayer(plumage::Registrar& registrar) {
  using plumage::multilayer::MultilayerReflection;
  registrar.add<plumage::LocalReflection>(
      {.kind = "",
       .type = "multilayer",
       .version = "1.0.0",
       .summary = "planar multilayer under each surface point: Airy/scattering-matrix recursion, "
                  "complex r_s (E) and r_p (H), stable for thick absorbing stacks",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) {
        return std::make_unique<MultilayerReflection>();
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_multilayer)
