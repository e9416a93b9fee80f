// The "bem" ScatteringSolver: prepare() builds the interfaces, solve() meshes at λ, assembles and
// factorises the PMCHWT matrix once per (λ, θ_i) and reuses it for every φ_i and both
// polarisations (spec §6.8), then radiates the outer-boundary currents (§6.9).
#include "bem_solver.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <fstream>

#include "plumage/atomic_file.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/memory_budget.hpp"
#include "memory_estimate.hpp"
#include "hmatrix_entries.hpp"
#include "radiation.hpp"

namespace plumage::bem {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string format(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

// Method gmres preconditions with the sparse LU of the entries of Z coupling segments closer than
// this × h (NOTES.md §5, "Method gmres"): 8 h converged on the coated cylinder and the junction
// body alike, where 2 h needed 8× the iterations on the junction body and 1 h stagnated.
constexpr double kGmresNearFieldFactor = 8.0;

// Far-field directions whose rows of the far-field operator are built at a time (memory_estimate.cpp).
constexpr std::size_t kFarFieldChunk = 32;

// "bem: GMRES (14032 unknowns, 550 nm)": the step name of the progress lines.
std::string step_name(const char* step, const Mesh& mesh, double lambda_nm) {
  return format("bem: %s (%d unknowns, %g nm)", step, mesh.unknowns(), lambda_nm);
}
}  // namespace

void check_mesh(const Geometry& geometry, const Mesh& mesh, double lambda_nm, const BemOptions& options) {
  if (options.warn_min_ppw > 0.0) {
    const MeshResolution r = mesh_resolution(mesh, geometry, lambda_nm, options.warn_min_ppw);
    if (r.min_ppw < options.warn_min_ppw) {
      warn("bem.mesh_coarse",
           format("bem: mesh at %g nm has %.1f points per wavelength in %s (segments of %.3g nm; %.0f %% of the "
                  "interface length below %g ppw, where the far field's error passed 1e-2 on the validation "
                  "cylinders); raise points_per_wavelength",
                  lambda_nm, r.min_ppw, geometry.domain_name[r.domain].c_str(), r.h_nm, 100.0 * r.length_fraction,
                  options.warn_min_ppw));
    }
  }
  if (options.warn_gap_ratio > 0.0) {
    const CloseApproach c = closest_approach(mesh, options.warn_gap_ratio);
    if (c.pairs > 0) {
      const Segment& A = mesh.segments[c.seg_a];
      const Segment& B = mesh.segments[c.seg_b];
      const Vec2 at = 0.5 * (A.p0 + A.p1);
      warn("bem.near_touching",
           format("bem: boundary %s|%s comes within %.3g nm of boundary %s|%s near (%.1f, %.1f) nm, segment length "
                  "%.3g nm (gap/h = %.1e < %g; %d segment pairs): the outlines touch or cross, and the far field of "
                  "such a body was measured wrong by 1e-2 to 1e-1",
                  geometry.domain_name[A.a].c_str(), geometry.domain_name[A.b].c_str(), c.gap_nm,
                  geometry.domain_name[B.a].c_str(), geometry.domain_name[B.b].c_str(), at.x, at.z, c.h_nm,
                  c.gap_nm / c.h_nm, options.warn_gap_ratio, c.pairs));
    }
  }
}

std::shared_ptr<const BemPrepared> prepare_geometry(const CrossSection& section) {
  auto p = std::make_shared<BemPrepared>();
  p->geometry = build_geometry(section);
  p->top = section.top;
  if (section.top.size() >= 2) {
    const double x0 = 0.5 * (section.top.front().x + section.top.back().x);
    p->focus = {x0, section.top.front().z};
    for (std::size_t k = 0; k + 1 < section.top.size(); ++k) {
      const Vec2 a = section.top[k], b = section.top[k + 1];
      if (a.x <= x0 && x0 <= b.x && b.x > a.x) {
        p->focus.z = a.z + (b.z - a.z) * (x0 - a.x) / (b.x - a.x);
        break;
      }
    }
    p->width = section.width_nm();
  }
  for (const InterfaceEdge& e : p->geometry.edges) {
    p->extent = std::max({p->extent, norm(e.p - p->focus), norm(e.q - p->focus)});
  }
  return p;
}

// The HODLR preconditioner (hodlr.hpp) from the rows and columns of the H-matrix.
static void build_hodlr(System& sys, const BemOptions& options) {
  sys.hodlr = std::make_unique<HodlrLU>(unknown_positions(sys.mesh), options.hodlr);
  const HMatrixEntries entries(*sys.hmatrix, sys.mesh, sys.media, sys.hodlr->perm());
  const auto row = [&](int p, const IndexBox& w, Eigen::VectorXcd& out) { entries.row(p, w, out); };
  const auto column = [&](int p, const IndexBox& w, Eigen::VectorXcd& out) { entries.column(p, w, out); };
  const std::string step = step_name("HODLR factorisation", sys.mesh, sys.lambda_nm);
  report_step(step, 0, 0);
  sys.hodlr->factorise(row, column, [&](int done, int total) { report_step(step, done, total, "levels"); });
  const HodlrStats& st = sys.hodlr->stats();
  report_step(step, st.levels + 1, st.levels + 1,
              format("levels; ranks mean %.1f max %d, %d blocks at the rank cap, %.2f GB", st.mean_rank, st.max_rank,
                     st.capped_blocks, st.memory_gb));
}

std::unique_ptr<System> build_system(const Geometry& geometry, double lambda_nm, double theta,
                                     const BemOptions& options, int rhs, int far_directions) {
  auto sys = std::make_unique<System>();
  sys->lambda_nm = lambda_nm;
  sys->theta = theta;
  sys->k0 = 2.0 * std::numbers::pi / lambda_nm;
  sys->beta = -sys->k0 * std::sin(theta);
  sys->mesh = build_mesh(geometry, lambda_nm, options.points_per_wavelength, options.corner_split_deg);
  check_mesh(geometry, sys->mesh, lambda_nm, options);
  sys->media = media(geometry, lambda_nm, sys->beta);
  const double n = sys->mesh.unknowns();
  if (options.method == BemOptions::Method::hmatrix &&
      options.hmatrix.preconditioner == HMatrixOptions::Preconditioner::dense_single &&
      n > options.max_dense_single_unknowns) {
    throw Error("bem: " + std::to_string(sys->mesh.unknowns()) + " unknowns at " + std::to_string(lambda_nm) +
                " nm exceed max_dense_single_unknowns = " + std::to_string(options.max_dense_single_unknowns) +
                " (the dense_single preconditioner would need " + std::to_string(static_cast<long>(n * n * 8 / 1e9 + 0.5)) +
                " GB); use preconditioner: near_field or raise the limit if the machine has the memory");
  }
  if (options.method == BemOptions::Method::hmatrix) {
    // Before anything is assembled (issue 23): a system over the budget is refused, not killed.
    check_memory(estimate_system_memory(sys->mesh, lambda_nm, options, rhs, far_directions),
                 memory_available(options.max_memory));
    auto t0 = std::chrono::steady_clock::now();
    sys->hmatrix = std::make_unique<HMatrix>(sys->mesh, sys->media, sys->k0, sys->beta, options.quadrature,
                                             options.hmatrix, step_name("H-matrix assembly", sys->mesh, lambda_nm));
    sys->assembly_seconds = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    if (options.hmatrix.preconditioner == HMatrixOptions::Preconditioner::dense_single) {
      // Tens of minutes at ~35 000 unknowns: say how far the factorisation is (memory_budget.hpp's
      // step progress: the CLI prints it with an ETA, -q silences it).
      report_step(step_name("expanding the H-matrix to dense single precision", sys->mesh, lambda_nm), 0, 0);
      Eigen::MatrixXcf dense = sys->hmatrix->to_dense_single(sys->mesh, sys->media);
      sys->expand_seconds = seconds_since(t0);
      const std::string lu_step = step_name("single-precision LU", sys->mesh, lambda_nm);
      const auto progress = [&](double f) { report_step(lu_step, 100.0 * f, 100.0, "% of the flops"); };
      report_step(lu_step, 0, 100.0, "% of the flops");
      sys->dense_single = std::make_unique<SinglePrecisionLU>(std::move(dense), 256, progress);
    } else if (options.hmatrix.preconditioner == HMatrixOptions::Preconditioner::hodlr) {
      build_hodlr(*sys, options);
    } else {
      report_step(step_name("sparse LU of the near field (preconditioner)", sys->mesh, lambda_nm), 0, 0);
      sys->near_field = std::make_unique<NearFieldLU>(sys->hmatrix->take_preconditioner_matrix());
    }
    sys->factor_seconds = seconds_since(t0);
    return sys;
  }
  if (n > options.max_dense_unknowns) {
    throw Error("bem: " + std::to_string(sys->mesh.unknowns()) + " unknowns at " + std::to_string(lambda_nm) +
                " nm (" + std::to_string(sys->mesh.segments.size()) + " segments) exceed max_dense_unknowns = " +
                std::to_string(options.max_dense_unknowns) + " (dense LU would need " +
                std::to_string(static_cast<long>(n * n * 16 / 1e9 + 0.5)) +
                " GB); use method: hmatrix (compressed mat-vec) or simulate a narrower segment");
  }
  check_memory(estimate_system_memory(sys->mesh, lambda_nm, options, rhs, far_directions),
               memory_available(options.max_memory));
  auto t0 = std::chrono::steady_clock::now();
  report_step(step_name("dense assembly", sys->mesh, lambda_nm), 0, 0);
  sys->Z = assemble_dense(sys->mesh, sys->media, sys->k0, sys->beta, options.quadrature);
  sys->assembly_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  report_step(step_name(options.method == BemOptions::Method::gmres ? "near-field LU" : "dense LU", sys->mesh, lambda_nm),
              0, 0);
  if (options.method == BemOptions::Method::gmres) {
    sys->near_field = std::make_unique<NearFieldLU>(sys->mesh, sys->Z, kGmresNearFieldFactor);
  } else {
    sys->lu = std::make_unique<Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXcd>>>(sys->Z);  // in place
  }
  sys->factor_seconds = seconds_since(t0);
  return sys;
}

Eigen::MatrixXcd System::solve(const Eigen::MatrixXcd& B, const BemOptions& options, std::vector<int>* iterations) const {
  if (options.method == BemOptions::Method::dense) return lu->solve(B);
  Eigen::MatrixXcd X = Eigen::MatrixXcd::Zero(B.rows(), B.cols());
  const BlockOp A = [&](const Eigen::MatrixXcd& in, Eigen::MatrixXcd& out) {
    if (hmatrix) hmatrix->apply(in, out);
    else out.noalias() = Z * in;
  };
  const BlockOp M = [&](const Eigen::MatrixXcd& in, Eigen::MatrixXcd& out) {
    if (hodlr) return hodlr->apply(in, out);
    out.resize(in.rows(), in.cols());
    for (Eigen::Index c = 0; c < in.cols(); ++c) {
      Eigen::VectorXcd o;
      if (dense_single) dense_single->apply(in.col(c), o);
      else near_field->apply(in.col(c), o);
      out.col(c) = o;
    }
  };
  const std::string gmres_step = step_name("GMRES", mesh, lambda_nm);
  const int ncols = static_cast<int>(B.cols()), block = std::max(1, options.gmres_block);
  Eigen::MatrixXcd AX(options.warm_start ? B.rows() : 0, options.warm_start ? B.cols() : 0);
  for (int c0 = 0; c0 < ncols; c0 += block) {
    const int nb = std::min(block, ncols - c0);
    // warm start: the combination of all earlier groups' solutions that minimises the residual,
    // x0 = X_c y with y = argmin ‖b − (A X_c) y‖ (A X_c kept, one extra mat-vec per column)
    Eigen::MatrixXcd Xg = Eigen::MatrixXcd::Zero(B.rows(), nb);
    if (options.warm_start && c0 >= 1) {
      const auto qr = AX.leftCols(c0).colPivHouseholderQr();
      for (int j = 0; j < nb; ++j) Xg.col(j) = X.leftCols(c0) * qr.solve(B.col(c0 + j));
    }
    // Long solves say how far they are (step progress, memory_budget.hpp: the CLI prints at most
    // every 10 s, with the ETA from the right-hand sides done).
    const auto progress = [&](int j, int it, double residual) {
      report_step(gmres_step, static_cast<double>(c0), static_cast<double>(ncols),
                  format("right-hand side %d: %d iterations, relative residual %.1e (goal %.0e)", c0 + j + 1, it,
                         residual, options.gmres_tolerance));
    };
    const std::vector<GmresResult> rs = gmres_lockstep(A, M, B.middleCols(c0, nb), Xg, options.gmres_tolerance,
                                                       options.gmres_restart, options.gmres_max_iterations, progress);
    for (int j = 0; j < nb; ++j) {
      const GmresResult& r = rs[j];
      if (!r.converged) {
        // Not an error: a long run keeps its other (λ, θ_i), and the result of this one carries
        // the warning (output metadata, stderr) with the residual it reached.
        warn("bem.gmres_not_converged",
             format("bem: GMRES stopped after %d iterations at relative residual %.2e (goal %.0e) for right-hand "
                    "side %d of %d at %g nm, theta_i %.1f deg; that solution is unconverged (raise "
                    "gmres_max_iterations or use a stronger preconditioner)",
                    r.iterations, r.relative_residual, options.gmres_tolerance, c0 + j + 1, ncols, lambda_nm,
                    theta * 180.0 / std::numbers::pi));
      }
      if (iterations) iterations->push_back(r.iterations);
    }
    X.middleCols(c0, nb) = Xg;
    if (options.warm_start && c0 + nb < ncols) {
      Eigen::MatrixXcd ax;
      A(Xg, ax);
      AX.middleCols(c0, nb) = ax;
    }
    report_step(gmres_step, static_cast<double>(c0 + nb), static_cast<double>(ncols),
                format("right-hand sides %d-%d converged", c0 + 1, c0 + nb));
  }
  return X;
}

IncidentField incident_for(const BemPrepared& prep, const BemOptions& options, double k0, double theta,
                           double phi, int pol) {
  if (options.incidence == BemOptions::Incidence::plane_wave) return plane_wave(theta, phi, pol);
  const double s = options.window_fraction * prep.width;
  if (!(s > 0.0)) throw Error("bem: a Gaussian beam needs a top surface of positive width");
  return gaussian_beam(k0, theta, phi, pol, s * std::cos(phi), prep.focus, prep.extent);
}

double window_incident_power(const BemPrepared& prep, double window_fraction, double theta, double phi) {
  // spec §1.7: Φ_i = (1/2η0) Σ_{lit interior top nodes} d_m w_m² ω_i·n̂_m, w = exp(−x²/s²)
  const Polyline& top = prep.top;
  if (top.size() < 3) return 0.0;
  const auto normals = vertex_normals(top);
  const double s = window_fraction * prep.width;
  const Direction wi = direction_from_angles(theta, phi);
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < top.size(); ++i) {
    const double cos_a = wi.x * normals[i].x + wi.z * normals[i].z;
    if (cos_a <= 0.0) continue;
    const double x = top[i].x - prep.focus.x;
    const double w = std::exp(-(x * x) / (s * s));
    const double d = 0.5 * (norm(top[i] - top[i - 1]) + norm(top[i + 1] - top[i]));
    sum += d * w * w * cos_a;
  }
  return sum / (2.0 * kEta0_ohm);
}

double absorption_width(const Mesh& mesh, const Eigen::Ref<const Eigen::VectorXcd>& x) {
  // tents: ∫ N_i N_j = h M_ij, M = [[1/3, 1/6], [1/6, 1/3]]
  double sum = 0.0;
  for (const Segment& S : mesh.segments) {
    if (S.a != 0) continue;
    const cplx jt[2] = {x[mesh.jt(S.v0)], x[mesh.jt(S.v1)]};
    const cplx jz[2] = {x[mesh.jz(S.zdof[0])], x[mesh.jz(S.zdof[1])]};
    const cplx mt[2] = {x[mesh.mt(S.v0)], x[mesh.mt(S.v1)]};
    const cplx mz[2] = {x[mesh.mz(S.zdof[0])], x[mesh.mz(S.zdof[1])]};
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const double m = S.h * (i == j ? 1.0 / 3.0 : 1.0 / 6.0);
        sum += m * std::real(mz[i] * std::conj(jt[j]) - mt[i] * std::conj(jz[j]));
      }
    }
  }
  return sum;
}

std::shared_ptr<const ScatteringSolver::Prepared> BemSolver::prepare(
    const CrossSection& section, std::shared_ptr<const LocalReflection>) const {
  auto p = prepare_geometry(section);
  if (options_.incidence == BemOptions::Incidence::beam && section.top.size() < 3) {
    throw Error("bem: cross section '" + section.label + "' has no top surface for the Gaussian beam "
                "(use incidence: plane_wave)");
  }
  return p;
}

MemoryEstimate BemSolver::estimate_memory(const CrossSection& section, double lambda_nm, std::size_t n_phi_i,
                                          std::size_t n_phi_o) const {
  const Geometry geometry = build_geometry(section);
  const Mesh mesh = build_mesh(geometry, lambda_nm, options_.points_per_wavelength, options_.corner_split_deg);
  return estimate_system_memory(mesh, lambda_nm, options_, 2 * static_cast<int>(n_phi_i), static_cast<int>(n_phi_o));
}

std::vector<FarField> BemSolver::solve(const Prepared& prepared, double lambda_nm, double theta,
                                       std::span<const double> phi_i, std::span<const double> phi_o) const {
  const auto* prep = dynamic_cast<const BemPrepared*>(&prepared);
  if (!prep) throw Error("bem: prepared data of another solver");
  const auto sys = build_system(prep->geometry, lambda_nm, theta, options_, 2 * static_cast<int>(phi_i.size()),
                                static_cast<int>(phi_o.size()));
  const Mesh& mesh = sys->mesh;
  const int n = mesh.unknowns();
  const int nrhs = 2 * static_cast<int>(phi_i.size());
  Eigen::MatrixXcd B(n, nrhs);
  for (std::size_t a = 0; a < phi_i.size(); ++a) {
    for (int pol = 0; pol < 2; ++pol) {
      fill_rhs(mesh, sys->k0, incident_for(*prep, options_, sys->k0, theta, phi_i[a], pol), B.col(2 * a + pol));
    }
  }
  auto t0 = std::chrono::steady_clock::now();
  std::vector<int> iterations;
  const Eigen::MatrixXcd X = sys->solve(B, options_, &iterations);
  const double solve_s = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  // Method hmatrix: E = F X by chunks of directions, since F (3 rows per direction × N) would
  // otherwise be the largest array after the factor at the bench's 400 directions (3.8 GiB at
  // 214 732 unknowns); the dense methods hold N² anyway and build F at once (memory_estimate.cpp).
  Eigen::MatrixXcd E(3 * phi_o.size(), nrhs);
  const std::size_t chunk = options_.method == BemOptions::Method::hmatrix ? kFarFieldChunk : phi_o.size();
  for (std::size_t d0 = 0; d0 < phi_o.size(); d0 += std::max<std::size_t>(chunk, 1)) {
    const std::size_t nd = std::min(chunk, phi_o.size() - d0);
    const Eigen::MatrixXcd F = far_field_operator(mesh, sys->k0, theta, phi_o.subspan(d0, nd));
    E.middleRows(3 * d0, 3 * nd) = F * X;
  }
  const double far_s = seconds_since(t0);
  if (!options_.log_file.empty()) {
    check_output_path(options_.log_file);
    std::ofstream log(options_.log_file, std::ios::app);
    log << "lambda_nm " << lambda_nm << " theta_deg " << theta * 180.0 / std::numbers::pi << " unknowns " << n
        << " segments " << mesh.segments.size() << " assembly_s " << sys->assembly_seconds << " factor_s "
        << sys->factor_seconds << " solve_s " << solve_s << " far_field_s " << far_s;
    if (sys->hmatrix) {
      const HMatrixStats& st = sys->hmatrix->stats();
      log << " near_s " << st.near_seconds << " aca_s " << st.aca_seconds << " near_pairs " << st.near_pairs
          << " near_nnz " << st.near_nonzeros << " precond_nnz " << st.preconditioner_nonzeros << " blocks "
          << st.admissible_blocks << " dense_fallback " << st.dense_blocks << " mean_rank " << st.mean_rank
          << " max_rank " << st.max_rank << " hmatrix_gb " << st.memory_gb();
      log << " preconditioner " << (sys->dense_single ? "dense_single" : sys->hodlr ? "hodlr" : "near_field");
      if (sys->hodlr) {
        const HodlrStats& hs = sys->hodlr->stats();
        log << " hodlr_gb " << hs.memory_gb << " hodlr_mean_rank " << hs.mean_rank << " hodlr_max_rank " << hs.max_rank
            << " hodlr_capped " << hs.capped_blocks << " hodlr_compress_thread_s " << hs.seconds_compress
            << " hodlr_factor_thread_s " << hs.seconds_factor;
      }
      if (sys->dense_single) log << " expand_s " << sys->expand_seconds << " dense_single_gb " << sys->dense_single->memory_gb();
    }
    if (!iterations.empty()) {
      log << " iterations";
      for (int it : iterations) log << " " << it;
    }
    log << "\n";
  }
  std::vector<FarField> out;
  for (std::size_t a = 0; a < phi_i.size(); ++a) {
    FarField ff;
    ff.lambda_nm = lambda_nm;
    ff.incident = {theta, phi_i[a]};
    ff.phi_o_rad.assign(phi_o.begin(), phi_o.end());
    for (int pol = 0; pol < 2; ++pol) {
      auto& f = ff.field[pol];
      f.resize(phi_o.size());
      for (std::size_t d = 0; d < phi_o.size(); ++d) {
        for (int c = 0; c < 3; ++c) f[d][c] = E(3 * d + c, 2 * a + pol);
      }
      ff.incident_power[pol] = options_.incidence == BemOptions::Incidence::plane_wave
                                   ? 1.0 / (2.0 * kEta0_ohm)
                                   : window_incident_power(*prep, options_.window_fraction, theta, phi_i[a]);
    }
    out.push_back(std::move(ff));
  }
  return out;
}

}  // namespace plumage::bem
