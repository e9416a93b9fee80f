// The material store: feather materials of species variants, found in a folder of cached .plm
// files, else characterised (characterize.hpp) at preview fidelity and cached for the next use.
//
// Cache: <dir>/<species>-<variant>-<fidelity>-<config hash>.plm (default dir build/materials,
// relative to the working directory like build/cache/tables). Files of other names in that
// folder whose header matches (label species/variant, config hash, fidelity) are used too, e.g.
// a production material written there by `plumage characterize --out`. A preview request is
// served by a matching production material if no preview one exists.
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
  bool characterised = false;  // made by this call
  double characterise_wall_s = 0, characterise_cpu_s = 0;
};

struct MaterialStoreOptions {
  std::filesystem::path directory = "build/materials";
  // false: a missing material is an error naming the command that makes it.
  bool allow_characterize = true;
  PreparationOptions preparation;  // for characterising a missing material
  // One line per event (hit, fallback, characterisation); may be empty.
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

  const MaterialStoreOptions& options() const { return options_; }

 private:
  const PluginRegistry& registry_;
  MaterialStoreOptions options_;
};

// Reads a material file; its characterisation warnings are raised as `material.warnings`.
std::shared_ptr<const FeatherMaterial> load_material(const std::filesystem::path& file);

}  // namespace plumage
