// Entry point of libplumage_rcwa.so.
//
// Provides:
//   table_builder "rcwa"    photonic-crystal reflection tables by the Fourier modal method (issue 27)
//   accuracy_ladder "rcwa"  harmonics and slices on a crystal against the finest rung (ladder/)
//   benchmark "rcwa"        one entry and a whole production table (bench/)
#include "builder.hpp"
#include "rcwa_benchmark.hpp"
#include "rcwa_ladder.hpp"
#include "plumage/config_sections.hpp"
#include "plumage/plugin_export.hpp"

namespace {

using namespace plumage;
using namespace plumage::rcwa;

// The crystal files' `rcwa:` section (production settings of one cell), listed beside the cell's
// own fields in docs/parameters.md (registered by the plug-in, which reads it).
const ConfigSectionRegistration kCrystalSection{
    {"crystal", "crystal.rcwa", "production settings of the rcwa table builder for this cell (plug-in rcwa)",
     [] { return cell_params().specs(); }}};

class RcwaLadder final : public AccuracyLadder {
 public:
  explicit RcwaLadder(std::string crystal) : crystal_(std::move(crystal)) {}
  std::vector<LadderPoint> run(const Options& options) const override { return run_rcwa_ladder(options, crystal_); }

 private:
  std::string crystal_;
};

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
  registrar.add<AccuracyLadder>(
      {.type = "rcwa",
       .version = kPluginVersion,
       .summary = "accuracy ladder: (harmonics, slices) from (2, 3) to (7, 24) on a crystal against the finest "
                  "rung (10, 48)",
       .params = ladder_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<RcwaLadder>(ladder_params().read(params).crystal);
      });
  registrar.add<Benchmark>(
      {.type = "rcwa",
       .version = kPluginVersion,
       .summary = "rcwa table builder: one (lambda, angle) entry and a whole production table (beside the fdtd one)",
       .params = bench_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<RcwaBenchmark>(bench_params().read(params));
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_rcwa)
