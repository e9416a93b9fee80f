// Entry point of libplumage_bem.so.
//
// Provides:
//   scattering_solver "bem"   full-wave 2.5D multi-region PMCHWT (spec wave-simulation.md §6)
//   accuracy_ladder "bem"     ppw ladder on cylinders against the exact series (ladder/, issue 9)
//   benchmark "bem"           the solver on a barbule segment vs the approximate solver (bench/)
#include "bem_solver.hpp"
#include "bench/bem_benchmark.hpp"
#include "plumage/accuracy_ladder.hpp"
#include "plumage/plugin_export.hpp"

namespace plumage::bem {
std::vector<LadderPoint> run_bem_ladder(const AccuracyLadder::Options& options);  // ladder/bem_ladder.cpp
}

namespace {

class BemLadder final : public plumage::AccuracyLadder {
 public:
  std::vector<plumage::LadderPoint> run(const Options& options) const override {
    return plumage::bem::run_bem_ladder(options);
  }
};

void register_bem(plumage::Registrar& registrar) {
  using plumage::bem::bem_options_table;
  registrar.add<plumage::ScatteringSolver>(
      {.type = "bem",
       .version = "0.1.0",
       .summary = "full-wave 2.5D boundary elements: multi-region PMCHWT, Galerkin tents, analytic "
                  "log/1/R parts, junctions, exact 2.5D Gaussian beam; dense LU or GMRES with a hierarchical "
                  "matrix (ACA) per (lambda, theta_i)",
       .params = bem_options_table().specs()},
      [](const plumage::ParamView& p, const plumage::PluginContext&) {
        return std::make_unique<plumage::bem::BemSolver>(bem_options_table().read(p));
      });
  registrar.add<plumage::AccuracyLadder>(
      {.type = "bem",
       .version = "0.1.0",
       .summary = "accuracy ladder: 8-48 points per wavelength on keratin and coated cylinders against the "
                  "exact series",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) { return std::make_unique<BemLadder>(); });
  plumage::bem::register_bem_benchmark(registrar);
}

}  // namespace

PLUMAGE_PLUGIN(register_bem)
