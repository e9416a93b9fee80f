// Scene feather materials: cache lookup, else preview characterisation (material_cache.hpp).
#include "material_cache.hpp"

#include "plumage/diagnostics.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <optional>

#include "characterize_run.hpp"
#include "plumage/species_config.hpp"

namespace plumage::cli {

namespace fs = std::filesystem;

namespace {

bool matches(const FeatherMaterial& m, const std::string& label, const std::string& hash, const std::string& fidelity) {
  return m.label == label && m.config_hash == hash && m.fidelity == fidelity;
}

// A matching material in `dir`: the canonical name first, then any <species>-<variant>*.plm.
std::optional<fs::path> find_cached(const fs::path& dir, const fs::path& canonical, const std::string& prefix,
                                    const std::string& label, const std::string& hash, const std::string& fidelity) {
  auto ok = [&](const fs::path& f) {
    try {
      return matches(read_feather_material(f), label, hash, fidelity);
    } catch (const std::exception&) {
      return false;  // unreadable or another format: not a cache hit
    }
  };
  if (fs::exists(canonical) && ok(canonical)) return canonical;
  if (!fs::is_directory(dir)) return std::nullopt;
  std::vector<fs::path> candidates;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && e.path().extension() == ".plm" && name.rfind(prefix, 0) == 0) candidates.push_back(e.path());
  }
  std::sort(candidates.begin(), candidates.end());  // deterministic choice
  for (const auto& f : candidates)
    if (f != canonical && ok(f)) return f;
  return std::nullopt;
}

std::shared_ptr<const FeatherBsdf> load_bsdf(const fs::path& file, double transmission_albedo) {
  auto material = std::make_shared<const FeatherMaterial>(read_feather_material(file));
  // A material characterised with warnings passes them on to what is rendered with it.
  if (!material->warnings.empty()) {
    std::string first = material->warnings.substr(0, material->warnings.find('\n'));
    warn("material.warnings", file.string() + " was characterised with warnings (first: " + first + ")");
  }
  FeatherBsdfOptions options;
  options.transmission_albedo = transmission_albedo;
  return std::make_shared<const FeatherBsdf>(material, options);
}

}  // namespace

ResolvedFeather resolve_feather_material(const FeatherMaterialRequest& q, AppContext& context, const fs::path& cache_dir,
                                         bool allow_characterize, bool quiet) {
  ResolvedFeather r;
  if (!q.file.empty()) {
    r.file = q.file;
    r.bsdf = load_bsdf(q.file, q.transmission_albedo);
    return r;
  }
  const SpeciesConfig config = load_species_config(q.species_config, context.registry(), q.variant);
  const std::string label = config.species + "/" + config.variant;
  const std::string prefix = config.species + "-" + config.variant;
  auto canonical = [&](const std::string& fidelity) {
    return cache_dir / (prefix + "-" + fidelity + "-" + config.content_hash + ".plm");
  };
  std::optional<fs::path> hit = find_cached(cache_dir, canonical(q.fidelity), prefix, label, config.content_hash, q.fidelity);
  if (!hit && q.fidelity == "preview")
    hit = find_cached(cache_dir, canonical("production"), prefix, label, config.content_hash, "production");
  if (!hit && q.fidelity == "production") {
    if (!quiet)
      std::cerr << "warning: no production material for " << label << " in " << cache_dir.string()
                << " (make one with `plumage characterize " << q.species_config.string() << " --variant " << config.variant
                << " --fidelity production --out " << canonical("production").string() << "`); using preview fidelity\n";
    hit = find_cached(cache_dir, canonical("preview"), prefix, label, config.content_hash, "preview");
  }
  if (hit) {
    if (!quiet) std::cerr << "material " << label << ": " << hit->string() << "\n";
    r.file = *hit;
    r.bsdf = load_bsdf(*hit, q.transmission_albedo);
    return r;
  }
  const fs::path out = canonical("preview");
  if (!allow_characterize) {
    throw UsageError("no cached material for " + label + " (" + q.fidelity + ") in " + cache_dir.string() +
                     "; make it with `plumage characterize " + q.species_config.string() + " --variant " + config.variant +
                     " --fidelity preview --out " + out.string() + "`");
  }
  fs::create_directories(cache_dir);
  PreparationOptions preparation = context.preparation();
  if (quiet) preparation.progress = nullptr;
  const CharacterizeRun run = characterize_to_file(config, preset_settings(config, "preview"), out, quiet, preparation);
  if (!quiet)
    std::cerr << "material " << label << ": characterised at preview fidelity in " << std::fixed << std::setprecision(1)
              << run.wall_s << " s wall, " << run.cpu_s << " s CPU -> " << out.string() << "\n";
  r.file = out;
  r.characterised = true;
  r.characterise_cpu_s = run.cpu_s;
  r.characterise_wall_s = run.wall_s;
  r.bsdf = load_bsdf(out, q.transmission_albedo);
  return r;
}

}  // namespace plumage::cli
