// The material store (material_store.hpp): materials found by their key in .plm headers, else
// characterised at preview fidelity and cached.
#include "plumage/atomic_file.hpp"
#include "plumage/material_store.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <iomanip>
#include <set>
#include <sstream>

#include "plumage/characterize.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/material_warnings.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

// The .plm files of a species variant in the store's folder: `canonical` first, then every
// <species>-<variant>*.plm in name order, each with its header (unreadable ones left out).
std::vector<std::pair<fs::path, FeatherMaterialHeader>> candidates(const fs::path& dir, const std::string& prefix,
                                                                   const fs::path& canonical) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (fs::is_directory(dir, ec)) {
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (e.is_regular_file() && e.path().extension() == ".plm" && name.rfind(prefix, 0) == 0) files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end(), [&](const fs::path& a, const fs::path& b) {
    return std::make_pair(a != canonical, a) < std::make_pair(b != canonical, b);
  });
  std::vector<std::pair<fs::path, FeatherMaterialHeader>> out;
  for (const fs::path& f : files) {
    try {
      out.emplace_back(f, read_feather_material_header(f));  // the header only
    } catch (const std::exception&) {
      // unreadable or another format: not a candidate
    }
  }
  return out;
}

// The parts of `wanted` (key text lines, up to their digest) that a stale key lacks.
std::string key_difference(const std::string& wanted, const std::string& stale) {
  if (stale.empty()) return "it has no key (made before keyed materials)";
  std::set<std::string> have;
  std::istringstream s(stale);
  for (std::string line; std::getline(s, line);) have.insert(line);
  std::string parts;
  std::istringstream w(wanted);
  for (std::string line; std::getline(w, line);) {
    if (have.count(line)) continue;
    const auto a = line.find(' '), b = a == std::string::npos ? a : line.find(' ', a + 1);
    const std::string part = line.rfind("file ", 0) == 0 || line.rfind("model ", 0) == 0 ? line.substr(0, b) : line.substr(0, a);
    parts += (parts.empty() ? "" : ", ") + part;
  }
  return "its " + (parts.empty() ? std::string("key") : parts) + " differ" + (parts.find(',') == std::string::npos ? "s" : "");
}

}  // namespace

std::shared_ptr<const FeatherMaterial> load_material(const fs::path& file) {
  auto material = std::make_shared<const FeatherMaterial>(read_feather_material(file));
  // A material characterised with warnings passes them on to what is made with it; a code that
  // says where it was raised (its cells, plumage/material_warnings.hpp) is passed on by the
  // render only when the scene's paths reach those directions (render_job.cpp), the others here.
  std::string first;
  for (const MaterialWarning& w : parse_material_warnings(material->warnings, material->grid)) {
    if (!w.directional() && first.empty()) first = w.code + ": " + w.summary;
  }
  if (!first.empty()) warn("material.warnings", file.string() + " was characterised with warnings (first: " + first + ")");
  return material;
}

MaterialStore::MaterialStore(const PluginRegistry& registry, MaterialStoreOptions options)
    : registry_(registry), options_(std::move(options)) {}

void MaterialStore::status(const std::string& line) const {
  if (options_.status) options_.status(line);
}

CharacterizeSettings MaterialStore::settings(const SpeciesConfig& config, const std::string& fidelity) const {
  return characterize_settings(config, registry_, fidelity, options_.overrides);
}

fs::path MaterialStore::canonical_path(const CharacterizeSettings& s) const {
  const std::string prefix = s.label.substr(0, s.label.find('/')) + "-" + s.variant;
  return options_.directory / (prefix + "-" + s.fidelity + "-" + s.key() + ".plm");
}

std::optional<ResolvedMaterial> MaterialStore::find(const CharacterizeSettings& s) const {
  const fs::path canonical = canonical_path(s);
  const std::string prefix = s.label.substr(0, s.label.find('/')) + "-" + s.variant;
  const std::string key = s.key();
  for (const auto& [file, header] : candidates(options_.directory, prefix, canonical)) {
    if (header.key != key) {
      if (header.label == s.label && header.fidelity == s.fidelity)
        status("material " + s.label + ": " + file.string() + " is stale (" + key_difference(s.key_text(), header.key_text) + ")");
      continue;
    }
    ResolvedMaterial r;
    try {
      r.material = load_material(file);  // its tables and checksum, read only now
    } catch (const Error& e) {
      status("material " + s.label + ": skipping a damaged file (" + e.what() + ")");
      continue;
    }
    r.file = file;
    r.fidelity = s.fidelity;
    status("material " + s.label + ": " + file.string());
    return r;
  }
  return std::nullopt;
}

ResolvedMaterial MaterialStore::resolve(const MaterialRequest& q) const {
  if (!q.file.empty()) {
    ResolvedMaterial r;
    r.file = q.file;
    r.material = load_material(q.file);
    r.fidelity = r.material->fidelity;
    return r;
  }
  const SpeciesConfig config = load_species_config(q.species_config, registry_, q.variant);
  const CharacterizeSettings wanted = settings(config, q.fidelity);
  // A production material serves a preview request, before a preview one (it is better: once
  // `make materials` has run, the scenes asking for preview use its materials); a preview one
  // serves a production request only as a fallback, said in a warning every image made with it carries.
  if (q.fidelity == "preview") {
    if (auto hit = find(settings(config, "production"))) return *hit;
  }
  if (auto hit = find(wanted)) return *hit;
  const CharacterizeSettings preview = q.fidelity == "preview" ? wanted : settings(config, "preview");
  if (q.fidelity != "preview") {
    warn("material.fidelity_fallback",
         "no " + q.fidelity + " material for " + wanted.label + " in " + options_.directory.string() +
             " (make one with `plumage characterize " + q.species_config.string() + " --variant " + config.variant +
             " --fidelity " + q.fidelity + " --out " + canonical_path(wanted).string() + "`); using preview fidelity");
    if (auto hit = find(preview)) return *hit;
  }
  const fs::path out = canonical_path(preview);
  if (!options_.allow_characterize) {
    throw ConfigError(q.where, "", "no cached material for " + wanted.label + " (" + q.fidelity + ") in " +
                                       options_.directory.string() + "; make it with `plumage characterize " +
                                       q.species_config.string() + " --variant " + config.variant +
                                       " --fidelity preview --out " + out.string() + "`");
  }
  return characterise(config, preview, out);
}

ResolvedMaterial MaterialStore::make(const SpeciesConfig& config, const std::string& fidelity) const {
  const CharacterizeSettings s = settings(config, fidelity);
  if (auto hit = find(s)) return *hit;
  // The canonical name holds the key, so a rerun of the same settings finds its journal there.
  return characterise(config, s, canonical_path(s));
}

ResolvedMaterial MaterialStore::characterise(const SpeciesConfig& config, const CharacterizeSettings& s,
                                             const fs::path& out) const {
  create_output_directory(options_.directory);
  CharacterizeOptions o;
  o.preparation = options_.preparation;
  o.distribution = CharacterizeOptions::Distribution::single_process;
  o.other_journal = CharacterizeOptions::OtherJournal::restart;
  o.progress = options_.progress;
  ResolvedMaterial r;
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
  line << "material " << s.label << ": characterised at " << s.fidelity << " fidelity in " << std::fixed
       << std::setprecision(1) << r.characterise_wall_s << " s wall, " << r.characterise_cpu_s << " s CPU -> " << out.string();
  status(line.str());
  r.file = out;
  r.fidelity = s.fidelity;
  r.characterised = true;
  r.material = load_material(out);
  return r;
}

}  // namespace plumage
