#include "bem_options.hpp"

#include <stdexcept>

#include <utility>
#include <vector>

#include "plumage/memory_budget.hpp"

namespace plumage::bem {

namespace {

using Method = BemOptions::Method;
using Incidence = BemOptions::Incidence;
using Preconditioner = HMatrixOptions::Preconditioner;

const std::vector<std::pair<std::string_view, Method>>& methods() {
  static const std::vector<std::pair<std::string_view, Method>> words = {
      {"dense", Method::dense}, {"gmres", Method::gmres}, {"hmatrix", Method::hmatrix}};
  return words;
}

// A field of the nested HMatrixOptions, for the table (param_table.hpp: any callable T& -> V&).
template <class V>
auto hodlr_field(V HodlrOptions::*member) {
  return [member](BemOptions& o) -> V& { return o.hodlr.*member; };
}

template <class V>
auto hmatrix_field(V HMatrixOptions::*member) {
  return [member](BemOptions& o) -> V& { return o.hmatrix.*member; };
}

ParamTable<BemOptions> make_table() {
  const BemOptions d{};
  const HMatrixOptions& h = d.hmatrix;
  ParamTable<BemOptions> t;
  t.number("points_per_wavelength", &BemOptions::points_per_wavelength, "1", d.points_per_wavelength,
           Limits::positive(), "segments per wavelength in the denser side of each interface (h <= lambda/(|n| ppw))")
      .choice("incidence", &BemOptions::incidence, {{"beam", Incidence::beam}, {"plane_wave", Incidence::plane_wave}},
              d.incidence,
              "beam (Gaussian beam with the approximate solver's footprint, per Phi_i) | plane_wave (validation "
              "bodies; far field as 2D differential scattering width)")
      .number("window_fraction", &BemOptions::window_fraction, "1", d.window_fraction, Limits::positive(),
              "beam footprint exp(-x^2/s^2), s = fraction * width")
      .choice("method", &BemOptions::method, methods(), d.method,
              "dense (LU) | gmres (near-field-LU preconditioned GMRES, dense mat-vec) | hmatrix (GMRES, "
              "hierarchical-matrix mat-vec with ACA blocks, near-field or dense single-precision LU "
              "preconditioner; large barbules)")
      .number("aca_tolerance", hmatrix_field(&HMatrixOptions::aca_tolerance), "1", h.aca_tolerance,
              Limits::positive(), "method hmatrix: relative error of each ACA block")
      .number("eta", hmatrix_field(&HMatrixOptions::eta), "1", h.eta, Limits::positive(),
              "method hmatrix: admissibility max(diam) <= eta * distance")
      .integer("leaf_size", hmatrix_field(&HMatrixOptions::leaf_size), "1", h.leaf_size, Limits::positive(),
               "method hmatrix: segments per leaf cluster (larger: bigger near field and preconditioner, fewer "
               "iterations)")
      .number("preconditioner_factor", hmatrix_field(&HMatrixOptions::preconditioner_factor), "1",
              h.preconditioner_factor, Limits::non_negative(),
              "method hmatrix: preconditioner = near-field entries of segments closer than factor * h (0: the "
              "whole near field)")
      .choice("preconditioner", hmatrix_field(&HMatrixOptions::preconditioner),
              {{"near_field", Preconditioner::near_field}, {"dense_single", Preconditioner::dense_single},
               {"hodlr", Preconditioner::hodlr}},
              h.preconditioner,
              "method hmatrix: near_field (sparse LU of the near field) | dense_single (LU of the whole operator "
              "in complex<float>, 8 N^2 bytes: rod lattices where the near field does not precondition) | hodlr "
              "(hierarchical LU of the whole operator, low-rank off-diagonal blocks)")
      .number("hodlr_tolerance", hodlr_field(&HodlrOptions::tolerance), "1", d.hodlr.tolerance, Limits::positive(),
              "preconditioner hodlr: relative accuracy of each low-rank off-diagonal block")
      .integer("hodlr_leaf_size", hodlr_field(&HodlrOptions::leaf_size), "1", d.hodlr.leaf_size, Limits::positive(),
               "preconditioner hodlr: unknowns per dense diagonal leaf")
      .integer("hodlr_max_rank", hodlr_field(&HodlrOptions::max_rank), "1", d.hodlr.max_rank, Limits::positive(),
               "preconditioner hodlr: rank cap per off-diagonal block (bounds the memory estimate)")
      .integer("max_dense_single_unknowns", &BemOptions::max_dense_single_unknowns, "1", d.max_dense_single_unknowns,
               Limits::positive(), "preconditioner dense_single: refuse larger systems (memory 8 N^2 bytes)")
      .number("gmres_tolerance", &BemOptions::gmres_tolerance, "1", d.gmres_tolerance, Limits::positive(),
              "methods gmres/hmatrix: relative residual")
      .integer("gmres_restart", &BemOptions::gmres_restart, "1", d.gmres_restart, Limits::positive(),
               "methods gmres/hmatrix: Krylov vectors kept")
      .integer("gmres_max_iterations", &BemOptions::gmres_max_iterations, "1", d.gmres_max_iterations,
               Limits::positive(),
               "methods gmres/hmatrix: stop there; an unconverged solve raises warning bem.gmres_not_converged")
      .number("corner_split_deg", &BemOptions::corner_split_deg, "deg", d.corner_split_deg, Limits::non_negative(),
              "axial currents get separate half tents where an interface turns by this much or more")
      .number("warn_min_ppw", &BemOptions::warn_min_ppw, "1", d.warn_min_ppw, Limits::non_negative(),
              "warning bem.mesh_coarse below this many points per wavelength on any segment (0: off)")
      .number("warn_gap_ratio", &BemOptions::warn_gap_ratio, "1", d.warn_gap_ratio, Limits::non_negative(),
              "warning bem.near_touching where boundary pieces that are not mesh neighbours come closer than this "
              "times their segment length (0: off)")
      .boolean("warm_start", &BemOptions::warm_start, d.warm_start,
               "methods gmres/hmatrix: start from the residual-minimising combination of the earlier solutions")
      .integer("gmres_block", &BemOptions::gmres_block, "1", d.gmres_block, Limits::positive(),
               "methods gmres/hmatrix: right-hand sides whose GMRES run together (one pass over the matrices "
               "per step for all; each keeps its own Krylov vectors)")
      .text("log_file", &BemOptions::log_file, d.log_file,
            "append one line of timings and sizes per (lambda, theta_i)")
      .custom("max_memory", "size", "-", "(the machine's)",
              "memory budget of one solve, e.g. 8GiB (default: --max-memory, else MemAvailable and any cgroup "
              "limit): a system whose estimated peak is larger is refused before assembly",
              [](const ParamView& p, BemOptions& o) {
                if (!p.has("max_memory")) return;
                o.max_memory = p.node("max_memory").scalar_text();
                try {
                  parse_memory_size(o.max_memory);
                } catch (const std::invalid_argument& e) {
                  p.fail("max_memory", e.what());
                }
              },
              [](BemOptions& o) { o.max_memory.clear(); })
      .integer("max_dense_unknowns", &BemOptions::max_dense_unknowns, "1", d.max_dense_unknowns, Limits::positive(),
               "methods dense/gmres: refuse larger systems (memory: 16 N^2 bytes)");
  return t;
}

}  // namespace

const ParamTable<BemOptions>& bem_options_table() {
  static const ParamTable<BemOptions> table = make_table();
  return table;
}

std::string_view method_name(BemOptions::Method method) {
  for (const auto& [word, value] : methods())
    if (value == method) return word;
  return "?";
}

}  // namespace plumage::bem
