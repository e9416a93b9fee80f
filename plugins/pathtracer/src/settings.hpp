// The path tracer's own settings (issue 22: a plug-in owns its options): read from the scene's
// `renderer:` section (`renderer: {type: pathtracer, spp: 64, lod: mean}`) through one parameter
// table, which also documents them (`plumage plugins describe pathtracer`, docs/parameters.md).
// `plumage render --spp/--seed/--lod/--threads` set the same keys of that section.
#pragma once

#include <cstdint>
#include <string>

#include "plumage/param_table.hpp"

namespace plumage::pathtracer {

enum class LevelOfDetail {
  automatic,  // mean BRDF where a pixel footprint covers >= Settings::lod_barbules barbules
  mean,       // the mean BRDF everywhere
  instance,   // BRDF instances everywhere
};

struct Settings {
  int samples_per_pixel = 16;
  std::uint64_t seed = 1;  // every random draw derives from (seed, pixel, sample)
  int max_depth = 8;       // path vertices after the camera
  LevelOfDetail lod = LevelOfDetail::automatic;
  double lod_barbules = 2.0;
  double lambda_min_nm = 400.0, lambda_max_nm = 700.0;
  int spectral_bins = 0;  // > 0: also accumulate this many equal spectral radiance channels
  int tile_size = 16;
  int threads = 0;  // 0: all hardware threads (oneTBB default)
};

// The declarations of the `renderer: {type: pathtracer, ...}` keys.
const ParamTable<Settings>& settings_table();

// "16 spp, lod auto, seed 1": the settings a log line names.
std::string describe(const Settings& settings);

}  // namespace plumage::pathtracer
