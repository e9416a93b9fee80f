// Benchmark "fdtd" (`plumage bench fdtd`): the periodic FDTD table builder — one (λ, angle)
// solve at production resolution (both polarizations), one broadband fixed-Bloch-k run, and the
// whole production table of one crystal (by default kProductionTableGrid, 201 λ × 20 cos θ × 50
// cos φ × 2 polarizations: the parameter table's defaults); its
// report is the "fdtd" section of docs/benchmarks.md.
#pragma once

#include <string>

#include "plumage/benchmark.hpp"
#include "plumage/param_table.hpp"

namespace plumage::fdtd_table {

struct BenchParams {
  std::string config;  // crystal config
  int n_lambda = 50, n_theta = 20, n_phi = 50;
  double kz_min = 0.25;
  bool skip_table = false;
  std::string out;  // also save the whole table here (e.g. the lazy cache's production file)
};
const ParamTable<BenchParams>& bench_params();

class FdtdBenchmark final : public Benchmark {
 public:
  explicit FdtdBenchmark(BenchParams params) : params_(std::move(params)) {}
  Report run(const Options& options) const override;

 private:
  BenchParams params_;
};

}  // namespace plumage::fdtd_table
