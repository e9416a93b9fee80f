// Entry point of libplumage_multilayer.so.
//
// Provides:
//   local_reflection "multilayer"         planar stack reflection (no parameters: the stack comes
//                                         with each request)
//   structure_generator "layered_barbule" procedural barbules of types 1–4 (layered_barbule.cpp)
//   accuracy_ladder "multilayer"          periodic stacks vs their closed form (issue 9; no parameters)
//   benchmark "multilayer"                time per (point, wavelength) (multilayer_benchmark.cpp)
#include "layered_barbule.hpp"
#include "multilayer_benchmark.hpp"
#include "multilayer_ladder.hpp"
#include "multilayer_reflection.hpp"
#include "plumage/plugin_export.hpp"

namespace {

void register_multilayer(plumage::Registrar& registrar) {
  using namespace plumage::multilayer;
  registrar.add<plumage::LocalReflection>(
      {.type = "multilayer",
       .version = "1.0.0",
       .summary = "planar multilayer under each surface point: Airy/scattering-matrix recursion, "
                  "complex r_s (E) and r_p (H), stable for thick absorbing stacks",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) { return std::make_unique<MultilayerReflection>(); });
  registrar.add<plumage::StructureGenerator>(
      {.type = "layered_barbule",
       .version = "1.0.0",
       .summary = "procedural barbule cross sections with layered interiors (types 1-4): granules "
                  "under an air gap, melanosome rows, hollow platelets, conformal films",
       .params = layered_table().specs()},
      [](const plumage::ParamView& params, const plumage::PluginContext&) {
        return std::make_unique<LayeredBarbule>(params);
      });
  registrar.add<plumage::AccuracyLadder>(
      {.type = "multilayer",
       .version = "1.0.0",
       .summary = "accuracy ladder: Bragg stacks of 1-64 periods against the closed-form periodic "
                  "stack (Abeles matrix, Chebyshev power)",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) { return std::make_unique<MultilayerLadder>(); });
  registrar.add<plumage::Benchmark>(
      {.type = "multilayer",
       .version = "1.0.0",
       .summary = "multilayer reflection: time per (surface point, wavelength) through the batch API, one thread",
       .params = multilayer_bench_table().specs()},
      [](const plumage::ParamView& params, const plumage::PluginContext&) {
        return std::make_unique<MultilayerBenchmark>(multilayer_bench_table().read(params));
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_multilayer)
