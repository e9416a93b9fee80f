// The material store: feather materials of species variants, found by their key in a folder of
// cached .plm files, else characterised (characterize.hpp) at preview fidelity and cached for the
// next use.
//
// A material's key (CharacterizeSettings::key, characterize_settings.hpp) covers everything its
// numbers depend on: the merged species variant as canonical text (comments and layout do not
// matter), every file the variant names (a crystal config...), the plug-in types and versions
// that model it, the fit revision and the fidelity settings. It is stored in the .plm header, and
// a lookup reads headers only: a material made from other inputs (a crystal edited, a newer
// fitter) is stale and not used; one made before keys existed (.plm version < 3) neither.
//
// Folder: <dir>/<species>-<variant>-<fidelity>-<key>.plm (default dir build/materials, relative
// to the working directory like build/cache/tables). Files of other names starting with
// <species>-<variant> whose header key matches are used too, e.g. a production material written
// there by `plumage characterize --out`. A preview request is served by a production material
// when one exists, else by a preview one (so after `make materials` the scenes that ask for
// preview render with production materials); a production request that finds none is served at preview fidelity
// with the warning `material.fidelity_fallback` (plumage/diagnostics.hpp), so every file made
// with it (an image's plumage:warnings) says so.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "plumage/characterize_settings.hpp"
#include "plumage/error.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage {

struct MaterialRequest {
  std::filesystem::path file;            // an explicit .plm (then nothing else is used)
  std::filesystem::path species_config;  // else a species variant at a fidelity
  std::string variant;                   // empty: the species file's default variant
  std::string fidelity = "preview";      // preview | production
  SourceMark where;                      // who asked, for messages
};

struct ResolvedMaterial {
  std::shared_ptr<const FeatherMaterial> material;
  std::filesystem::path file;
  std::string fidelity;        // of the material served
  bool characterised = false;  // made by this call
  double characterise_wall_s = 0, characterise_cpu_s = 0;
};

struct MaterialStoreOptions {
  std::filesystem::path directory = "build/materials";
  // false: a missing material is an error naming the command that makes it.
  bool allow_characterize = true;
  // Applied to every characterisation and key of the store (e.g. a small grid for tests).
  CharacterizeOverrides overrides = characterize_overrides_table().defaults();
  PreparationOptions preparation;  // for characterising a missing material
  // One line per event (hit, stale file, characterisation); may be empty.
  std::function<void(std::string_view)> status;
  // Progress of a characterisation (characterize.hpp); may be empty.
  std::function<void(std::size_t, std::size_t, std::string_view)> progress;
};

class MaterialStore {
 public:
  MaterialStore(const PluginRegistry& registry, MaterialStoreOptions options);

  // The material of a request: the explicit file, else a cached one, else characterised (when
  // allowed; a ConfigError naming the command otherwise). A material characterised with warnings
  // raises `material.warnings` (plumage/diagnostics.hpp) so they reach what is made with it.
  ResolvedMaterial resolve(const MaterialRequest& request) const;

  // The settings (and so the key) of a variant at a fidelity, with the store's overrides.
  CharacterizeSettings settings(const SpeciesConfig& config, const std::string& fidelity) const;
  // The cached material of exactly these settings (headers compared, then the hit read whole).
  std::optional<ResolvedMaterial> find(const CharacterizeSettings& s) const;
  // Where a material of these settings is cached.
  std::filesystem::path canonical_path(const CharacterizeSettings& s) const;
  // The material of a variant at exactly `fidelity` (no fallback to another fidelity): the cached
  // one when its key is current, else characterised into canonical_path, resuming from that
  // file's journal when an earlier run of the same settings was interrupted (`make materials`).
  ResolvedMaterial make(const SpeciesConfig& config, const std::string& fidelity) const;

  const MaterialStoreOptions& options() const { return options_; }

 private:
  ResolvedMaterial characterise(const SpeciesConfig& config, const CharacterizeSettings& s,
                                const std::filesystem::path& out) const;
  void status(const std::string& line) const;

  const PluginRegistry& registry_;
  MaterialStoreOptions options_;
};

// Reads a material file; its characterisation warnings are raised as `material.warnings`.
std::shared_ptr<const FeatherMaterial> load_material(const std::filesystem::path& file);

}  // namespace plumage
