// Entry point of libplumage_photonic_crystal.so.
//
// Provides:
//   structure_generator "crystal_barbule"   procedural barbules of types 5–7 (crystal_barbule.cpp)
//   local_reflection "photonic_crystal"     table-driven crystal reflection (crystal_table_reflection.cpp,
//                                           its table built in the preparation step: on_demand_table.cpp)
#include "crystal_barbule.hpp"
#include "crystal_table_reflection.hpp"
#include "plumage/plugin_export.hpp"

namespace {

void register_photonic_crystal(plumage::Registrar& registrar) {
  using plumage::photonic_crystal::CrystalBarbule;
  registrar.add<plumage::StructureGenerator>(
      {.type = "crystal_barbule",
       .version = "1.0.0",
       .summary = "procedural barbule cross sections over a photonic crystal (types 5-7): rough "
                  "top, crystal reference and regularity; exact model with rods, hollow cores "
                  "and air channels under the top",
       .params = plumage::photonic_crystal::crystal_barbule_table().specs()},
      [](const plumage::ParamView& params, const plumage::PluginContext& context) {
        return std::make_unique<CrystalBarbule>(params, context);
      });
  registrar.add<plumage::LocalReflection>(
      {.type = "photonic_crystal",
       .version = "1.0.0",
       .summary = "photonic-crystal reflection from a table (Jones s/p over lambda, cos theta, cos phi): "
                  "cubic in the angles, mirror symmetry, exact grazing limit; built in the preparation step "
                  "and cached",
       .params = plumage::photonic_crystal::CrystalTableReflection::param_table()},
      [](const plumage::ParamView& params, const plumage::PluginContext& context) {
        return std::make_unique<plumage::photonic_crystal::CrystalTableReflection>(params, context);
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_photonic_crystal)
