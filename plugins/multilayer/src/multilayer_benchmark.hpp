// benchmark "multilayer": time per (surface point, wavelength) of the batched stack reflection
// (`plumage bench multilayer`, docs/benchmarks.md section "multilayer").
#pragma once

#include "plumage/benchmark.hpp"
#include "plumage/param_table.hpp"

namespace plumage::multilayer {

struct MultilayerBenchParams {
  int layers = 30;
  int points = 1000;
  int wavelengths = 50;
  int repeats = 5;
};

const ParamTable<MultilayerBenchParams>& multilayer_bench_table();

class MultilayerBenchmark final : public Benchmark {
 public:
  explicit MultilayerBenchmark(const MultilayerBenchParams& params) : params_(params) {}
  Report run(const Options& options) const override;

 private:
  MultilayerBenchParams params_;
};

}  // namespace plumage::multilayer
