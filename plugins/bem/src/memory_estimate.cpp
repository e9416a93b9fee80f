// BEM memory estimate (memory_estimate.hpp).
#include "memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cluster.hpp"

namespace plumage::bem {

namespace {

// Stored near-field entries per near segment pair (8 x 8 local entries, shared between
// neighbours): measured 27.0 (hummingbird 0.3 um, 30 ppw), 26.8 (5 um, 10 ppw), 33.0 (mallard).
constexpr double kEntriesPerNearPair = 34.0;
constexpr double kSparseEntryBytes = 20.0;  // complex<double> + int index
// Sparse LU fill: bytes of the factors per near-field entry, 128 at 14 032 unknowns and growing as
// N^0.4 (fitted to the peaks at 14 032 and 39 508 unknowns; x1.25 margin for an upper bound).
double lu_bytes_per_entry(double n) { return 1.25 * 128.0 * std::pow(std::max(n, 1000.0) / 14032.0, 0.4); }
constexpr double kMaxRank = 16.0;  // ACA rank per kernel (measured mean 7-8, max 11-13)

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

}  // namespace

HMatrixSizes hmatrix_sizes(const Mesh& mesh, const QuadratureOptions& q, const HMatrixOptions& options) {
  HMatrixSizes s;
  for (int d = 0; d < mesh.a_count; ++d) {
    const ClusterTree tree = build_cluster_tree(mesh, mesh.domain_segments[d], options.leaf_size);
    const BlockPartition part = partition_blocks(tree, options.eta, 1.01 * q.near_factor);
    for (const BlockPair& bp : part.near) {
      const Cluster& r = tree.nodes[bp.row];
      const Cluster& c = tree.nodes[bp.col];
      if (r.begin > c.begin) continue;  // counted with its mirror, as near_pairs() fills it
      const long nr = r.size(), nc = c.size();
      s.near_pairs += bp.row == bp.col ? nr * (nr + 1) / 2 : nr * nc;
    }
    s.admissible_blocks += static_cast<long>(part.admissible.size());
    for (const BlockPair& bp : part.admissible) {
      s.lowrank_rows += 2.0 * (tree.nodes[bp.row].size() + tree.nodes[bp.col].size());
    }
  }
  return s;
}

MemoryEstimate estimate_system_memory(const Mesh& mesh, double lambda_nm, const BemOptions& options, int rhs,
                                      int far_directions) {
  const double n = mesh.unknowns();
  MemoryEstimate e;
  char job[200];
  std::snprintf(job, sizeof job, "bem %s solve of %s unknowns (%zu segments) at %g nm",
                std::string(method_name(options.method)).c_str(), number(n).c_str(), mesh.segments.size(), lambda_nm);
  e.job = job;
  const std::string ppw = "points_per_wavelength (now " + number(options.points_per_wavelength) + ")";
  // each of the right-hand sides solved together keeps its restart + 1 Krylov vectors and restart
  // preconditioned ones (flexible GMRES, gmres_lockstep), plus the block's products and warm start
  const double together = std::max(1, std::min(options.gmres_block, std::max(rhs, 1)));
  const double krylov = 16.0 * n * together * (2.0 * options.gmres_restart + 5.0);
  if (options.method == BemOptions::Method::hmatrix) {
    const HMatrixSizes s = hmatrix_sizes(mesh, options.quadrature, options.hmatrix);
    const double entries = kEntriesPerNearPair * static_cast<double>(s.near_pairs);
    e.add("near field", entries * kSparseEntryBytes);
    e.add("ACA blocks", 3.0 * 16.0 * kMaxRank * s.lowrank_rows);
    if (options.hmatrix.preconditioner == HMatrixOptions::Preconditioner::dense_single) {
      e.add("dense single-precision LU 8 N^2", 8.0 * n * n);
      e.lower_with = {ppw, "preconditioner: near_field"};
    } else if (options.hmatrix.preconditioner == HMatrixOptions::Preconditioner::hodlr) {
      e.add("HODLR factor (rank <= hodlr_max_rank)", hodlr_memory_bound_bytes(n, options.hodlr));
      e.lower_with = {ppw, "hodlr_max_rank (now " + number(options.hodlr.max_rank) + ")"};
    } else {
      e.add("preconditioner copy of the near field", entries * kSparseEntryBytes);
      e.add("sparse LU of the near field", entries * lu_bytes_per_entry(n));
      e.lower_with = {ppw, "leaf_size (now " + number(options.hmatrix.leaf_size) + ")",
                      "preconditioner_factor (now " + number(options.hmatrix.preconditioner_factor) +
                          "; e.g. 10 keeps fewer near entries, more iterations)"};
    }
    e.add("GMRES Krylov basis", krylov);
  } else {
    e.add("dense matrix 16 N^2", 16.0 * n * n);
    if (options.method == BemOptions::Method::gmres) {
      // the near-field LU of method gmres (pairs closer than 8 h): bounded like the H-matrix's
      const HMatrixSizes s = hmatrix_sizes(mesh, options.quadrature, options.hmatrix);
      const double entries = kEntriesPerNearPair * static_cast<double>(s.near_pairs);
      e.add("near-field LU", entries * (kSparseEntryBytes + lu_bytes_per_entry(n)));
      e.add("GMRES Krylov basis", krylov);
    }
    e.lower_with = {ppw, "method: hmatrix (compressed matrix, no N^2 storage)"};
  }
  e.add("right-hand sides and solutions", 3.0 * 16.0 * n * rhs);
  // method hmatrix: built 32 directions at a time (bem_solver.cpp, kFarFieldChunk)
  const bool chunked = options.method == BemOptions::Method::hmatrix;
  const double chunk = chunked ? std::min(far_directions, 32) : far_directions;
  e.add(chunked ? "far-field operator (32 directions at a time)" : "far-field operator", 48.0 * n * chunk);
  // E = F X packs blocks of F (Eigen's GEMM workspace): 21.9 MB beside F's 86.4 MB measured with
  // heaptrack on the keratin cylinder (1 264 unknowns, 1 424 directions); bounded by a third of F.
  e.add("far-field product workspace", 16.0 * n * chunk);
  e.add("mesh and bookkeeping", 64.0 * n);
  e.lower_with.push_back("a narrower segment (outline.width_um / bench --width-um)");
  e.lower_with.push_back("fewer incident azimuths");
  return e;
}

}  // namespace plumage::bem
