// Entry point of libplumage_bem.so.
//
// Provides:
//   scattering_solver "bem"   full-wave 2.5D multi-region PMCHWT (spec wave-simulation.md §6)
#include "bem_solver.hpp"
#include "plumage/plugin_export.hpp"

namespace {

void register_bem(plumage::Registrar& registrar) {
  using plumage::bem::BemOptions;
  static constexpr std::string_view kIncidence[] = {"beam", "plane_wave"};
  static constexpr std::string_view kMethod[] = {"dense", "gmres"};
  registrar.add<plumage::ScatteringSolver>(
      {.kind = "",
       .type = "bem",
       .version = "0.1.0",
       .summary = "full-wave 2.5D boundary elements: multi-region PMCHWT, Galerkin tents, analytic "
                  "log/1/R parts, junctions, exact 2.5D Gaussian beam, dense LU per (lambda, theta_i)",
       .params = {{"points_per_wavelength", "number", "1", "30",
                   "segments per wavelength in the denser side of each interface (h <= lambda/(|n| ppw))"},
                  {"incidence", "choice", "-", "beam",
                   "beam (Gaussian beam with the approximate solver's footprint, per Phi_i) | plane_wave "
                   "(validation bodies; far field as 2D differential scattering width)"},
                  {"window_fraction", "number", "1", "0.25", "beam footprint exp(-x^2/s^2), s = fraction * width"},
                  {"method", "choice", "-", "dense", "dense (LU) | gmres (near-field-LU preconditioned GMRES; dense mat-vec for now)"},
                  {"max_dense_unknowns", "integer", "1", "20000",
                   "refuse dense systems larger than this (memory: 16 N^2 bytes)"}}},
      [](const plumage::ParamView& p, const plumage::PluginContext&) {
        BemOptions o;
        o.points_per_wavelength = p.number_or("points_per_wavelength", 30.0, plumage::Limits::positive());
        o.incidence = p.choice_or("incidence", kIncidence, "beam") == "beam" ? BemOptions::Incidence::beam
                                                                              : BemOptions::Incidence::plane_wave;
        o.window_fraction = p.number_or("window_fraction", 0.25, plumage::Limits::positive());
        o.method = p.choice_or("method", kMethod, "dense") == "dense" ? BemOptions::Method::dense
                                                                      : BemOptions::Method::gmres;
        o.max_dense_unknowns = static_cast<int>(p.integer_or("max_dense_unknowns", 20000, plumage::Limits::positive()));
        return std::make_unique<plumage::bem::BemSolver>(o);
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_bem)
