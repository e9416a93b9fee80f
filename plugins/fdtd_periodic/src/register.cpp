// Entry point of libplumage_fdtd_periodic.so.
//
// Provides:
//   table_builder "fdtd_periodic"   photonic-crystal reflection tables from the periodic 2.5D FDTD
//   accuracy_ladder "fdtd_periodic" resolution ladder vs the multilayer limit and vs the finest rung (ladder/, issue 9)
//   benchmark "fdtd"                one solve, one broadband run, a whole production table (bench/)
#include "builder.hpp"
#include "fdtd_benchmark.hpp"
#include "fdtd_ladder.hpp"
#include "plumage/config_sections.hpp"
#include "plumage/plugin_export.hpp"

namespace {

using namespace plumage;
using namespace plumage::fdtd_table;

// The crystal files' `fdtd_periodic:` section, listed beside the cell's own fields in
// docs/parameters.md (registered by the plug-in, which reads it; libraries are never unloaded).
const ConfigSectionRegistration kCrystalSection{
    {"crystal", "crystal.fdtd_periodic", "numerics of the fdtd_periodic table builder for this cell (plug-in fdtd_periodic)",
     [] { return crystal_numerics_params().specs(); }}};

class FdtdLadder final : public AccuracyLadder {
 public:
  explicit FdtdLadder(std::string crystal) : crystal_(std::move(crystal)) {}
  std::vector<LadderPoint> run(const Options& options) const override { return run_fdtd_ladder(options, crystal_); }

 private:
  std::string crystal_;
};

void register_fdtd_periodic(Registrar& registrar) {
  registrar.add<TableBuilder>(
      {.type = "fdtd_periodic",
       .version = kPluginVersion,
       .summary = "photonic-crystal reflection tables from a periodic 2.5D FDTD (Bloch k, CPML, "
                  "subpixel smoothing, dispersive melanin/keratin), Jones (s, p) per (lambda, theta, phi); "
                  "per crystal its fdtd_periodic: section",
       .params = builder_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<FdtdTableBuilder>(builder_params().read(params));
      });
  registrar.add<AccuracyLadder>(
      {.type = "fdtd_periodic",
       .version = kPluginVersion,
       .summary = "accuracy ladder: grid steps 20-5 nm on a layered stack against the closed-form Airy "
                  "recursion, 15-3.8 nm on a crystal against its finest rung",
       .params = ladder_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<FdtdLadder>(ladder_params().read(params).crystal);
      });
  registrar.add<Benchmark>(
      {.type = "fdtd",
       .version = kPluginVersion,
       .summary = "periodic FDTD table builder: one solve, one broadband run, a whole production table",
       .params = bench_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<FdtdBenchmark>(bench_params().read(params));
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_fdtd_periodic)
