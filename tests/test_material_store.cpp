// Complete material keys and the material store (plumage/material_store.hpp, issue 22): a key
// covers the merged variant (not its comments), the files it names (a crystal config), the
// models' plug-in versions, the fit revision and the settings; the store reuses a material after
// a comment edit, characterises again after a value edit, refuses journals of another fit
// revision, skips a damaged file and says a fidelity fallback in a warning.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

#include "plumage/characterize.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/fitter.hpp"
#include "plumage/material_store.hpp"
#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::registry;

const fs::path kConfigs = fs::path(PLUMAGE_SOURCE_DIR) / "configs";

std::string text_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

void replace_once(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = text_of(file);
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  write_text(file, text.replace(at, from.size(), to));
}

// A fresh copy of configs/species/<species>.yaml (and, for crystal species, configs/crystals)
// in a scratch tree with the same layout.
fs::path scratch_species(const std::string& name, const std::string& species) {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-material-store" / name;
  fs::remove_all(dir);
  fs::create_directories(dir / "species");
  fs::copy_file(kConfigs / "species" / (species + ".yaml"), dir / "species" / (species + ".yaml"));
  fs::copy(kConfigs / "crystals", dir / "crystals");
  return dir / "species" / (species + ".yaml");
}

std::string preview_key(const fs::path& species, const std::string& variant = "") {
  const SpeciesConfig config = load_species_config(species, registry(), variant);
  return characterize_settings(config, registry(), "preview").key();
}

// Tiny settings for characterisations that take a second.
CharacterizeOverrides tiny() {
  CharacterizeOverrides o = characterize_overrides_table().defaults();
  o.instances = 2;
  o.grid = 2;
  o.lambda_nm = {500};
  o.noise_functions = 4;
  return o;
}

MaterialStore tiny_store(const fs::path& dir, std::vector<std::string>* status = nullptr) {
  MaterialStoreOptions options;
  options.directory = dir;
  options.overrides = tiny();
  if (status) options.status = [status](std::string_view line) { status->emplace_back(line); };
  return MaterialStore(registry(), options);
}

bool mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (const auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("material key: comments do not matter, values and named files do", "[material-store]") {
  const fs::path rockdove = scratch_species("key-rockdove", "rockdove");
  const std::string key = preview_key(rockdove);
  CHECK(key.size() == 16);
  // A comment, and another variant's values: the same key (the file's bytes hash changes).
  const std::string hash = load_species_config(rockdove, registry()).content_hash;
  replace_once(rockdove, "# Rock dove", "# The rock dove");
  replace_once(rockdove, "structure: {cortex_nm: 582}", "structure: {cortex_nm: 583}");  // jade
  CHECK(load_species_config(rockdove, registry()).content_hash != hash);
  CHECK(preview_key(rockdove) == key);
  CHECK(preview_key(rockdove, "jade") != preview_key(scratch_species("key-rockdove-2", "rockdove"), "jade"));
  // A value of this variant: another key.
  replace_once(rockdove, "structure: {cortex_nm: 595}", "structure: {cortex_nm: 596}");
  CHECK(preview_key(rockdove) != key);

  // Mallard: its crystal config enters by content; its comments do not.
  const fs::path mallard = scratch_species("key-mallard", "mallard");
  const fs::path crystal = mallard.parent_path().parent_path() / "crystals" / "mallard-green.yaml";
  const SpeciesConfig config = load_species_config(mallard, registry());
  const CharacterizeSettings s = characterize_settings(config, registry(), "preview");
  CHECK(s.key_text().find("\nfile structure.crystal ") != std::string::npos);
  CHECK(s.key_text().find("\nfile reflection.crystal ") != std::string::npos);
  CHECK(s.key_text().find("\nmodel local_reflection photonic_crystal ") != std::string::npos);
  CHECK(s.key_text().find("\nmodel scattering_solver approximate ") != std::string::npos);
  CHECK(s.key_text().find("\nfit_revision " + std::to_string(kFitRevision) + "\n") != std::string::npos);
  replace_once(crystal, "# 1D effective-medium estimate", "# estimate (1D effective medium)");
  CHECK(preview_key(mallard) == s.key());
  replace_once(crystal, "rod_diameter_nm: 152", "rod_diameter_nm: 150");
  CHECK(preview_key(mallard) != s.key());
  // Settings enter too.
  CharacterizeOverrides other = tiny();
  CHECK(characterize_settings(config, registry(), "preview", other).key() != s.key());
  CHECK(characterize_settings(config, registry(), "production").key() != s.key());
}

TEST_CASE("material store: reuses after a comment edit, characterises again after a value edit", "[material-store]") {
  const fs::path rockdove = scratch_species("store-edit", "rockdove");
  const fs::path dir = rockdove.parent_path().parent_path() / "materials";
  std::vector<std::string> status;
  const MaterialStore store = tiny_store(dir, &status);
  const MaterialRequest request{{}, rockdove, "", "preview", {}};
  const ResolvedMaterial made = store.resolve(request);
  CHECK(made.characterised);
  CHECK(made.fidelity == "preview");
  CHECK(made.file.filename().string().rfind("rockdove-forest-preview-", 0) == 0);
  CHECK(made.material->key == store.settings(load_species_config(rockdove, registry()), "preview").key());
  CHECK(read_feather_material_header(made.file).key_text == made.material->key_text);
  CHECK(!fs::exists(fs::path(made.file).concat(".journal")));

  const ResolvedMaterial again = store.resolve(request);
  CHECK_FALSE(again.characterised);
  CHECK(again.file == made.file);
  // A comment edit: the same material.
  replace_once(rockdove, "# Rock dove", "# The rock dove");
  const ResolvedMaterial commented = store.resolve(request);
  CHECK_FALSE(commented.characterised);
  CHECK(commented.file == made.file);
  // A value edit: the old file is stale (and says why), a new one is made beside it.
  replace_once(rockdove, "structure: {cortex_nm: 595}", "structure: {cortex_nm: 596}");
  status.clear();
  const ResolvedMaterial edited = store.resolve(request);
  CHECK(edited.characterised);
  CHECK(edited.file != made.file);
  CHECK(fs::exists(made.file));
  CHECK(mentions(status, made.file.string() + " is stale (its species differs)"));
  // Without characterising, a miss names the command that makes the material.
  replace_once(rockdove, "structure: {cortex_nm: 596}", "structure: {cortex_nm: 597}");
  MaterialStoreOptions strict = store.options();
  strict.allow_characterize = false;
  CHECK_THROWS_WITH(MaterialStore(registry(), strict).resolve(request),
                    Catch::Contains("no cached material for rockdove/forest (preview)") && Catch::Contains("plumage characterize"));
}

TEST_CASE("material store: a damaged hit is skipped, a fallback is a warning", "[material-store]") {
  const fs::path rockdove = scratch_species("store-damaged", "rockdove");
  const fs::path dir = rockdove.parent_path().parent_path() / "materials";
  std::vector<std::string> status;
  const MaterialStore store = tiny_store(dir, &status);
  const MaterialRequest request{{}, rockdove, "", "preview", {}};
  const ResolvedMaterial made = store.resolve(request);
  // Damage the tables, not the header: the lookup (headers only) still matches; loading it fails
  // its checksum, so it is skipped and made again.
  {
    std::fstream f(made.file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(made.file) - 40));
    f.put('\x7f');
  }
  CHECK(read_feather_material_header(made.file).key == made.material->key);
  status.clear();
  const ResolvedMaterial remade = store.resolve(request);
  CHECK(remade.characterised);
  CHECK(mentions(status, "skipping a damaged file"));
  CHECK(read_feather_material(remade.file).key == made.material->key);

  // No production material: the preview one serves, and the warning says so.
  CapturedWarnings warnings;
  const ResolvedMaterial fallback = store.resolve({{}, rockdove, "", "production", {}});
  CHECK_FALSE(fallback.characterised);
  CHECK(fallback.fidelity == "preview");
  CHECK(warnings.count("material.fidelity_fallback") == 1);
  CHECK(warnings.message("material.fidelity_fallback").find("no production material for rockdove/forest") != std::string::npos);
  // A preview request does not warn.
  CapturedWarnings quiet;
  store.resolve(request);
  CHECK(quiet.count("material.fidelity_fallback") == 0);
}

TEST_CASE("material store: make() at one fidelity; a production material serves preview first", "[material-store]") {
  const fs::path rockdove = scratch_species("store-make", "rockdove");
  const fs::path dir = rockdove.parent_path().parent_path() / "materials";
  const MaterialStore store = tiny_store(dir);
  const SpeciesConfig config = load_species_config(rockdove, registry());
  const MaterialRequest request{{}, rockdove, "", "preview", {}};
  const ResolvedMaterial preview = store.resolve(request);
  REQUIRE(preview.characterised);
  // make() does not take the preview material for production: it characterises, under the
  // canonical name, and skips it the next time.
  const ResolvedMaterial made = store.make(config, "production");
  CHECK(made.characterised);
  CHECK(made.fidelity == "production");
  CHECK(made.file == store.canonical_path(store.settings(config, "production")));
  CHECK(made.material->key == store.settings(config, "production").key());
  const ResolvedMaterial again = store.make(config, "production");
  CHECK_FALSE(again.characterised);
  CHECK(again.file == made.file);
  // With both in the folder, a preview request (the scenes') gets the production one.
  const ResolvedMaterial served = store.resolve(request);
  CHECK_FALSE(served.characterised);
  CHECK(served.fidelity == "production");
  CHECK(served.file == made.file);
  // And make() at preview finds the preview one, not the production one.
  const ResolvedMaterial own = store.make(config, "preview");
  CHECK_FALSE(own.characterised);
  CHECK(own.file == preview.file);
}

TEST_CASE("journals and shards of another fit revision are refused", "[material-store][characterize]") {
  const fs::path rockdove = scratch_species("fit-revision", "rockdove");
  const fs::path dir = rockdove.parent_path();
  const SpeciesConfig config = load_species_config(rockdove, registry());
  const CharacterizeSettings s = characterize_settings(config, registry(), "preview", tiny());
  CharacterizeOptions options;
  options.distribution = CharacterizeOptions::Distribution::single_process;
  options.shard = CharacterizeShard{0, 1};
  const fs::path shard = dir / "all.shard";
  characterize(config, s, shard, options);
  CHECK_NOTHROW(merge_shards({shard}, dir / "merged.plm"));

  // The same records as written by a build of another fit revision.
  const std::string current = "fit_revision=" + std::to_string(kFitRevision) + " ";
  const std::string older = "fit_revision=" + std::to_string(kFitRevision - 1) + " ";
  std::string bytes = text_of(shard);
  REQUIRE(bytes.find(current) != std::string::npos);
  bytes.replace(bytes.find(current), current.size(), older);
  const fs::path old_shard = dir / "old.shard";
  write_text(old_shard, bytes);
  CHECK_THROWS_WITH(merge_shards({old_shard}, dir / "old.plm"), Catch::Contains("fit revision"));
  CHECK_FALSE(fs::exists(dir / "old.plm"));

  // As a journal beside the output: refused (the command), or started over (a cache).
  const fs::path out = dir / "resumed.plm";
  write_text(fs::path(out).concat(".journal"), bytes);
  CharacterizeOptions run;
  run.distribution = CharacterizeOptions::Distribution::single_process;
  CHECK_THROWS_WITH(characterize(config, s, out, run), Catch::Contains("journal of a run with other settings"));
  CHECK_FALSE(fs::exists(out));
  run.other_journal = CharacterizeOptions::OtherJournal::restart;
  const CharacterizeResult r = characterize(config, s, out, run);
  CHECK(r.plan.resumed == 0);
  CHECK(r.plan.todo == s.group_count());
  CHECK(text_of(out) == text_of(dir / "merged.plm"));
}

TEST_CASE("noise-pool seed: comments do not change it, the variant's values do", "[material-store][characterize]") {
  // The seed derives from the comment-independent identity of the variant (config_digest,
  // material_key.hpp), so two species files that differ only in comments give the same noise
  // pool (bit for bit) although the bytes of the files, and so their config hashes, differ.
  const fs::path plain = scratch_species("seed-plain", "rockdove");
  const fs::path commented = scratch_species("seed-commented", "rockdove");
  const fs::path edited = scratch_species("seed-edited", "rockdove");
  replace_once(commented, "# Rock dove", "# The rock dove, with another comment\n# and one more line");
  replace_once(edited, "structure: {cortex_nm: 595}", "structure: {cortex_nm: 596}");
  CharacterizeOptions run;
  run.distribution = CharacterizeOptions::Distribution::single_process;
  auto make = [&](const fs::path& species) {
    const SpeciesConfig config = load_species_config(species, registry());
    const CharacterizeSettings s = characterize_settings(config, registry(), "preview", tiny());
    const fs::path out = species.parent_path() / "seed.plm";
    characterize(config, s, out, run);
    return read_feather_material(out);
  };
  const FeatherMaterial a = make(plain), b = make(commented), c = make(edited);
  CHECK(a.config_hash != b.config_hash);
  CHECK(a.key == b.key);
  REQUIRE(a.noise.functions.size() == b.noise.functions.size());
  CHECK(a.noise.lag1 == b.noise.lag1);
  CHECK(a.noise.functions == b.noise.functions);
  CHECK(a.nodes.size() == b.nodes.size());
  // Another value of the variant: another key and another pool.
  CHECK(c.key != a.key);
  REQUIRE(c.noise.functions.size() == a.noise.functions.size());
  CHECK(c.noise.functions != a.noise.functions);
}
