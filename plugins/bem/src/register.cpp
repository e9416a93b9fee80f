// Entry point of libplumage_bem.so.
//
// Provides:
//   scattering_solver "bem"   full-wave 2.5D multi-region PMCHWT (spec wave-simulation.md §6)
//   accuracy_ladder "bem"     ppw ladder on cylinders against the exact series (ladder/, issue 9)
#include "bem_solver.hpp"
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
  using plumage::bem::BemOptions;
  static constexpr std::string_view kIncidence[] = {"beam", "plane_wave"};
  static constexpr std::string_view kMethod[] = {"dense", "gmres", "hmatrix"};
  static constexpr std::string_view kPreconditioner[] = {"near_field", "dense_single"};
  registrar.add<plumage::ScatteringSolver>(
      {.kind = "",
       .type = "bem",
       .version = "0.1.0",
       .summary = "full-wave 2.5D boundary elements: multi-region PMCHWT, Galerkin tents, analytic "
                  "log/1/R parts, junctions, exact 2.5D Gaussian beam; dense LU or GMRES with a hierarchical "
                  "matrix (ACA) per (lambda, theta_i)",
       .params = {{"points_per_wavelength", "number", "1", "30",
                   "segments per wavelength in the denser side of each interface (h <= lambda/(|n| ppw))"},
                  {"incidence", "choice", "-", "beam",
                   "beam (Gaussian beam with the approximate solver's footprint, per Phi_i) | plane_wave "
                   "(validation bodies; far field as 2D differential scattering width)"},
                  {"window_fraction", "number", "1", "0.25", "beam footprint exp(-x^2/s^2), s = fraction * width"},
                  {"method", "choice", "-", "dense",
                   "dense (LU) | gmres (near-field-LU preconditioned GMRES, dense mat-vec) | hmatrix (GMRES, "
                   "hierarchical-matrix mat-vec with ACA blocks, near-field or dense single-precision LU preconditioner; large barbules)"},
                  {"aca_tolerance", "number", "1", "1e-6", "method hmatrix: relative error of each ACA block"},
                  {"eta", "number", "1", "1", "method hmatrix: admissibility max(diam) <= eta * distance"},
                  {"leaf_size", "integer", "1", "24", "method hmatrix: segments per leaf cluster (larger: bigger near field and preconditioner, fewer iterations)"},
                  {"preconditioner_factor", "number", "1", "0",
                   "method hmatrix: preconditioner = near-field entries of segments closer than factor * h "
                   "(0: the whole near field)"},
                  {"preconditioner", "choice", "-", "near_field",
                   "method hmatrix: near_field (sparse LU of the near field) | dense_single (LU of the whole "
                   "operator in complex<float>, 8 N^2 bytes: rod lattices where the near field does not precondition)"},
                  {"max_dense_single_unknowns", "integer", "1", "40000",
                   "preconditioner dense_single: refuse larger systems (memory 8 N^2 bytes)"},
                  {"gmres_tolerance", "number", "1", "1e-8", "methods gmres/hmatrix: relative residual"},
                  {"gmres_restart", "integer", "1", "300", "methods gmres/hmatrix: Krylov vectors kept"},
                  {"gmres_max_iterations", "integer", "1", "5000",
                   "methods gmres/hmatrix: stop there; an unconverged solve raises warning bem.gmres_not_converged"},
                  {"corner_split_deg", "number", "deg", "30",
                   "axial currents get separate half tents where an interface turns by this much or more"},
                  {"warn_min_ppw", "number", "1", "14",
                   "warning bem.mesh_coarse below this many points per wavelength on any segment (0: off)"},
                  {"warm_start", "bool", "-", "true",
                   "methods gmres/hmatrix: start from the residual-minimising combination of the earlier solutions"},
                  {"log_file", "text", "-", "", "append one line of timings and sizes per (lambda, theta_i)"},
                  {"max_dense_unknowns", "integer", "1", "20000",
                   "refuse dense systems larger than this (memory: 16 N^2 bytes)"}}},
      [](const plumage::ParamView& p, const plumage::PluginContext&) {
        BemOptions o;
        o.points_per_wavelength = p.number_or("points_per_wavelength", 30.0, plumage::Limits::positive());
        o.incidence = p.choice_or("incidence", kIncidence, "beam") == "beam" ? BemOptions::Incidence::beam
                                                                              : BemOptions::Incidence::plane_wave;
        o.window_fraction = p.number_or("window_fraction", 0.25, plumage::Limits::positive());
        const auto method = p.choice_or("method", kMethod, "dense");
        o.method = method == "dense"   ? BemOptions::Method::dense
                   : method == "gmres" ? BemOptions::Method::gmres
                                       : BemOptions::Method::hmatrix;
        o.hmatrix.aca_tolerance = p.number_or("aca_tolerance", 1e-6, plumage::Limits::positive());
        o.hmatrix.eta = p.number_or("eta", 1.0, plumage::Limits::positive());
        o.hmatrix.leaf_size = static_cast<int>(p.integer_or("leaf_size", 24, plumage::Limits::positive()));
        o.hmatrix.preconditioner_factor = p.number_or("preconditioner_factor", 0.0, plumage::Limits::non_negative());
        o.hmatrix.preconditioner = p.choice_or("preconditioner", kPreconditioner, "near_field") == "dense_single"
                                       ? plumage::bem::HMatrixOptions::Preconditioner::dense_single
                                       : plumage::bem::HMatrixOptions::Preconditioner::near_field;
        o.max_dense_single_unknowns =
            static_cast<int>(p.integer_or("max_dense_single_unknowns", 40000, plumage::Limits::positive()));
        o.gmres_tolerance = p.number_or("gmres_tolerance", 1e-8, plumage::Limits::positive());
        o.gmres_restart = static_cast<int>(p.integer_or("gmres_restart", 300, plumage::Limits::positive()));
        o.gmres_max_iterations =
            static_cast<int>(p.integer_or("gmres_max_iterations", 5000, plumage::Limits::positive()));
        o.warn_min_ppw = p.number_or("warn_min_ppw", 14.0, plumage::Limits::non_negative());
        o.corner_split_deg = p.number_or("corner_split_deg", 30.0, plumage::Limits::non_negative());
        o.warm_start = p.boolean_or("warm_start", true);
        o.log_file = p.text_or("log_file", "");
        o.max_dense_unknowns = static_cast<int>(p.integer_or("max_dense_unknowns", 20000, plumage::Limits::positive()));
        return std::make_unique<plumage::bem::BemSolver>(o);
      });
  registrar.add<plumage::AccuracyLadder>(
      {.kind = "",
       .type = "bem",
       .version = "0.1.0",
       .summary = "accuracy ladder: 8-48 points per wavelength on keratin and coated cylinders against the "
                  "exact series",
       .params = {}},
      [](const plumage::ParamView&, const plumage::PluginContext&) { return std::make_unique<BemLadder>(); });
}

}  // namespace

PLUMAGE_PLUGIN(register_bem)
