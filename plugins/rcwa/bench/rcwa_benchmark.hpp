// Benchmark "rcwa" (`plumage bench rcwa`): the Fourier modal method table builder beside the
// FDTD's "fdtd" benchmark — one (λ, ω_i) entry at production settings (both polarizations, one
// thread, mean over a sweep of entries) and the whole production table of one crystal on the
// builder's threads; its report is the "rcwa" section of docs/benchmarks.md.
#pragma once

#include <string>

#include "plumage/benchmark.hpp"
#include "plumage/param_table.hpp"

namespace plumage::rcwa {

struct BenchParams {
  std::string config;  // crystal config
  int n_lambda = 0, n_theta = 0, n_phi = 0;  // 0: the production table grid
  int threads = 2;
  int harmonics = 0, slices_per_row = 0;  // 0: the production settings of the cell
  bool skip_table = false;
};
const ParamTable<BenchParams>& bench_params();

class RcwaBenchmark final : public Benchmark {
 public:
  explicit RcwaBenchmark(BenchParams params) : params_(std::move(params)) {}
  Report run(const Options& options) const override;

 private:
  BenchParams params_;
};

}  // namespace plumage::rcwa
