// Benchmark "bsdf" (`plumage bench bsdf --material x.plm`): C++ throughput of the feather BSDF
// (feather_bsdf.hpp) on a batch of (ω_o, λ) samples at one incident direction, the mean BRDF and
// instance 0, one thread: the reference the Python package's batch evaluation is measured
// against (python/bench/bench_python.py). The incident state is looked up once per wavelength
// bin, as a renderer does for one ω_i (incident_bin with the shared IncidentGeometry).
#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "plumage/bench_record.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/conventions.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/param_table.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/random.hpp"

namespace plumage {

namespace {

struct BsdfBenchParams {
  std::string material;
  int samples = 1000000;
  double theta_deg = 30.0, phi_deg = -20.0;
};

const ParamTable<BsdfBenchParams>& bsdf_bench_params() {
  static const auto table =
      ParamTable<BsdfBenchParams>{}
          .text("material", &BsdfBenchParams::material, required, "feather material (.plm) to evaluate")
          .integer("samples", &BsdfBenchParams::samples, "1", 1000000, Limits::at_least(1), "(w_o, lambda) samples per pass")
          .number("theta_deg", &BsdfBenchParams::theta_deg, "deg", 30.0, Limits::closed(-89.0, 89.0), "incident theta_i")
          .number("phi_deg", &BsdfBenchParams::phi_deg, "deg", -20.0, Limits::closed(-89.0, 89.0), "incident phi_i");
  return table;
}

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Uniform in [0, 1) from a counter (splitmix64): the same samples every run.
double uniform(std::uint64_t k) { return static_cast<double>(splitmix64(k) >> 11) * 0x1.0p-53; }

class BsdfBenchmark final : public Benchmark {
 public:
  explicit BsdfBenchmark(BsdfBenchParams params) : params_(std::move(params)) {}

  Report run(const Options& options) const override {
    auto material = std::make_shared<const FeatherMaterial>(read_feather_material(params_.material));
    const FeatherBsdf bsdf(material);
    const std::size_t n = static_cast<std::size_t>(params_.samples);
    // ω_o uniform over the upper hemisphere, λ uniform over the material's bins.
    std::vector<Direction> wo(n);
    std::vector<double> lambda(n);
    const double lo = material->lambda_nm.front(), span = material->lambda_nm.back() + material->bin_width_nm - lo;
    for (std::size_t k = 0; k < n; ++k) {
      const double z = uniform(3 * k), a = 2.0 * kPi * uniform(3 * k + 1), r = std::sqrt(1.0 - z * z);
      wo[k] = {r * std::cos(a), r * std::sin(a), z};
      lambda[k] = lo + span * uniform(3 * k + 2);
    }
    const Direction wi = direction_from_angles(params_.theta_deg * kPi / 180.0, params_.phi_deg * kPi / 180.0);
    std::ostringstream md;
    md << "## bsdf\n\n"
       << "Feather BSDF evaluation (`FeatherBsdf::eval`, one thread) of " << n << " (ω_o, λ) samples of "
       << material->label << " (" << material->fidelity << ") at (θ_i, φ_i) = (" << params_.theta_deg << "°, "
       << params_.phi_deg << "°), the incident state looked up once per wavelength bin; best of 3 passes. "
       << "CPU time of the evaluating thread.\n\n"
       << "| machine | command | date | what | samples | CPU s | Msamples/s (CPU) | wall s |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    const std::string command = options.command.empty() ? "plumage bench bsdf --material " + params_.material : options.command;
    for (const bool instance : {false, true}) {
      double best_cpu = 1e300, best_wall = 1e300, sum = 0.0;
      for (int pass = 0; pass < 3; ++pass) {
        const double c0 = thread_cpu_s();
        const auto t0 = std::chrono::steady_clock::now();
        sum = evaluate(bsdf, wi, wo, lambda, instance);
        best_wall = std::min(best_wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        best_cpu = std::min(best_cpu, thread_cpu_s() - c0);
      }
      if (!std::isfinite(sum) && options.progress) options.progress("warning: non-finite BSDF values");
      md << std::fixed << std::setprecision(3) << "| " << machine_description() << " | `" << command << "` | "
         << today_iso() << " | " << (instance ? "instance 0" : "mean BRDF") << " | " << n << " | " << best_cpu << " | "
         << static_cast<double>(n) / best_cpu * 1e-6 << " | " << best_wall << " |\n";
    }
    return {"bsdf", md.str()};
  }

 private:
  // Σ f over the batch (kept so that the evaluations cannot be optimised away).
  static double evaluate(const FeatherBsdf& bsdf, const Direction& wi, const std::vector<Direction>& wo,
                         const std::vector<double>& lambda, bool instance) {
    const FeatherBsdf::IncidentGeometry geometry = bsdf.incident_geometry(wi);
    std::vector<std::optional<FeatherBsdf::Incident>> per_bin(bsdf.material().lambda_nm.size());
    double sum = 0.0;
    for (std::size_t k = 0; k < wo.size(); ++k) {
      auto& in = per_bin[bsdf.material().wavelength_bin(lambda[k])];
      if (!in) in = bsdf.incident_bin(bsdf.material().wavelength_bin(lambda[k]), geometry);
      sum += instance ? bsdf.eval(*in, wo[k], 0) : bsdf.eval(*in, wo[k]);
    }
    return sum;
  }

  BsdfBenchParams params_;
};

}  // namespace

void register_bsdf_benchmark(PluginRegistry& registry) {
  registry.builtin_registrar().add<Benchmark>(
      {.type = "bsdf",
       .version = "1.0.0",
       .summary = "feather BSDF: mean BRDF and instance evaluations per second (one thread)",
       .params = bsdf_bench_params().specs()},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<BsdfBenchmark>(bsdf_bench_params().read(params));
      });
}

}  // namespace plumage
