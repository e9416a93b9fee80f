// The material store (material_store.hpp): cache lookup, else a preview characterisation.
#include "plumage/material_store.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <iomanip>
#include <sstream>

#include "plumage/characterize.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

bool matches(const FeatherMaterialHeader& m, const std::string& label, const std::string& hash, const std::string& fidelity) {
  return m.label == label && m.config_hash == hash && m.fidelity == fidelity;
}

// The matching materials in `dir` by their headers: the canonical name first, then any
// <species>-<variant>*.plm in name order.
std::vector<fs::path> find_cached(const fs::path& dir, const fs::path& canonical, const std::string& prefix,
                                  const std::string& label, const std::string& hash, const std::string& fidelity) {
  auto ok = [&](const fs::path& f) {
    try {
      return matches(read_feather_material_header(f), label, hash, fidelity);  // the header only
    } catch (const std::exception&) {
      return false;  // unreadable or another format: not a cache hit
    }
  };
  std::vector<fs::path> hits;
  if (fs::exists(canonical) && ok(canonical)) hits.push_back(canonical);
  if (!fs::is_directory(dir)) return hits;
  std::vector<fs::path> candidates;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && e.path().extension() == ".plm" && name.rfind(prefix, 0) == 0) candidates.push_back(e.path());
  }
  std::sort(candidates.begin(), candidates.end());  // deterministic choice
  for (const auto& f : candidates)
    if (f != canonical && ok(f)) hits.push_back(f);
  return hits;
}

}  // namespace

std::shared_ptr<const FeatherMaterial> load_material(const fs::path& file) {
  auto material = std::make_shared<const FeatherMaterial>(read_feather_material(file));
  // A material characterised with warnings passes them on to what is made with it.
  if (!material->warnings.empty()) {
    std::string first = material->warnings.substr(0, material->warnings.find('\n'));
    warn("material.warnings", file.string() + " was characterised with warnings (first: " + first + ")");
  }
  return material;
}

MaterialStore::MaterialStore(const PluginRegistry& registry, MaterialStoreOptions options)
    : registry_(registry), options_(std::move(options)) {}

ResolvedMaterial MaterialStore::resolve(const MaterialRequest& q) const {
  auto status = [&](const std::string& line) {
    if (options_.status) options_.status(line);
  };
  ResolvedMaterial r;
  if (!q.file.empty()) {
    r.file = q.file;
    r.material = load_material(q.file);
    return r;
  }
  const fs::path& dir = options_.directory;
  const SpeciesConfig config = load_species_config(q.species_config, registry_, q.variant);
  const std::string label = config.species + "/" + config.variant;
  const std::string prefix = config.species + "-" + config.variant;
  auto canonical = [&](const std::string& fidelity) {
    return dir / (prefix + "-" + fidelity + "-" + config.content_hash + ".plm");
  };
  std::vector<fs::path> hits = find_cached(dir, canonical(q.fidelity), prefix, label, config.content_hash, q.fidelity);
  if (hits.empty() && q.fidelity == "preview")
    hits = find_cached(dir, canonical("production"), prefix, label, config.content_hash, "production");
  if (hits.empty() && q.fidelity == "production") {
    status("warning: no production material for " + label + " in " + dir.string() + " (make one with `plumage characterize " +
           q.species_config.string() + " --variant " + config.variant + " --fidelity production --out " +
           canonical("production").string() + "`); using preview fidelity");
    hits = find_cached(dir, canonical("preview"), prefix, label, config.content_hash, "preview");
  }
  for (const fs::path& hit : hits) {
    try {
      r.material = load_material(hit);  // the tables and checksum, read only now
    } catch (const Error& e) {
      status(std::string("material ") + label + ": skipping a damaged file (" + e.what() + ")");
      continue;
    }
    status("material " + label + ": " + hit.string());
    r.file = hit;
    return r;
  }
  const fs::path out = canonical("preview");
  if (!options_.allow_characterize) {
    throw ConfigError(q.where, "", "no cached material for " + label + " (" + q.fidelity + ") in " + dir.string() +
                                       "; make it with `plumage characterize " + q.species_config.string() + " --variant " +
                                       config.variant + " --fidelity preview --out " + out.string() + "`");
  }
  fs::create_directories(dir);
  const CharacterizeSettings s = characterize_settings(config, "preview");
  CharacterizeOptions o;
  o.preparation = options_.preparation;
  o.distribution = CharacterizeOptions::Distribution::single_process;
  o.other_journal = CharacterizeOptions::OtherJournal::restart;
  o.progress = options_.progress;
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  characterize(config, s, out, o, [&](const CharacterizePlan& plan) {
    std::ostringstream line;
    line << s.label << ": characterising at " << s.fidelity << " fidelity, " << s.lambda_nm.size() << " wavelengths x "
         << s.grid << " x " << s.grid << " incident nodes, " << s.instances << " instances";
    if (plan.resumed) line << ", resuming (" << plan.resumed << " groups in " << plan.journal.string() << ")";
    status(line.str());
  });
  r.characterise_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.characterise_cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  std::ostringstream line;
  line << "material " << label << ": characterised at preview fidelity in " << std::fixed << std::setprecision(1)
       << r.characterise_wall_s << " s wall, " << r.characterise_cpu_s << " s CPU -> " << out.string();
  status(line.str());
  r.file = out;
  r.characterised = true;
  r.material = load_material(out);
  return r;
}

}  // namespace plumage
