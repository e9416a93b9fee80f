// Entry point of libplumage_multilayer.so.
//
// Provides:
//   local_reflection "multilayer"         planar stack reflection (no parameters)
//   structure_generator "layered_barbule" procedural barbules of types 1–4 (layered_barbule.cpp)
//   accuracy_ladder "multilayer"          periodic stacks vs their closed form (issue 9)
#include "layered_barbule.hpp"
#include "multilayer_ladder.hpp"
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
  using plumage::multilayer::LayeredBarbule;
  registrar.add<plumage::StructureGenerator>(
      {.kind = "",
       .type = "layered_barbule",
       .version = "1.0.0",
       .summary = "procedural barbule cross sections with layered interiors (types 1-4): granules "
                  "under an air gap, melanosome rows, hollow platelets, conformal films",
       .params = LayeredBarbule::param_table()},
      [](const plumage::ParamView& params, const plumage::PluginContext&) {
        return std::make_unique<LayeredBarbule>(params);
      });
  registrar.add<plumage::AccuracyLadder>(
      {.kind = "",
       .type = "multilayer",
       .version = "1.0.0",
       .summary = "accuracy ladder: Bragg stacks of 1-64 periods against the closed-form periodic "
                  "stack (Abeles matrix, Chebyshev power)",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) {
        return std::make_unique<plumage::multilayer::MultilayerLadder>();
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_multilayer)
