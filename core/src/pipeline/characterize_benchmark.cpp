// Benchmark "characterize" (`plumage bench characterize`, issue 26): one characterisation end to
// end through the library's characterize() (plumage/characterize.hpp) — the models' one-time
// work, the instances' preparation, every work group (solves and fits), the assembly and the
// .plm written to a temporary folder — timed as wall and process CPU (all threads). The size is
// the preset's (`fidelity`) with the characterisation's own overrides (--instances, --grid,
// --lambda-nm: the same parameter table as `plumage characterize`), so a reduced run can stand
// in for the half-hour production one.
//
// With `reference` (a .plm of the same settings, e.g. written by an earlier build with `keep`),
// the fitted parameters are compared node by node: for every field the largest |new − old|
// relative to the field's largest |old| over all nodes (so φ's near 0 do not divide by 0), the
// "fitted parameters change by < 1e-4 relative" criterion of issue 26.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <array>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "plumage/bench_record.hpp"
#include "plumage/benchmark.hpp"
#include "plumage/characterize.hpp"
#include "plumage/characterize_settings.hpp"
#include "plumage/error.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/fidelity.hpp"
#include "plumage/param_table.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

namespace {

namespace fs = std::filesystem;

struct CharacterizeBenchParams {
  std::string config;
  std::string variant;
  std::string fidelity;
  std::string keep;       // copy the material here ("" = do not keep)
  std::string reference;  // compare the fitted parameters with this .plm ("" = no comparison)
};

const ParamTable<CharacterizeBenchParams>& characterize_bench_params() {
  static const auto table =
      ParamTable<CharacterizeBenchParams>{}
          .text("config", &CharacterizeBenchParams::config, "configs/species/rockdove.yaml", "species config")
          .text("variant", &CharacterizeBenchParams::variant, "", "variant (\"\": the file's)")
          .text("fidelity", &CharacterizeBenchParams::fidelity, "preview", "fidelity preset (preview | production | ...)")
          .text("keep", &CharacterizeBenchParams::keep, "", "copy the material written to this .plm (\"\": none)")
          .text("reference", &CharacterizeBenchParams::reference, "",
                "compare the fitted parameters with this .plm of the same settings (\"\": none)");
  return table;
}

// Both tables' rows: the benchmark's own and the characterisation overrides.
std::vector<ParamSpec> characterize_bench_specs() {
  std::vector<ParamSpec> specs = characterize_bench_params().specs();
  for (ParamSpec& s : characterize_overrides_table().specs()) specs.push_back(std::move(s));
  return specs;
}

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A fresh folder under the system's temporary directory, removed when it goes out of scope.
class TempFolder {
 public:
  TempFolder() {
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = fs::temp_directory_path() / ("plumage-bench-characterize-" + std::to_string(::getpid()) + "-" +
                                         std::to_string(stamp));
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Per field: max |new − old| over nodes / max |old| over nodes.
struct ParameterChange {
  std::array<double, kMaterialParameters> relative{};
  double worst = 0.0;
  std::string worst_field;
};

ParameterChange compare_materials(const FeatherMaterial& now, const FeatherMaterial& before, const std::string& file) {
  if (now.nodes.size() != before.nodes.size() || now.grid != before.grid || now.lambda_nm != before.lambda_nm) {
    throw ConfigError({file, 0, 0}, "reference", "the reference material has other settings (grid, wavelengths)");
  }
  ParameterChange c;
  for (int f = 0; f < kMaterialParameters; ++f) {
    double diff = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < now.nodes.size(); ++k) {
      const double a = now.nodes[k].*kMaterialFields[f], b = before.nodes[k].*kMaterialFields[f];
      diff = std::max(diff, std::abs(a - b));
      scale = std::max(scale, std::abs(b));
    }
    c.relative[f] = scale > 0.0 ? diff / scale : diff;
    if (c.relative[f] >= c.worst) c.worst = c.relative[f], c.worst_field = kMaterialFieldNames[f];
  }
  return c;
}

class CharacterizeBenchmark final : public Benchmark {
 public:
  CharacterizeBenchmark(const PluginRegistry& registry, CharacterizeBenchParams params, CharacterizeOverrides overrides)
      : registry_(registry), p_(std::move(params)), overrides_(std::move(overrides)) {}

  Report run(const Options& options) const override {
    const SpeciesConfig config = load_species_config(p_.config, registry_, p_.variant);
    const CharacterizeSettings s = characterize_settings(config, registry_, p_.fidelity, overrides_);
    std::optional<FeatherMaterial> reference;
    if (!p_.reference.empty()) reference = read_feather_material(p_.reference);  // before any work
    const TempFolder folder;
    const fs::path out = folder.path() / "material.plm";
    CharacterizeOptions o;
    o.preparation = options.preparation;
    o.distribution = CharacterizeOptions::Distribution::single_process;
    if (options.progress) options.progress(s.label + ": characterising into " + out.string());
    const double cpu0 = process_cpu_s();
    const auto wall0 = std::chrono::steady_clock::now();
    const CharacterizeResult r = characterize(config, s, out, o);
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const double cpu_s = process_cpu_s() - cpu0;
    const std::uintmax_t bytes = fs::file_size(out);
    std::optional<ParameterChange> change;
    if (reference) change = compare_materials(read_feather_material(out), *reference, p_.reference);
    if (!p_.keep.empty()) fs::copy_file(out, p_.keep, fs::copy_options::overwrite_existing);
    return {"bench-characterize:" + config.species + "-" + config.variant + ":" + s.fidelity,
            markdown(s, r, wall_s, cpu_s, bytes, change, options)};
  }

 private:
  std::string markdown(const CharacterizeSettings& s, const CharacterizeResult& r, double wall_s, double cpu_s,
                       std::uintmax_t bytes, const std::optional<ParameterChange>& change, const Options& options) const {
    const std::string command = options.command.empty() ? "plumage bench characterize --config " + p_.config : options.command;
    const double cores = std::max(1u, std::thread::hardware_concurrency());
    std::ostringstream md;
    md << "## bench characterize " << s.label << " (" << s.fidelity << ")\n\n"
       << "`plumage bench characterize`: the library's characterize() end to end (models' one-time work, "
          "instances, "
       << s.group_count() << " work groups of solves and fits, assembly, the .plm written to a temporary "
                             "folder): "
       << s.lambda_nm.size() << " wavelengths x " << s.grid << " x " << s.grid << " incident nodes, " << s.instances
       << " instances, " << s.pattern_samples << " pattern + " << s.projected_samples
       << " projected directions. Wall and process CPU (all threads) around the call; CPU / cores is what "
          "an idle machine would take.\n\n"
       << std::fixed << std::setprecision(1)
       << "| machine | command | date | wall | CPU | CPU / cores | CPU per group | file size | fitted parameters vs reference |\n"
       << "|---|---|---|---|---|---|---|---|---|\n"
       << "| " << machine_description() << " | `" << command << "` | " << today_iso() << " | " << wall_s << " s | "
       << cpu_s << " s | " << cpu_s / cores << " s | " << std::setprecision(3)
       << cpu_s / static_cast<double>(std::max<std::size_t>(1, r.plan.todo)) << " s | " << std::setprecision(2)
       << static_cast<double>(bytes) / 1e6 << " MB | ";
    if (change) {
      md << std::scientific << std::setprecision(2) << "max " << change->worst << " (" << change->worst_field << ")";
    } else {
      md << "-";
    }
    md << " |\n";
    if (change) {
      md << "\nRelative change per fitted parameter (max |new - old| over nodes / max |old|): ";
      for (int f = 0; f < kMaterialParameters; ++f) {
        md << (f ? ", " : "") << kMaterialFieldNames[f] << " " << change->relative[f];
      }
      md << ".\n";
    }
    return md.str();
  }

  const PluginRegistry& registry_;
  CharacterizeBenchParams p_;
  CharacterizeOverrides overrides_;
};

}  // namespace

void register_characterize_benchmark(PluginRegistry& registry) {
  registry.builtin_registrar().add<Benchmark>(
      {.type = "characterize",
       .version = "1.0.0",
       .summary = "a characterisation end to end (wall and process CPU), optionally reduced (--grid, --lambda-nm, "
                  "--instances) and compared with an earlier material",
       .params = characterize_bench_specs()},
      [](const ParamView& params, const PluginContext& context) {
        if (!context.registry) throw Error("benchmark 'characterize': needs a registry in its context");
        CharacterizeBenchParams own = characterize_bench_params().read(params);
        CharacterizeOverrides overrides = characterize_overrides_table().read(params);
        return std::make_unique<CharacterizeBenchmark>(*context.registry, std::move(own), std::move(overrides));
      });
}

}  // namespace plumage
