// The multilayer benchmark: a bronzewing-like stack (alternating keratin and melanin with
// per-point thickness jitter), each surface point at its own angle, every wavelength per point,
// through the plug-in's batch API (LocalReflection::reflect, the path the solvers take), one
// thread; best and median of the timed runs.
#include "multilayer_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <random>
#include <sstream>
#include <vector>

#include "multilayer_reflection.hpp"
#include "plumage/bench_record.hpp"
#include "plumage/diagnostics.hpp"

namespace plumage::multilayer {

const ParamTable<MultilayerBenchParams>& multilayer_bench_table() {
  using P = MultilayerBenchParams;
  static const auto table =
      ParamTable<P>{}
          .integer("layers", &P::layers, "1", 30, Limits::at_least(1), "layers in the stack")
          .integer("points", &P::points, "1", 1000, Limits::at_least(1), "surface points (distinct stacks)")
          .integer("wavelengths", &P::wavelengths, "1", 50, Limits::at_least(1),
                   "wavelengths per point (400 nm on in 6 nm steps)")
          .integer("repeats", &P::repeats, "1", 5, Limits::at_least(1), "timed runs");
  return table;
}

Benchmark::Report MultilayerBenchmark::run(const Options& options) const {
  const MultilayerBenchParams& b = params_;
  const MultilayerReflection model;
  std::mt19937_64 rng(20241203);
  std::uniform_real_distribution<double> jitter(0.9, 1.1), angle(0.0, deg_to_rad(80.0));
  std::vector<LayerProfile> profiles(static_cast<std::size_t>(b.points));
  std::vector<double> angles(profiles.size());
  for (std::size_t p = 0; p < profiles.size(); ++p) {
    for (int j = 0; j < b.layers; ++j) {
      const bool melanin = j % 2 == 1;
      profiles[p].layers.push_back({melanin ? Material::melanin() : Material::keratin(),
                                    (melanin ? 90.0 : 100.0) * jitter(rng)});
    }
    angles[p] = angle(rng);
  }
  std::vector<LocalReflection::Request> requests;
  for (std::size_t p = 0; p < profiles.size(); ++p) {
    for (int w = 0; w < b.wavelengths; ++w) requests.push_back({400.0 + 6.0 * w, {0.0, angles[p]}, &profiles[p]});
  }
  std::vector<JonesReflection> out(requests.size());
  std::vector<double> seconds;
  double checksum = 0;
  for (int r = 0; r < b.repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    model.reflect(requests, out);
    const auto t1 = std::chrono::steady_clock::now();
    seconds.push_back(std::chrono::duration<double>(t1 - t0).count());
    checksum += std::norm(out[out.size() / 2].ss);
    if (options.progress) {
      std::ostringstream line;
      line << "run " << r + 1 << " of " << b.repeats << ": " << seconds.back() << " s";
      options.progress(line.str());
    }
  }
  if (checksum != checksum) warn("multilayer.benchmark_non_finite", "bench multilayer: non-finite reflection");
  std::sort(seconds.begin(), seconds.end());
  const double per_eval_ns = seconds.front() / static_cast<double>(requests.size()) * 1e9;
  const double median_ns = seconds[seconds.size() / 2] / static_cast<double>(requests.size()) * 1e9;

  // The command column names every setting but the repeat count, so a row can be reproduced.
  std::ostringstream command;
  command << "plumage bench multilayer --layers " << b.layers << " --points " << b.points << " --wavelengths "
          << b.wavelengths;
  std::ostringstream md;
  md << std::fixed << std::setprecision(1);
  md << "## multilayer\n\n"
     << "Time per (surface point, wavelength) for a " << b.layers
     << "-layer keratin/melanin stack, both polarizations (r_s and r_p), one thread, through the "
        "plug-in's batch API (`LocalReflection::reflect`), " << requests.size()
     << " evaluations per run (" << b.points << " points x " << b.wavelengths
     << " wavelengths, each point at its own angle), best and median of " << b.repeats << " runs.\n\n"
     << "| machine | command | date | best ns/eval | median ns/eval | goal |\n"
     << "|---|---|---|---|---|---|\n"
     << "| " << machine_description() << " | `" << command.str() << "` | " << today_iso() << " | " << per_eval_ns
     << " | " << median_ns << " | <= 1000 ns |\n";
  return {"multilayer", md.str()};
}

}  // namespace plumage::multilayer
