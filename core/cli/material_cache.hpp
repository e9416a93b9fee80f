// Feather materials of a scene (`plumage render`): a cached .plm keyed by the species config's
// content hash, the variant and the fidelity, else characterised in-process at preview fidelity
// (characterize_run.hpp) and cached for the next render.
//
// Cache: <dir>/<species>-<variant>-<fidelity>-<config hash>.plm (default dir build/materials,
// relative to the working directory like build/cache/tables). Files of other names in that
// folder whose header matches (label species/variant, config hash, fidelity) are used too, e.g.
// a production material written there by `plumage characterize --out`. A preview request is
// served by a matching production material if no preview one exists.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "app_context.hpp"
#include "plumage/feather_bsdf.hpp"
#include "plumage/scene_config.hpp"

namespace plumage::cli {

struct ResolvedFeather {
  std::shared_ptr<const FeatherBsdf> bsdf;
  std::filesystem::path file;
  bool characterised = false;  // made by this call
  double characterise_cpu_s = 0, characterise_wall_s = 0;
};

// `allow_characterize` false: a missing material is an error naming the command that makes it.
ResolvedFeather resolve_feather_material(const FeatherMaterialRequest& request, AppContext& context,
                                         const std::filesystem::path& cache_dir, bool allow_characterize, bool quiet);

}  // namespace plumage::cli
