// Entry point of libplumage_rcwa.so.
//
// Provides:
//   table_builder "rcwa"   photonic-crystal reflection tables by the Fourier modal method (issue 27)
#include "builder.hpp"
#include "plumage/plugin_export.hpp"

namespace {

using namespace plumage;
using namespace plumage::rcwa;

void register_rcwa(Registrar& registrar) {
  registrar.add<TableBuilder>(
      {.type = "rcwa",
       .version = kPluginVersion,
       .summary = "photonic-crystal reflection tables by the Fourier modal method (RCWA): staircase slices, "
                  "conical incidence, Li's inverse rule, Redheffer S-matrices; Jones (s, p) per (lambda, theta, phi)",
       .params = builder_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<RcwaTableBuilder>(builder_params().read(params));
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_rcwa)
