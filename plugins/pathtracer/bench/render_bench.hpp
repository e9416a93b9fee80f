// Benchmark "render" of the pathtracer plug-in (benchmark.hpp): `plumage bench render [--size N]
// [--spp N] [--material FILE.plm] [--traversal-rays N] [--lod auto|mean|instance] [--out PREFIX]
// [--record docs/benchmarks.md]`, section "render" of docs/benchmarks.md.
#pragma once

#include <memory>
#include <string>

#include "plumage/benchmark.hpp"
#include "plumage/param_table.hpp"
#include "settings.hpp"

namespace plumage::pathtracer {

struct RenderBenchParams {
  int size = 1024;
  int spp = 64;
  std::string material;
  int traversal_rays = 4;
  LevelOfDetail lod = LevelOfDetail::automatic;
  std::string out;  // optional EXR + PNG of the render
};

const ParamTable<RenderBenchParams>& render_bench_table();

class RenderBenchmark final : public Benchmark {
 public:
  explicit RenderBenchmark(RenderBenchParams params) : params_(std::move(params)) {}
  Report run(const Options& options) const override;

 private:
  RenderBenchParams params_;
};

// The factory: the table's values, and the material file must exist (bad input, before any work).
std::unique_ptr<RenderBenchmark> make_render_benchmark(const ParamView& params);

}  // namespace plumage::pathtracer
